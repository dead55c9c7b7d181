#include "trac0r/gltf_size.h"

#include "trac0r/gltf_nodes.h"

#include <nlohmann/json.hpp>

#include <stdexcept>
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

std::uint64_t gltf_promised_triangles(const std::string& json_text, const std::string& path) {
    const json doc = json::parse(json_text, nullptr, false);
    // The nodes are walked even without meshes: the walk refuses nodes
    // nested too deep for the reader, which recurses through them all.
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("nodes") ||
        !doc["nodes"].is_array()) {
        return 0;
    }
    std::vector<std::uint64_t> per_mesh;
    if (doc.contains("meshes") && doc["meshes"].is_array()) {
        for (const json& mesh : doc["meshes"]) {
            per_mesh.push_back(mesh_triangles(doc, mesh));
        }
    }
    std::uint64_t total = 0;
    try {
        // A coincident copy counts once, as the reader draws it once.
        walk_gltf_mesh_placements(doc, path,
                                  [&](std::size_t, const json&, std::size_t mesh, long repeats) {
                                      if (repeats < 0 && mesh < per_mesh.size()) {
                                          total += per_mesh[mesh];
                                      }
                                  });
    } catch (const GltfNodesTooDeep&) {
        throw;
    } catch (const std::runtime_error&) {
        // A transform that is not finite: the reader refuses the file.
    }
    return total;
}

}  // namespace trac0r
