#include "trac0r/file_materials.h"

#include "trac0r/input_checks.h"

#include <assimp/GltfMaterial.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace trac0r {

namespace {

float peak(const glm::vec3& c) { return std::max({c.x, c.y, c.z}); }

// colour, which `key` of the file's material `where` gives, if each channel
// is in [0, 1].
glm::vec3 unit_colour(const std::string& where, const char* key, const glm::vec3& c) {
    if (!(std::min({c.x, c.y, c.z}) >= 0.0f) || !(peak(c) <= 1.0f)) {
        char text[96];
        std::snprintf(text, sizeof text, "%s (%g, %g, %g): expected each in [0, 1]", key, c.x, c.y,
                      c.z);
        throw std::runtime_error(where + text);
    }
    return c;
}

// An emissive material of emission e (each channel in [0,
// max_emitted_radiance]).
Material emitter(const std::string& where, const char* key, const glm::vec3& e) {
    if (!(std::min({e.x, e.y, e.z}) >= 0.0f) || !(peak(e) <= max_emitted_radiance)) {
        throw std::runtime_error(where + key + ": expected each in [0, 1e30]");
    }
    Material out;
    out.type = MaterialType::emissive;
    out.emittance = peak(e);
    out.color = e / out.emittance;
    return out;
}

// The float property key (an AI_MATKEY_...) of m, or fallback where m has
// none.
float property(const aiMaterial& m, const char* key, unsigned type, unsigned index,
               float fallback) {
    float value = fallback;
    m.Get(key, type, index, value);
    return value;
}

}  // namespace

