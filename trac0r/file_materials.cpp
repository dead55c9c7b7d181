#include "trac0r/file_materials.h"

#include "trac0r/input_checks.h"

#include <assimp/GltfMaterial.h>

#include <algorithm>
#include <cmath>
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

// A number in [0, 1] that `key` of the file's material `where` gives.
float unit_number(const std::string& where, const char* key, float value) {
    if (!(value >= 0.0f && value <= 1.0f)) {
        char text[96];
        std::snprintf(text, sizeof text, "%s %g: expected it in [0, 1]", key, value);
        throw std::runtime_error(where + text);
    }
    return value;
}

// GGX roughness for a Phong exponent Ns, as Blender's OBJ importer maps
// it: 1 - sqrt(Ns / 1000), Ns clamped to [0, 1000].
float roughness_from_ns(float ns) {
    return 1.0f - std::sqrt(std::min(std::max(ns, 0.0f), 1000.0f) / 1000.0f);
}

// An emission e, checked: each channel in [0, max_emitted_radiance].
glm::vec3 checked_emission(const std::string& where, const char* key, const glm::vec3& e) {
    if (!(std::min({e.x, e.y, e.z}) >= 0.0f) || !(peak(e) <= max_emitted_radiance)) {
        throw std::runtime_error(where + key + ": expected each in [0, 1e30]");
    }
    return e;
}

