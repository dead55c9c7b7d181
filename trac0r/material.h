// Host-side materials, with the thesis' parameters.
#ifndef TRAC0R_MATERIAL_H
#define TRAC0R_MATERIAL_H

#include "trac0r/kernel/types.h"

#include <glm/glm.hpp>

#include <string>

namespace trac0r {

enum class MaterialType : unsigned {
    emissive = T0_MATERIAL_EMISSIVE,  // a pure emitter: radiance color x emittance
    diffuse = T0_MATERIAL_DIFFUSE,    // Lambertian, BRDF color/pi; may also emit
    glass = T0_MATERIAL_GLASS,        // smooth dielectric with Fresnel, tinted by color
    glossy = T0_MATERIAL_GLOSSY,      // the thesis' roughness cone around the mirror direction
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::diffuse;
    glm::vec3 color{0.8f};
    float emittance = 0.0f;
    float roughness = 0.0f;
    float ior = 1.5f;
};

const char* to_string(MaterialType type);

}  // namespace trac0r

#endif
