#include "trac0r/light_loader.h"

#include "trac0r/input_file.h"
#include "trac0r/material.h"
#include "trac0r/refused_value.h"

#include <algorithm>
#include <cstdio>

namespace trac0r {

using namespace json_diagnostics;

namespace {

// A number of degrees in [lowest, highest] (the ends as `closed` says).
float read_degrees(const ObjectReader& o, const std::string& key, float lowest, bool low_closed,
                   float highest, float fallback) {
    if (!o.has(key)) {
        return fallback;
    }
    char text[96];
    std::snprintf(text, sizeof text, "a number of degrees in %c%g, %g]", low_closed ? '[' : '(',
                  static_cast<double>(lowest), static_cast<double>(highest));
    const json& value = o[key];
    if (!value.is_number() || !fits_float(value)) {
        fail_expected(o.at(key), text, value);
    }
    const float degrees = value.get<float>();
    if (!(low_closed ? degrees >= lowest : degrees > lowest) || !(degrees <= highest)) {
        fail_expected(o.at(key), text, value);
    }
    return degrees;
}

// A direction as the file gives it (SceneBuilder::add_lamp makes it unit).
glm::vec3 read_direction(const ObjectReader& o, const std::string& key,
                         const std::string& meaning) {
    // A zero or overflowing vector is SceneBuilder::add_lamp's to refuse.
    return read_vec3(o.required(key, "an array of 3 finite numbers, not all zero: " + meaning),
                     o.at(key), NumberRule::finite);
}

}  // namespace

void read_environment(const json& value, const Location& at, const std::string& base_dir,
                      SceneBuilder& builder) {
    const ObjectReader o(value, at,
                         "an environment object: {\"color\": [r, g, b]} or "
                         "{\"map\": \"sky.exr\"}, with an optional \"strength\"");
    o.allow_only({"color", "map", "strength", "rotation"}, "the environment");
    if (o.has("color") == o.has("map")) {
        fail(at, o.has("color") ? "an environment has a \"color\" or a \"map\", not both"
                                : "required key is missing (expected \"color\": [r, g, b] for a "
                                  "constant environment, or \"map\": \"FILE.exr\" or .hdr)");
    }
    Environment e;
    if (o.has("map")) {
        const json& map = o["map"];
        if (!map.is_string() || map.get<std::string>().empty()) {
            fail_expected(o.at("map"), "the path of an equirectangular .exr or .hdr map", map);
        }
        try {
            e = read_environment_map(resolve_path(base_dir, map.get<std::string>()));
        } catch (const std::runtime_error& error) {
            fail(o.at("map"), error.what());
        }
        e.rotation = o.optional_float("rotation", NumberRule::finite, 0.0f);
    } else {
        if (o.has("rotation")) {
            fail(o.at("rotation"),
                 "a constant environment has no rotation (it looks the same "
                 "from every direction): remove the key or give a \"map\"");
        }
        e.present = true;
        e.color = o.required_vec3("color", NumberRule::non_negative);
    }
    e.strength = o.optional_float("strength", NumberRule::non_negative, 1.0f);
    try {
        builder.set_environment(std::move(e));
    } catch (const SceneValueError& error) {
        fail_refused(value, at, error);
    }
}

namespace {

Lamp read_lamp(const json& value, const Location& at, const glm::dvec3& origin) {
    const ObjectReader o(value, at, "a light object");
    const std::vector<std::string> types = lamp_type_names();
    Lamp lamp;
    lamp.type = parse_lamp_type(
        read_choice(o.required("type", "one of " + join(types, "\"")), o.at("type"), types));
    lamp.color = o.optional_vec3("color", NumberRule::non_negative, glm::vec3(1.0f));
    if (lamp.type == LampType::sun) {
        o.allow_only({"type", "direction", "color", "irradiance", "angle"}, "a sun light");
        lamp.direction = read_direction(o, "direction", "towards the sun");
        lamp.power = o.required_float("irradiance", NumberRule::non_negative);
        lamp.angle = read_degrees(o, "angle", 0.0f, true, 90.0f, default_sun_angle);
        return lamp;
    }
    if (lamp.type == LampType::point) {
        o.allow_only({"type", "position", "color", "intensity"}, "a point light");
    } else {
        o.allow_only({"type", "position", "direction", "color", "intensity", "angle", "blend"},
                     "a spot light");
        lamp.direction = read_direction(o, "direction", "where the spot points");
        lamp.angle = read_degrees(o, "angle", 0.0f, false, 180.0f, 45.0f);
        lamp.blend = o.optional_float("blend", NumberRule::unit_interval, 0.15f);
    }
    const glm::dvec3 position =
        read_dvec3(o.required("position", expectation(NumberRule::finite, 3)), o.at("position"),
                   NumberRule::finite);
    lamp.position = glm::vec3(position - origin);
    lamp.power = o.required_float("intensity", NumberRule::non_negative);
    return lamp;
}

}  // namespace

void read_light(const json& value, const Location& at, SceneBuilder& builder) {
    const Lamp lamp = read_lamp(value, at, builder.scene().origin);
    try {
        builder.add_lamp(lamp);
    } catch (const SceneValueError& e) {
        fail_refused(value, at, e);
    }
}

void read_lamps(const json& value, const Location& at, SceneBuilder& builder) {
    if (!value.is_array()) {
        fail_expected(at, "an array of lights ({\"type\": \"point\", ...})", value);
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
        read_light(value[i], at.index(i), builder);
    }
}

}  // namespace trac0r
