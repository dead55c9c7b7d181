#include "trac0r/gltf_view.h"

#include "trac0r/gltf_nodes.h"
#include "trac0r/input_checks.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>

namespace trac0r {

namespace {

using nlohmann::json;

const double pi = 3.14159265358979323846;
// Luminous efficacy at 555 nm: candela to W/sr, lux to W/m^2.
const double lumens_per_watt = 683.0;

double number(const json& object, const char* key, double fallback, const std::string& what) {
    if (!object.is_object() || !object.contains(key)) {
        return fallback;
    }
    return gltf_numbers(json::array({object[key]}), 1, what + ": " + key)[0];
}

glm::dvec3 unit_or(const glm::dvec3& v, const glm::dvec3& fallback) {
    const double l = glm::length(v);
    return l > 0.0 && std::isfinite(l) ? v / l : fallback;
}

}  // namespace

GltfView gltf_view(const std::string& json_text, const std::string& path) {
    GltfView view;
    const json doc = json::parse(json_text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("nodes") ||
        !doc["nodes"].is_array()) {
        return view;
    }
    const json no_lights = json::array();
    const json* lights = &no_lights;
    if (doc.contains("extensions") && doc["extensions"].is_object() &&
        doc["extensions"].contains("KHR_lights_punctual") &&
        doc["extensions"]["KHR_lights_punctual"].is_object() &&
        doc["extensions"]["KHR_lights_punctual"].contains("lights") &&
        doc["extensions"]["KHR_lights_punctual"]["lights"].is_array()) {
        lights = &doc["extensions"]["KHR_lights_punctual"]["lights"];
    }
    walk_gltf_nodes(doc, path, [&](std::size_t index, const json& node, const glm::dmat4& world) {
        const std::string what = path + ": node " + std::to_string(index);
        const glm::dvec3 origin = glm::dvec3(world * glm::dvec4(0, 0, 0, 1));
        const glm::dvec3 forward =
            unit_or(glm::dvec3(world * glm::dvec4(0, 0, -1, 0)), glm::dvec3(0, 0, -1));
        if (!view.has_camera && node.contains("camera") && node["camera"].is_number_unsigned() &&
            doc.contains("cameras") && doc["cameras"].is_array() &&
            node["camera"].get<std::size_t>() < doc["cameras"].size()) {
            const json& camera = doc["cameras"][node["camera"].get<std::size_t>()];
            const std::string type = camera.is_object() ? camera.value("type", "") : "";
            const std::string at = what + ": camera";
            if (type == "perspective" && camera.contains("perspective")) {
                const double yfov = number(camera["perspective"], "yfov", -1.0, at);
                if (!(yfov > 0.0 && yfov < pi)) {
                    throw std::runtime_error(at + ": yfov: expected radians in (0, pi)");
                }
                view.has_camera = true;
                view.vertical_fov = yfov * 180.0 / pi;
                view.aspect = number(camera["perspective"], "aspectRatio", 0.0, at);
            } else if (type == "orthographic" && camera.contains("orthographic")) {
                // xmag and ymag: half the view's width and height (which
                // should not be negative: taken as their size).
                const double xmag = std::fabs(number(camera["orthographic"], "xmag", 0.0, at));
                const double ymag = std::fabs(number(camera["orthographic"], "ymag", 0.0, at));
                if (!(xmag > 0.0 && ymag > 0.0 && xmag <= 5e29 && ymag <= 5e29)) {
                    throw std::runtime_error(at + ": xmag, ymag: expected numbers not zero and " +
                                             "at most 5e29 (half the view's width and height), " +
                                             "got " + json(xmag).dump() + ", " + json(ymag).dump());
                }
                view.has_camera = true;
                view.orthographic = true;
                view.view_height = 2.0 * ymag;
                view.aspect = xmag / ymag;
            }
            if (view.has_camera) {
                view.position = origin;
                view.direction = forward;
                view.up = unit_or(glm::dvec3(world * glm::dvec4(0, 1, 0, 0)), glm::dvec3(0, 1, 0));
            }
        }
        if (node.contains("extensions") && node["extensions"].is_object() &&
            node["extensions"].contains("KHR_lights_punctual")) {
            const json& ref = node["extensions"]["KHR_lights_punctual"];
            if (ref.is_object() && ref.contains("light") && ref["light"].is_number_unsigned() &&
                ref["light"].get<std::size_t>() < lights->size()) {
                const std::size_t li = ref["light"].get<std::size_t>();
                const json& light = (*lights)[li];
                const std::string at = path + ": KHR_lights_punctual light " + std::to_string(li);
                Lamp lamp;
                const std::string type = light.is_object() ? light.value("type", "") : "";
                if (light.contains("color")) {
                    const std::vector<double> c = gltf_numbers(light["color"], 3, at + ": color");
                    lamp.color = glm::vec3(c[0], c[1], c[2]);
                }
                const double intensity = number(light, "intensity", 1.0, at);
                if (!(intensity >= 0.0) || lamp.color.x < 0.0f || lamp.color.y < 0.0f ||
                    lamp.color.z < 0.0f) {
                    throw std::runtime_error(at + ": expected intensity and colour >= 0");
                }
                lamp.power = static_cast<float>(intensity / lumens_per_watt);
                lamp.position = glm::vec3(origin);
                lamp.direction = glm::vec3(forward);
                if (type == "point") {
                    lamp.type = LampType::point;
                } else if (type == "spot") {
                    lamp.type = LampType::spot;
                    const json spot = light.contains("spot") ? light["spot"] : json::object();
                    const double outer = number(spot, "outerConeAngle", pi / 4.0, at);
                    const double inner = number(spot, "innerConeAngle", 0.0, at);
                    if (!(outer > 0.0 && outer <= pi / 2.0 && inner >= 0.0 && inner < outer)) {
                        throw std::runtime_error(
                            at + ": expected 0 <= innerConeAngle < outerConeAngle <= pi/2");
                    }
                    lamp.angle = static_cast<float>(2.0 * outer * 180.0 / pi);
                    lamp.blend = static_cast<float>((outer - inner) / outer);
                } else if (type == "directional") {
                    lamp.type = LampType::sun;
                    lamp.direction = -glm::vec3(forward);  // towards the sun
                    lamp.angle = 0.0f;
                } else {
                    throw std::runtime_error(at + ": type '" + printable(type, 20) +
                                             "': expected point, spot or directional");
                }
                view.lamps.push_back(lamp);
            }
        }
    });
    return view;
}

}  // namespace trac0r
