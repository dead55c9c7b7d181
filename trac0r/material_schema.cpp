#include "trac0r/material_schema.h"

#include "trac0r/json_diagnostics.h"

namespace trac0r {

using json_diagnostics::NumberRule;

const std::vector<MaterialKey>& material_keys() {
    static const std::vector<MaterialKey> keys = {
        {MaterialType::emissive, "emittance", NumberRule::positive, true, 0.0f,
         &Material::emittance},
        {MaterialType::diffuse, "emittance", NumberRule::non_negative, false, 0.0f,
         &Material::emittance},
        {MaterialType::glass, "ior", NumberRule::positive, false, 1.5f, &Material::ior},
        {MaterialType::glass, "roughness", NumberRule::unit_interval, false, 0.0f,
         &Material::roughness},
        {MaterialType::glossy, "roughness", NumberRule::unit_interval, false, 0.0f,
         &Material::roughness},
        {MaterialType::conductor, "roughness", NumberRule::unit_interval, false, 0.0f,
         &Material::roughness},
        {MaterialType::plastic, "roughness", NumberRule::unit_interval, false, 0.0f,
         &Material::roughness},
        {MaterialType::plastic, "ior", NumberRule::positive, false, 1.5f, &Material::ior},
        // Blender's Principled BSDF's defaults (glTF's are metallic 1,
        // roughness 1: a file's materials always give theirs).
        {MaterialType::principled, "roughness", NumberRule::unit_interval, false, 0.5f,
         &Material::roughness},
        {MaterialType::principled, "metallic", NumberRule::unit_interval, false, 0.0f,
         &Material::metallic},
        {MaterialType::principled, "ior", NumberRule::positive, false, 1.5f, &Material::ior},
        {MaterialType::principled, "specular", NumberRule::unit_interval, false, 1.0f,
         &Material::specular},
    };
    return keys;
}

NumberRule material_color_rule(MaterialType type) {
    return type == MaterialType::emissive ? NumberRule::non_negative : NumberRule::unit_interval;
}

}  // namespace trac0r
