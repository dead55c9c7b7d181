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

namespace {

// A material's name for messages: its "name", else "#index".
std::string material_name(const nlohmann::json& m, std::size_t index) {
    return m.contains("name") && m["name"].is_string() ? m["name"].get<std::string>()
                                                       : "#" + std::to_string(index);
}

// The number at `key` of `object` (`fallback` where it has none); throws
// naming `where` where it is no finite number.
double number_at(const nlohmann::json& object, const char* key, double fallback,
                 const std::string& where) {
    if (!object.contains(key)) {
        return fallback;
    }
    const nlohmann::json& v = object[key];
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
        throw std::runtime_error(where + key + " " + printable(v.dump(), 40) +
                                 ": expected a finite number");
    }
    return v.get<double>();
}

// KHR_texture_transform of a textureInfo, as its affine map; false where
// it has none.
bool texture_transform(const nlohmann::json& info, std::vector<double>* m,
                       const std::string& where) {
    if (!info.is_object() || !info.contains("extensions") || !info["extensions"].is_object() ||
        !info["extensions"].contains("KHR_texture_transform")) {
        return false;
    }
    const nlohmann::json& t = info["extensions"]["KHR_texture_transform"];
    if (!t.is_object()) {
        return false;  // assimp refuses it first
    }
    const std::string at = where + "KHR_texture_transform: ";
    const auto pair_at = [&](const char* key, double fallback, double* out) {
        out[0] = fallback;
        out[1] = fallback;
        if (!t.contains(key)) {
            return;
        }
        const nlohmann::json& v = t[key];
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() ||
            !std::isfinite(v[0].get<double>()) || !std::isfinite(v[1].get<double>())) {
            throw std::runtime_error(at + key + " " + printable(v.dump(), 40) +
                                     ": expected two finite numbers");
        }
        out[0] = v[0].get<double>();
        out[1] = v[1].get<double>();
    };
    double offset[2];
    double scale[2];
    pair_at("offset", 0.0, offset);
    pair_at("scale", 1.0, scale);
    const double rotation = number_at(t, "rotation", 0.0, at);
    // The extension's T * R * S, with R = [cos sin; -sin cos].
    const double c = std::cos(rotation);
    const double s = std::sin(rotation);
    *m = {c * scale[0], s * scale[1], offset[0], -s * scale[0], c * scale[1], offset[1]};
    return true;
}

}  // namespace

std::vector<GltfMaterialExtras> gltf_material_extras(const std::string& json_text,
                                                     const std::string& path) {
    const nlohmann::json doc = nlohmann::json::parse(json_text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) {
        return {};
    }
    const auto materials = doc.find("materials");
    if (materials == doc.end() || !materials->is_array()) {
        return {};
    }
    std::vector<GltfMaterialExtras> out;
    for (const nlohmann::json& m : *materials) {
        GltfMaterialExtras extras;
        if (m.is_object() && m.contains("name") && m["name"].is_string()) {
            extras.name = m["name"].get<std::string>();
        }
        const std::string where =
            path + ": material '" + printable(material_name(m, out.size()), 60) + "': ";
        if (m.is_object() && m.contains("extensions") && m["extensions"].is_object() &&
            m["extensions"].contains("KHR_materials_emissive_strength")) {
            const nlohmann::json& ext = m["extensions"]["KHR_materials_emissive_strength"];
            if (ext.is_object() && ext.contains("emissiveStrength")) {
                const nlohmann::json& value = ext["emissiveStrength"];
                const double v = value.is_number() ? value.get<double>() : -1.0;
                if (!(v >= 0.0 && v <= 1e30)) {
                    throw std::runtime_error(
                        where + "KHR_materials_emissive_strength: emissiveStrength " +
                        printable(value.dump(), 40) + ": expected a number in [0, 1e30]");
                }
                extras.emissive_strength = static_cast<float>(v);
            }
        }
        if (m.is_object()) {
            // The textures in the order their transform is taken from.
            std::vector<const nlohmann::json*> infos;
            if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object()) {
                const nlohmann::json& pbr = m["pbrMetallicRoughness"];
                for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"}) {
                    if (pbr.contains(key)) {
                        infos.push_back(&pbr[key]);
                    }
                }
            }
            for (const char* key : {"normalTexture", "emissiveTexture", "occlusionTexture"}) {
                if (m.contains(key)) {
                    infos.push_back(&m[key]);
                }
            }
            std::vector<std::vector<double>> matrices;  // empty: none
            for (const nlohmann::json* info : infos) {
                std::vector<double> matrix;
                if (!texture_transform(*info, &matrix, where)) {
                    matrix.clear();
                }
                matrices.push_back(matrix);
            }
            for (const std::vector<double>& matrix : matrices) {
                if (!extras.uv_transform && !matrix.empty()) {
                    extras.uv_transform = true;
                    extras.uv_matrix = matrix;
                }
            }
            for (const std::vector<double>& matrix : matrices) {
                extras.transforms_differ =
                    extras.transforms_differ ||
                    (matrix.empty() ? extras.uv_transform : matrix != extras.uv_matrix);
            }
        }
        out.push_back(extras);
    }
    return out;
}

}  // namespace trac0r
