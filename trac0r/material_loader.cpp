#include "trac0r/material_loader.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace trac0r {

using namespace json_diagnostics;

namespace {

// What each type of material reads besides "type": a colour and one
// parameter, in the schema table above. A key of another type (roughness
// on a diffuse material) is an error, not ignored.
struct MaterialKeys {
    MaterialType type;
    NumberRule color_rule;
    const char* parameter;  // the parameter's key
    NumberRule parameter_rule;
    bool parameter_required;  // else optional, its default Material's
    float Material::*field;   // where the parameter goes
};

const MaterialKeys material_keys[] = {
    {MaterialType::emissive, NumberRule::non_negative, "emittance", NumberRule::positive, true,
     &Material::emittance},
    {MaterialType::diffuse, NumberRule::unit_interval, "emittance", NumberRule::non_negative, false,
     &Material::emittance},
    {MaterialType::glass, NumberRule::unit_interval, "ior", NumberRule::positive, false,
     &Material::ior},
    {MaterialType::glossy, NumberRule::unit_interval, "roughness", NumberRule::unit_interval, false,
     &Material::roughness},
};

void read_material_parameters(const ObjectReader& o, Material& m) {
    const MaterialKeys& keys =
        *std::find_if(std::begin(material_keys), std::end(material_keys),
                      [&](const MaterialKeys& k) { return k.type == m.type; });
    std::vector<std::string> allowed = {"type", "color", keys.parameter};
    if (keys.field == &Material::emittance) {
        allowed.push_back("two_sided");
    }
    o.allow_only(allowed, with_article(to_string(m.type)) + " material");
    m.two_sided = o.optional_bool("two_sided", true);
    m.color = o.required_vec3("color", keys.color_rule);
    float& parameter = m.*keys.field;
    parameter = keys.parameter_required
                    ? o.required_float(keys.parameter, keys.parameter_rule)
                    : o.optional_float(keys.parameter, keys.parameter_rule, parameter);
}

void check_emission(const ObjectReader& o, const Material& m) {
    const double emitted =
        static_cast<double>(m.emittance) * std::max({m.color.x, m.color.y, m.color.z});
    if (emitted > static_cast<double>(max_emitted_radiance)) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", emitted);
        fail(o.at("emittance"), "the colour times the emittance is " + std::string(text) +
                                    " in a channel, above 1e30, the most the renderer can "
                                    "sum over a pixel's samples in float: scale the "
                                    "scene's emittances down");
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
