#include "trac0r/gltf_size.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <vector>

namespace trac0r {

namespace {

using nlohmann::json;

// An accessor's count, or 0.
std::uint64_t accessor_count(const json& doc, const json& index) {
    if (!index.is_number_unsigned() || !doc.contains("accessors") || !doc["accessors"].is_array() ||
        index.get<std::size_t>() >= doc["accessors"].size()) {
        return 0;
    }
    const json& a = doc["accessors"][index.get<std::size_t>()];
    return a.is_object() && a.contains("count") && a["count"].is_number_unsigned()
               ? a["count"].get<std::uint64_t>()
               : 0;
}

// A mesh's triangles.
std::uint64_t mesh_triangles(const json& doc, const json& mesh) {
    std::uint64_t triangles = 0;
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) {
        return 0;
    }
    for (const json& p : mesh["primitives"]) {
        if (!p.is_object()) {
            continue;
        }
        const int mode =
            p.contains("mode") && p["mode"].is_number_integer() ? p["mode"].get<int>() : 4;
        std::uint64_t n = 0;
        if (p.contains("indices")) {
            n = accessor_count(doc, p["indices"]);
        } else if (p.contains("attributes") && p["attributes"].is_object() &&
                   p["attributes"].contains("POSITION")) {
            n = accessor_count(doc, p["attributes"]["POSITION"]);
        }
        if (mode == 4) {
            triangles += n / 3;
        } else if ((mode == 5 || mode == 6) && n >= 3) {
            triangles += n - 2;
        }
    }
    return triangles;
}

}  // namespace

std::uint64_t gltf_promised_triangles(const std::string& json_text) {
    const json doc = json::parse(json_text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("nodes") ||
        !doc["nodes"].is_array() || !doc.contains("meshes") || !doc["meshes"].is_array()) {
        return 0;
    }
    const json& nodes = doc["nodes"];
    const json& meshes = doc["meshes"];
    std::vector<std::uint64_t> per_mesh(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        per_mesh[m] = mesh_triangles(doc, meshes[m]);
    }
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
    }
    std::uint64_t total = 0;
    std::vector<bool> seen(nodes.size(), false);
    const std::function<void(std::size_t, int)> walk = [&](std::size_t i, int depth) {
        if (depth > 256 || seen[i] || !nodes[i].is_object()) {
            return;
        }
        seen[i] = true;
        const json& node = nodes[i];
        if (node.contains("mesh") && node["mesh"].is_number_unsigned() &&
            node["mesh"].get<std::size_t>() < per_mesh.size()) {
            total += per_mesh[node["mesh"].get<std::size_t>()];
        }
        if (node.contains("children") && node["children"].is_array()) {
            for (const json& c : node["children"]) {
                if (c.is_number_unsigned() && c.get<std::size_t>() < nodes.size()) {
                    walk(c.get<std::size_t>(), depth + 1);
                }
            }
        }
    };
    for (std::size_t r : roots) {
        walk(r, 0);
    }
    return total;
}

}  // namespace trac0r
