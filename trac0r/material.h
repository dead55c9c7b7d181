// Host-side materials, with the thesis' parameters.
#ifndef TRAC0R_MATERIAL_H
#define TRAC0R_MATERIAL_H

#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

namespace trac0r {

// The values are the kernel's T0_MATERIAL_* (material.cpp checks them).
enum class MaterialType : unsigned {
    emissive = 1,    // a pure emitter: radiance color x emittance
    diffuse = 2,     // Lambertian, BRDF color/pi; may also emit
    glass = 3,       // smooth dielectric with Fresnel, tinted by color
    glossy = 4,      // the thesis' roughness cone around the mirror direction
    conductor = 5,   // GGX metal: colour as F0, or a named metal
    plastic = 6,     // a Lambertian base under a GGX dielectric coat
    principled = 7,  // glTF 2.0's metallic-roughness BRDF
};

// The most a material may emit in a channel (colour times emittance): a
// pixel sums up to 2^24 samples in float, each the emission times a path's
// weights, and the sum must stay finite (FLT_MAX is 3.4e38). Scene files
// and meshes' materials are held to it.
const float max_emitted_radiance = 1e30f;

enum class AlphaMode : unsigned { opaque = 0, mask = 1, blend = 2 };

struct Material {
    std::string name;
    // The model file whose material this is ("" for the scene's own): a
    // file's names are its own, apart from the scene's and other files'
    // (SceneBuilder). Not part of the image (scene_digest leaves it out).
    std::string file;
    MaterialType type = MaterialType::diffuse;
    glm::vec3 color{0.8f};
    float emittance = 0.0f;
    // glossy: the cone's width; the microfacet types and glass: GGX's
    // roughness (alpha = roughness^2; glass of roughness 0 is the thesis'
    // smooth glass).
    float roughness = 0.0f;
    float ior = 1.5f;
    // A conductor's named metal (metal_index): its measured complex index,
    // times color; "" for Schlick's Fresnel with color as F0.
    std::string metal;
    // principled: glTF's metallicFactor and KHR_materials_specular's
    // specularFactor.
    float metallic = 0.0f;
    float specular = 1.0f;
    // A base-colour texture multiplying color (an emitter's: its emission
    // texture; glass has none): an index into the scene's textures
    // (Scene::textures, or MeshParts::textures for a mesh file's
    // materials); -1 for none.
    int texture = -1;
    // The microfacet types' data textures, indices as texture's: roughness
    // times the roughness texture's green, metallic times the metallic
    // texture's blue (glTF's metallicRoughnessTexture is both), and a
    // tangent-space normal map (any type but emitters) of scale
    // normal_scale.
    int roughness_texture = -1;
    int metallic_texture = -1;
    int normal_texture = -1;
    float normal_scale = 1.0f;
    // Alpha (glTF's alphaMode): opaque; a cut-out where alpha is below
    // alpha_cutoff (MASK); or stochastic opacity (BLEND). alpha is the
    // factor, times alpha_texture's channel alpha_channel (0 red, 3 alpha;
    // glTF: the base-colour texture's alpha, MTL: map_d's red) where given.
    AlphaMode alpha_mode = AlphaMode::opaque;
    float alpha = 1.0f;
    float alpha_cutoff = 0.5f;
    int alpha_texture = -1;
    int alpha_channel = 3;
    // principled: the radiance it emits besides what it reflects (glTF's
    // emissiveFactor x KHR_materials_emissive_strength), times
    // emission_texture (an index as texture's; -1 for none) where given.
    // The other types emit colour x emittance (emitters, diffuse).
    glm::vec3 emission{0.0f};
    int emission_texture = -1;
    // Whether an emitting material emits from both sides (the thesis'), or
    // only from the front: the side its triangles' counter-clockwise
    // winding faces, as OBJ and glTF define it.
    bool two_sided = true;
};

// Every texture index a material holds (base colour, roughness,
// metallic, normal map, alpha, emission), for code that moves or checks
// them all.
inline std::array<int*, 6> texture_fields(Material& m) {
    return {&m.texture,        &m.roughness_texture, &m.metallic_texture,
            &m.normal_texture, &m.alpha_texture,     &m.emission_texture};
}
inline std::array<int, 6> texture_fields(const Material& m) {
    return {m.texture,        m.roughness_texture, m.metallic_texture,
            m.normal_texture, m.alpha_texture,     m.emission_texture};
}

// Whether a material of this type takes a base-colour texture (all but
// glass; an emitter's multiplies its emission).
inline bool takes_texture(MaterialType type) { return type != MaterialType::glass; }

// The radiance a material emits: colour x emittance, or a principled
// material's emission.
inline glm::vec3 emitted_radiance(const Material& m) {
    return m.type == MaterialType::principled ? m.emission : m.color * m.emittance;
}

// Whether the type is one of the GGX microfacet ones (kernel/rough_materials.h).
inline bool is_microfacet(MaterialType type) {
    return type == MaterialType::conductor || type == MaterialType::plastic ||
           type == MaterialType::principled;
}

// A measured metal: its complex index of refraction eta + i k in the red,
// green and blue channels.
struct Metal {
    const char* name;
    glm::vec3 eta;
    glm::vec3 k;
};

// The metals a conductor may name: gold, silver, copper, aluminium,
// chromium, tungsten. Returns nullptr for another name.
const Metal* find_metal(const std::string& name);
std::vector<std::string> metal_names();

// The scale of plastic's diffuse term, 1 / (ior^2 (1 - F_dr)), where F_dr
// is the coat's diffuse reflectance from inside (the hemispherical average
// of the dielectric Fresnel reflectance, integrated numerically).
float plastic_diffuse_scale(float ior);

// "emissive", "diffuse", "glass", "glossy" (the scene format's names) and
// back; parse_material_type throws std::invalid_argument.
const char* to_string(MaterialType type);
MaterialType parse_material_type(const std::string& name);
// Every type's name, in the enum's order.
std::vector<std::string> material_type_names();

}  // namespace trac0r

#endif