// One of the renderer's materials for an MTL material (the table in
// docs/scene-format.md, "Materials from the file").
Material material_from_mtl(const tinyobj::material_t& m, const std::string& file) {
    const std::string where = file + ": material '" + printable(m.name, 60) + "': ";
    const glm::vec3 kd(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    const glm::vec3 ks(m.specular[0], m.specular[1], m.specular[2]);
    const glm::vec3 ke(m.emission[0], m.emission[1], m.emission[2]);
    const glm::vec3 tf(m.transmittance[0], m.transmittance[1], m.transmittance[2]);
    Material out;
    if (peak(ke) > 0.0f) {
        out = emitter(where, "Ke", ke);
    } else if (m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9 || m.dissolve < 1.0f) {
        out.type = MaterialType::glass;
        out.color = peak(tf) > 0.0f ? unit_colour(where, "Tf", tf) : glm::vec3(1.0f);
        out.ior = m.ior > 1.0f ? m.ior : 1.5f;
    } else if (m.illum == 3 || m.illum == 5 || m.illum == 8) {
        out.type = MaterialType::glossy;
        out.color = peak(ks) > 0.0f ? unit_colour(where, "Ks", ks) : unit_colour(where, "Kd", kd);
        // The Phong lobe of exponent Ns is about sqrt(2 / (Ns + 2)) radians
        // wide; roughness 1 is a cone of pi/2.
        const float width = std::sqrt(2.0f / (std::max(m.shininess, 0.0f) + 2.0f));
        out.roughness = std::min(1.0f, width / 1.5707963f);
    } else {
        out.type = MaterialType::diffuse;
        out.color = unit_colour(where, "Kd", kd);
    }
    out.name = m.name;
    return out;
}

// What assimp adds for glTF primitives that name no material: no name,
// and glTF's default values (white, metallic 1, roughness 1, no
// emission). A file's own unnamed material with exactly these values is
// glTF's default material too.
bool is_default_material(const aiMaterial& m) {
    aiString name;
    aiColor4D base(0.0f, 0.0f, 0.0f, 0.0f);
    aiColor3D emissive(0.0f, 0.0f, 0.0f);
    m.Get(AI_MATKEY_BASE_COLOR, base);
    m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    return m.Get(AI_MATKEY_NAME, name) != AI_SUCCESS && base == aiColor4D(1.0f, 1.0f, 1.0f, 1.0f) &&
           property(m, AI_MATKEY_METALLIC_FACTOR, 0.0f) == 1.0f &&
           property(m, AI_MATKEY_ROUGHNESS_FACTOR, 0.0f) == 1.0f && emissive.IsBlack();
}

// One of the renderer's materials for a glTF (or other assimp) material:
// emissive where it emits, glass where it transmits or is not opaque,
// glossy where it is metal (metallic >= 0.5, roughness as the file's),
// else diffuse of its base colour.
Material material_from_assimp(const aiMaterial& m, const std::string& file) {
    aiString name;
    m.Get(AI_MATKEY_NAME, name);
    const std::string where = file + ": material '" + printable(name.C_Str(), 60) + "': ";
    aiColor4D base(0.8f, 0.8f, 0.8f, 1.0f);
    if (m.Get(AI_MATKEY_BASE_COLOR, base) != AI_SUCCESS) {
        m.Get(AI_MATKEY_COLOR_DIFFUSE, base);
    }
    aiColor3D emissive(0.0f, 0.0f, 0.0f);
    m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    const float strength = property(m, AI_MATKEY_EMISSIVE_INTENSITY, 1.0f);
    const float metallic = property(m, AI_MATKEY_METALLIC_FACTOR, 0.0f);
    const float roughness = property(m, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f);
    const float transmission = property(m, AI_MATKEY_TRANSMISSION_FACTOR, 0.0f);
    // glTF's alpha counts only where its alpha mode is BLEND (OPAQUE
    // ignores it; MASK cuts out, which the renderer cannot).
    aiString alpha_mode;
    const bool blend = m.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS &&
                       std::strcmp(alpha_mode.C_Str(), "BLEND") == 0;
    const float opacity = blend ? property(m, AI_MATKEY_OPACITY, 1.0f) : 1.0f;
    const float ior = property(m, AI_MATKEY_REFRACTI, 1.5f);
    const glm::vec3 colour(base.r, base.g, base.b);
    const glm::vec3 emission = glm::vec3(emissive.r, emissive.g, emissive.b) * strength;
    Material out;
    if (peak(emission) > 0.0f) {
        out = emitter(where, "emissive", emission);
    } else if (transmission > 0.0f || opacity < 1.0f) {
        out.type = MaterialType::glass;
        out.color = unit_colour(where, "base colour", colour);
        out.ior = ior > 1.0f ? ior : 1.5f;
    } else if (metallic >= 0.5f) {
        out.type = MaterialType::glossy;
        out.color = unit_colour(where, "base colour", colour);
        if (!(roughness >= 0.0f && roughness <= 1.0f)) {
            throw std::runtime_error(where + "roughness " + std::to_string(roughness) +
                                     ": expected it in [0, 1]");
        }
        out.roughness = roughness;
    } else {
        out.type = MaterialType::diffuse;
        out.color = unit_colour(where, "base colour", colour);
    }
    // An emitter of a glTF file emits from its front alone unless the
    // material is doubleSided (glTF 2.0, 3.9.5), which assimp reports as
    // AI_MATKEY_TWOSIDED; other formats keep the thesis' two sides unless
    // they say otherwise.
    int two_sided = 0;
    if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) {
        out.two_sided = two_sided != 0;
    } else {
        out.two_sided = !has_extension(file, ".gltf") && !has_extension(file, ".glb");
    }
    out.name = name.C_Str();
    return out;
}

// The base-colour texture an MTL material names, for the material `out`
// made of it: map_Kd for a diffuse one, and for a glossy one the map of
// the colour it took (map_Ks with Ks, else map_Kd); "" for none. *key is
// the statement's name, for messages.
std::string mtl_texture_name(const tinyobj::material_t& m, const Material& out, const char** key) {
    *key = "map_Kd";
    if (out.type == MaterialType::diffuse) {
        return m.diffuse_texname;
    }
    if (out.type == MaterialType::glossy) {
        const bool from_ks = m.specular[0] > 0.0f || m.specular[1] > 0.0f || m.specular[2] > 0.0f;
        if (from_ks) {
            *key = "map_Ks";
            return m.specular_texname;
        }
        return m.diffuse_texname;
    }
    return "";
}

}  // namespace trac0r
