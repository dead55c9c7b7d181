#include "trac0r/gltf_json.h"

#include "trac0r/input_checks.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace trac0r {

std::string gltf_json_text(const std::string& text, bool glb) {
    if (!glb) {
        return text;
    }
    // 12 bytes of header (magic, version, length), then the JSON chunk:
    // its length, its type "JSON", its bytes.
    if (text.size() < 20 || text.compare(0, 4, "glTF") != 0 || text.compare(16, 4, "JSON") != 0) {
        return "";
    }
    std::uint32_t length = 0;
    std::memcpy(&length, text.data() + 12, sizeof length);
    if (length > text.size() - 20) {
        return "";
    }
    return text.substr(20, length);
}

std::vector<float> gltf_emissive_strengths(const std::string& json_text, const std::string& path) {
    const nlohmann::json doc = nlohmann::json::parse(json_text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) {
        return {};
    }
    const auto materials = doc.find("materials");
    if (materials == doc.end() || !materials->is_array()) {
        return {};
    }
    std::vector<float> strengths;
    for (const nlohmann::json& m : *materials) {
        float strength = 1.0f;
        if (m.is_object() && m.contains("extensions") && m["extensions"].is_object() &&
            m["extensions"].contains("KHR_materials_emissive_strength")) {
            const nlohmann::json& ext = m["extensions"]["KHR_materials_emissive_strength"];
            if (ext.is_object() && ext.contains("emissiveStrength")) {
                const nlohmann::json& value = ext["emissiveStrength"];
                const double v = value.is_number() ? value.get<double>() : -1.0;
                if (!(v >= 0.0 && v <= 1e30)) {
                    const std::string name = m.contains("name") && m["name"].is_string()
                                                 ? m["name"].get<std::string>()
                                                 : "#" + std::to_string(strengths.size());
                    throw std::runtime_error(
                        path + ": material '" + printable(name, 60) +
                        "': KHR_materials_emissive_strength: emissiveStrength " +
                        printable(value.dump(), 40) + ": expected a number >= 0");
                }
                strength = static_cast<float>(v);
            }
        }
        strengths.push_back(strength);
    }
    return strengths;
}

}  // namespace trac0r
