#include "trac0r/gltf_repeats.h"

#include "trac0r/gltf_json.h"
#include "trac0r/gltf_nodes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace trac0r {

const char* const gltf_repeat_defect = "a node repeats another node's mesh and transform";
const char* const gltf_repeat_done = "drawn once";

namespace {

using nlohmann::json;

// Whether `node` is a leaf placing a mesh: nothing but the mesh hangs on it.
bool mesh_leaf(const json& node) {
    const bool children =
        node.contains("children") && node["children"].is_array() && !node["children"].empty();
    return node.contains("mesh") && !children && !node.contains("skin") && !node.contains("camera");
}

// How many times each node is listed as a child or a scene's root.
std::vector<int> references(const json& doc) {
    std::vector<int> count(doc["nodes"].size(), 0);
    const auto add = [&](const json& list) {
        if (!list.is_array()) {
            return;
        }
        for (const json& n : list) {
            if (n.is_number_unsigned() && n.get<std::size_t>() < count.size()) {
                ++count[n.get<std::size_t>()];
            }
        }
    };
    for (const json& node : doc["nodes"]) {
        if (node.is_object() && node.contains("children")) {
            add(node["children"]);
        }
    }
    for (const json& scene : doc["scenes"]) {
        if (scene.is_object() && scene.contains("nodes")) {
            add(scene["nodes"]);
        }
    }
    return count;
}

// `list` (an array of node indices) without those marked in `out`.
void drop_marked(json& list, const std::vector<bool>& out) {
    if (!list.is_array()) {
        return;
    }
    json kept = json::array();
    for (const json& n : list) {
        if (!(n.is_number_unsigned() && n.get<std::size_t>() < out.size() &&
              out[n.get<std::size_t>()])) {
            kept.push_back(n);
        }
    }
    list = std::move(kept);
}

// A .glb of `glb`'s header and binary chunk around the JSON chunk `json`
// (glTF 2.0, 4.4: chunks 4-byte aligned, JSON padded with spaces).
std::string glb_with_json(const std::string& glb, std::string json_text) {
    std::uint32_t old_length = 0;
    std::memcpy(&old_length, glb.data() + 12, sizeof old_length);
    // The binary chunk starts after the old JSON chunk's padding.
    const std::size_t rest = 20 + ((static_cast<std::size_t>(old_length) + 3) & ~std::size_t(3));
    json_text.append((4 - json_text.size() % 4) % 4, ' ');
    const std::uint32_t length = static_cast<std::uint32_t>(json_text.size());
    const std::uint32_t total =
        static_cast<std::uint32_t>(20 + json_text.size() + glb.size() - std::min(rest, glb.size()));
    std::string out = glb.substr(0, 8);
    out.append(reinterpret_cast<const char*>(&total), 4);
    out.append(reinterpret_cast<const char*>(&length), 4);
    out += "JSON";
    out += json_text;
    if (rest < glb.size()) {
        out.append(glb, rest, std::string::npos);
    }
    return out;
}

}  // namespace

std::string gltf_without_repeated_leaves(const std::string& text, bool glb, const std::string& path,
                                         std::size_t* removed, std::string* first) {
    *removed = 0;
    first->clear();
    json doc = json::parse(gltf_json_text(text, glb), nullptr, false);
    // Without scenes every node is a root, which no list can take out.
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("nodes") ||
        !doc["nodes"].is_array() || !doc.contains("scenes") || !doc["scenes"].is_array() ||
        doc["scenes"].empty()) {
        return "";
    }
    // A node listed twice (against the format, but read) is placed twice,
    // once where the walk meets it: never left out.
    const std::vector<int> listed = references(doc);
    std::vector<bool> out(doc["nodes"].size(), false);
    try {
        walk_gltf_mesh_placements(
            doc, path, [&](std::size_t index, const json& node, std::size_t, long repeats) {
                if (repeats >= 0 && mesh_leaf(node) && listed[index] == 1) {
                    out[index] = true;
                    if (++*removed == 1) {
                        *first = "node " + std::to_string(index) + " repeats node " +
                                 std::to_string(repeats) + "'s mesh and transform";
                    }
                }
            });
    } catch (const std::runtime_error&) {
        *removed = 0;  // a transform that is not finite: the reader says so
        first->clear();
        return "";
    }
    if (*removed == 0) {
        return "";
    }
    for (json& node : doc["nodes"]) {
        if (node.is_object() && node.contains("children")) {
            drop_marked(node["children"], out);
        }
    }
    for (json& scene : doc["scenes"]) {
        if (scene.is_object() && scene.contains("nodes")) {
            drop_marked(scene["nodes"], out);
        }
    }
    const std::string json_text = doc.dump(-1, ' ', false, json::error_handler_t::replace);
    return glb ? glb_with_json(text, json_text) : json_text;
}

}  // namespace trac0r
