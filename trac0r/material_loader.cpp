#include "trac0r/material_loader.h"

#include "trac0r/material_schema.h"
#include "trac0r/refused_value.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace trac0r {

using namespace json_diagnostics;

namespace {

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
    for (const MaterialKey& k : material_keys()) {
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
    const NumberRule color_rule = material_color_rule(m.type);
    m.color = m.metal.empty() ? o.required_vec3("color", color_rule)
                              : o.optional_vec3("color", color_rule, glm::vec3(1.0f));
    for (const MaterialKey& k : material_keys()) {
        if (k.type == m.type) {
            m.*k.field = k.required ? o.required_float(k.key, k.rule)
                                    : o.optional_float(k.key, k.rule, k.fallback);
        }
    }
    if (m.type == MaterialType::principled) {
        m.emission = o.optional_vec3("emission", NumberRule::non_negative, glm::vec3(0.0f));
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
    return m;
}

}  // namespace

void read_materials(const json& value, const Location& at, SceneBuilder& builder) {
    const std::string expected = "a non-empty object of named materials";
    if (!value.is_object() || value.empty()) {
        fail_expected(at, expected, value);
    }
    for (auto it = value.begin(); it != value.end(); ++it) {
        const Location material_at = at.key(it.key());
        const Material m = read_material(it.key(), it.value(), material_at);
        try {
            builder.add_material(m);
        } catch (const SceneValueError& e) {
            fail_refused(it.value(), material_at, e);
        }
    }
}

}  // namespace trac0r