// An emissive material of emission e (checked_emission).
Material emitter(const std::string& where, const char* key, const glm::vec3& e) {
    checked_emission(where, key, e);
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
    } else if (m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9 ||
               (m.dissolve < 1.0f && m.alpha_texname.empty())) {
        out.type = MaterialType::glass;
        out.color = peak(tf) > 0.0f ? unit_colour(where, "Tf", tf) : glm::vec3(1.0f);
        out.ior = m.ior > 1.0f ? m.ior : 1.5f;
    } else if (m.roughness > 0.0f || m.metallic > 0.0f || !m.roughness_texname.empty() ||
               !m.metallic_texname.empty()) {
        // The PBR extension (Pr, Pm): glTF's model, as Blender reads it.
        out.type = MaterialType::principled;
        out.color = unit_colour(where, "Kd", kd);
        out.roughness = unit_number(where, "Pr", m.roughness);
        out.metallic = unit_number(where, "Pm", m.metallic);
    } else if (m.illum == 3 || m.illum == 5 || m.illum == 8) {
        // Reflection on: a metal of colour Ks (else Kd), as Blender makes
        // illum 3 metallic.
        out.type = MaterialType::conductor;
        out.color = peak(ks) > 0.0f ? unit_colour(where, "Ks", ks) : unit_colour(where, "Kd", kd);
        out.roughness = roughness_from_ns(m.shininess);
    } else if (peak(ks) > 0.0f && m.illum == 2) {
        // Highlights on: a coated (plastic) surface of colour Kd.
        out.type = MaterialType::plastic;
        out.color = unit_colour(where, "Kd", kd);
        out.roughness = roughness_from_ns(m.shininess);
        out.ior = m.ior > 1.0f ? m.ior : 1.5f;
    } else {
        out.type = MaterialType::diffuse;
        out.color = unit_colour(where, "Kd", kd);
    }
    if (!m.alpha_texname.empty() && out.type != MaterialType::emissive) {
        // map_d: an opacity map (its red), times d, as stochastic opacity.
        out.alpha_mode = AlphaMode::blend;
        out.alpha = unit_number(where, "d", m.dissolve);
        out.alpha_channel = 0;
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
// (rough) glass where it transmits (what it emits is then left out), else
// principled: its base colour, metallic, roughness, ior and specular
// factor, and its emission (emissiveFactor x emissive strength).
Material material_from_assimp(const aiMaterial& m, const std::string& file,
                              float emissive_strength) {
    aiString name;
    m.Get(AI_MATKEY_NAME, name);
    const std::string where = file + ": material '" + printable(name.C_Str(), 60) + "': ";
    aiColor4D base(0.8f, 0.8f, 0.8f, 1.0f);
    if (m.Get(AI_MATKEY_BASE_COLOR, base) != AI_SUCCESS) {
        m.Get(AI_MATKEY_COLOR_DIFFUSE, base);
    }
    aiColor3D emissive(0.0f, 0.0f, 0.0f);
    m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    const float metallic = property(m, AI_MATKEY_METALLIC_FACTOR, 0.0f);
    const float roughness = property(m, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f);
    const float transmission = property(m, AI_MATKEY_TRANSMISSION_FACTOR, 0.0f);
    // glTF's alpha: the base colour's (times its texture's, which
    // shape.cpp adds), counted only in the modes MASK (a cut-out below
    // the cutoff) and BLEND (stochastic opacity); OPAQUE ignores it.
    aiString alpha_mode;
    AlphaMode mode = AlphaMode::opaque;
    if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS) {
        if (std::strcmp(alpha_mode.C_Str(), "MASK") == 0) {
            mode = AlphaMode::mask;
        } else if (std::strcmp(alpha_mode.C_Str(), "BLEND") == 0) {
            mode = AlphaMode::blend;
        }
    }
    const float ior = property(m, AI_MATKEY_REFRACTI, 1.5f);
    const glm::vec3 colour(base.r, base.g, base.b);
    const glm::vec3 emission = glm::vec3(emissive.r, emissive.g, emissive.b) * emissive_strength;
    Material out;
    if (transmission > 0.0f) {
        out.type = MaterialType::glass;
        out.color = unit_colour(where, "base colour", colour);
        out.ior = ior > 1.0f ? ior : 1.5f;
        out.roughness = unit_number(where, "roughness", roughness);
    } else {
        // glTF 2.0's metallic-roughness (Appendix B), with KHR_materials_ior
        // and KHR_materials_specular's factor.
        out.type = MaterialType::principled;
        out.color = unit_colour(where, "base colour", colour);
        out.roughness = unit_number(where, "roughness", roughness);
        out.metallic = unit_number(where, "metallic", metallic);
        out.ior = ior > 0.0f && std::isfinite(ior) ? ior : 1.5f;
        out.specular = unit_number(where, "specular", property(m, AI_MATKEY_SPECULAR_FACTOR, 1.0f));
        // What it emits besides (glTF: every material reflects and emits).
        out.emission = checked_emission(where, "emissive", emission);
    }
    // A material of a glTF file emits from its front alone unless it is
    // material is doubleSided (glTF 2.0, 3.9.5), which assimp reports as
    // AI_MATKEY_TWOSIDED; other formats keep the thesis' two sides unless
    // they say otherwise.
    int two_sided = 0;
    if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) {
        out.two_sided = two_sided != 0;
    } else {
        out.two_sided = !has_extension(file, ".gltf") && !has_extension(file, ".glb");
    }
    if (mode != AlphaMode::opaque && out.type != MaterialType::emissive) {
        out.alpha_mode = mode;
        out.alpha = unit_number(where, "base colour alpha", base.a);
        out.alpha_cutoff =
            unit_number(where, "alphaCutoff", property(m, AI_MATKEY_GLTF_ALPHACUTOFF, 0.5f));
        out.alpha_channel = 3;
    }
    out.name = name.C_Str();
    return out;
}

// The base-colour texture an MTL material names, for the material `out`
// made of it: for an emitter its emission's (map_Ke), for a glossy or
// conductor one the map of the colour it took (map_Ks with Ks, else
// map_Kd), map_Kd for the others that take a texture; "" for none. *key is the statement's name,
// for messages.
std::string mtl_texture_name(const tinyobj::material_t& m, const Material& out, const char** key) {
    *key = "map_Kd";
    if (out.type == MaterialType::emissive) {
        *key = "map_Ke";
        return m.emissive_texname;
    }
    if (out.type == MaterialType::glossy || out.type == MaterialType::conductor) {
        const bool from_ks = m.specular[0] > 0.0f || m.specular[1] > 0.0f || m.specular[2] > 0.0f;
        if (from_ks) {
            *key = "map_Ks";
            return m.specular_texname;
        }
        return m.diffuse_texname;
    }
    if (takes_texture(out.type)) {
        return m.diffuse_texname;
    }
    return "";
}

}  // namespace trac0r
