#include "trac0r/material_loader.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace trac0r {

using namespace json_diagnostics;

namespace {

// What each type of material reads besides "type", "color" and the keys
// below: one row per number it takes, in the schema table
// (scene_loader.cpp). A key of another type (roughness on a diffuse
// material) is an error, not ignored.
struct MaterialKey {
    MaterialType type;
    const char* key;
    NumberRule rule;
    bool required;   // else optional, with the default below
    float fallback;  // the default
    float Material::*field;
};

const MaterialKey material_keys[] = {
    {MaterialType::emissive, "emittance", NumberRule::positive, true, 0.0f, &Material::emittance},
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
    // Blender's Principled BSDF's defaults (glTF's are metallic 1, roughness
    // 1: a file's materials always give theirs).
    {MaterialType::principled, "roughness", NumberRule::unit_interval, false, 0.5f,
     &Material::roughness},
    {MaterialType::principled, "metallic", NumberRule::unit_interval, false, 0.0f,
     &Material::metallic},
    {MaterialType::principled, "ior", NumberRule::positive, false, 1.5f, &Material::ior},
    {MaterialType::principled, "specular", NumberRule::unit_interval, false, 1.0f,
     &Material::specular},
};

// The colour's rule: emitted radiance may exceed 1, reflectances may not.
NumberRule color_rule(MaterialType type) {
    return type == MaterialType::emissive ? NumberRule::non_negative : NumberRule::unit_interval;
}

// A conductor's "metal": one of the names find_metal knows.
void read_metal(const ObjectReader& o, Material& m) {
    if (!o.has("metal")) {
        return;
    }
    const std::vector<std::string> names = metal_names();
    m.metal = read_choice(o["metal"], o.at("metal"), names);
}

void read_material_parameters(const ObjectReader& o, Material& m) {
    std::vector<std::string> allowed = {"type", "color"};
    for (const MaterialKey& k : material_keys) {
        if (k.type == m.type) {
            allowed.push_back(k.key);
        }
    }
    if (m.type == MaterialType::emissive || m.type == MaterialType::diffuse) {
        allowed.push_back("two_sided");
    }
    if (m.type == MaterialType::conductor) {
        allowed.push_back("metal");
    }
    if (m.type == MaterialType::principled) {
        allowed.push_back("emission");
        allowed.push_back("two_sided");
    }
    o.allow_only(allowed, with_article(to_string(m.type)) + " material");
    m.two_sided = o.optional_bool("two_sided", true);
    read_metal(o, m);
    // A named metal's colour is a factor on its measured reflectance: white
    // unless given.
    m.color = m.metal.empty() ? o.required_vec3("color", color_rule(m.type))
                              : o.optional_vec3("color", color_rule(m.type), glm::vec3(1.0f));
    for (const MaterialKey& k : material_keys) {
        if (k.type == m.type) {
            m.*k.field = k.required ? o.required_float(k.key, k.rule)
                                    : o.optional_float(k.key, k.rule, k.fallback);
        }
    }
    if (m.type == MaterialType::principled) {
        m.emission = o.optional_vec3("emission", NumberRule::non_negative, glm::vec3(0.0f));
    }
}

void check_emission(const ObjectReader& o, const Material& m) {
    const bool principled = m.type == MaterialType::principled;
    const double emitted =
        principled ? std::max({m.emission.x, m.emission.y, m.emission.z})
                   : static_cast<double>(m.emittance) * std::max({m.color.x, m.color.y, m.color.z});
    if (emitted > static_cast<double>(max_emitted_radiance)) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", emitted);
        fail(o.at(principled ? "emission" : "emittance"),
             std::string(principled ? "the emission" : "the colour times the emittance") + " is " +
                 text +
                 " in a channel, above 1e30, the most the renderer can "
                 "sum over a pixel's samples in float: scale the scene's emission down");
    }
}

Material read_material(const std::string& name, const json& value, const Location& at) {
    const ObjectReader o(value, at, "a material object");
    const std::vector<std::string> types = material_type_names();
    Material m;
    m.name = name;
    m.type = parse_material_type(
        read_choice(o.required("type", "one of " + join(types, "\"")), o.at("type"), types));
    read_material_parameters(o, m);
    check_emission(o, m);
    return m;
}

}  // namespace

std::vector<Material> read_materials(const json& value, const Location& at) {
    const std::string expected = "a non-empty object of named materials";
    if (!value.is_object() || value.empty()) {
        fail_expected(at, expected, value);
    }
    std::vector<Material> materials;
    for (auto it = value.begin(); it != value.end(); ++it) {
        materials.push_back(read_material(it.key(), it.value(), at.key(it.key())));
    }
    return materials;
}

}  // namespace trac0r
