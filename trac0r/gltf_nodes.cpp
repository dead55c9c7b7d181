#include "trac0r/gltf_nodes.h"

#include "trac0r/input_checks.h"

#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>

namespace trac0r {

namespace {

using nlohmann::json;

// A node's own transform: its matrix, else T R S.
glm::dmat4 local_transform(const json& node, const std::string& what) {
    if (node.contains("matrix")) {
        const std::vector<double> m = gltf_numbers(node["matrix"], 16, what + ": matrix");
        glm::dmat4 out;
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                out[c][r] = m[static_cast<std::size_t>(4 * c + r)];  // column-major
            }
        }
        return out;
    }
    glm::dmat4 out(1.0);
    if (node.contains("translation")) {
        const std::vector<double> t = gltf_numbers(node["translation"], 3, what + ": translation");
        out[3] = glm::dvec4(t[0], t[1], t[2], 1.0);
    }
    if (node.contains("rotation")) {
        const std::vector<double> q = gltf_numbers(node["rotation"], 4, what + ": rotation");
        out = out * glm::mat4_cast(glm::dquat(q[3], q[0], q[1], q[2]));
    }
    if (node.contains("scale")) {
        const std::vector<double> s = gltf_numbers(node["scale"], 3, what + ": scale");
        out = out * glm::dmat4(glm::dvec4(s[0], 0, 0, 0), glm::dvec4(0, s[1], 0, 0),
                               glm::dvec4(0, 0, s[2], 0), glm::dvec4(0, 0, 0, 1));
    }
    return out;
}

}  // namespace

// The numbers of `value` (n of them, finite), or throws naming `what`.
std::vector<double> gltf_numbers(const nlohmann::json& value, std::size_t n,
                                 const std::string& what) {
    if (!value.is_array() || value.size() != n) {
        throw std::runtime_error(what + ": expected " + std::to_string(n) + " numbers, got " +
                                 printable(value.dump(), 60));
    }
    std::vector<double> out;
    for (const nlohmann::json& v : value) {
        if (!v.is_number() || !std::isfinite(v.get<double>())) {
            throw std::runtime_error(what + ": expected finite numbers, got " +
                                     printable(value.dump(), 60));
        }
        out.push_back(v.get<double>());
    }
    return out;
}

void walk_gltf_nodes(
    const nlohmann::json& doc, const std::string& path,
    const std::function<void(std::size_t, const nlohmann::json&, const glm::dmat4&)>& visit) {
    if (!doc.is_object() || !doc.contains("nodes") || !doc["nodes"].is_array()) {
        return;
    }
    const json& nodes = doc["nodes"];
    std::vector<std::size_t> roots;
    if (doc.contains("scenes") && doc["scenes"].is_array() && !doc["scenes"].empty()) {
        std::size_t scene = 0;
        if (doc.contains("scene") && doc["scene"].is_number_unsigned() &&
            doc["scene"].get<std::size_t>() < doc["scenes"].size()) {
            scene = doc["scene"].get<std::size_t>();
        }
        const json& s = doc["scenes"][scene];
        if (s.is_object() && s.contains("nodes") && s["nodes"].is_array()) {
            for (const json& n : s["nodes"]) {
                if (n.is_number_unsigned() && n.get<std::size_t>() < nodes.size()) {
                    roots.push_back(n.get<std::size_t>());
                }
            }
        }
    } else {
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            roots.push_back(i);
        }
    }
    std::vector<bool> seen(nodes.size(), false);
    const std::function<void(std::size_t, const glm::dmat4&, int)> walk =
        [&](std::size_t index, const glm::dmat4& parent, int depth) {
            if (depth > max_gltf_node_depth) {
                throw GltfNodesTooDeep(path + ": cannot read mesh: its nodes nest deeper than " +
                                       std::to_string(max_gltf_node_depth));
            }
            if (seen[index] || !nodes[index].is_object()) {
                return;
            }
            seen[index] = true;
            const json& node = nodes[index];
            const glm::dmat4 world =
                parent * local_transform(node, path + ": node " + std::to_string(index));
            visit(index, node, world);
            if (node.contains("children") && node["children"].is_array()) {
                for (const json& c : node["children"]) {
                    if (c.is_number_unsigned() && c.get<std::size_t>() < nodes.size()) {
                        walk(c.get<std::size_t>(), world, depth + 1);
                    }
                }
            }
        };
    for (std::size_t r : roots) {
        walk(r, glm::dmat4(1.0), 0);
    }
}

void walk_gltf_mesh_placements(
    const json& doc, const std::string& path,
    const std::function<void(std::size_t, const json&, std::size_t, long)>& visit) {
    // Each (mesh, world transform) met, with the node that placed it.
    std::map<std::pair<std::size_t, std::array<double, 16>>, std::size_t> placed;
    walk_gltf_nodes(doc, path, [&](std::size_t index, const json& node, const glm::dmat4& world) {
        if (!node.contains("mesh") || !node["mesh"].is_number_unsigned()) {
            return;
        }
        const std::size_t mesh = node["mesh"].get<std::size_t>();
        std::array<double, 16> m;
        std::memcpy(m.data(), &world, sizeof m);
        const auto first = placed.emplace(std::make_pair(mesh, m), index);
        visit(index, node, mesh, first.second ? -1L : static_cast<long>(first.first->second));
    });
}

}  // namespace trac0r
