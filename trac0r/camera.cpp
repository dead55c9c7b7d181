#include "trac0r/camera.h"

#include "trac0r/kernel/types.h"

#include "trac0r/geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace trac0r {

namespace {

// v divided by its largest component's magnitude: the same direction, with
// a length between 1 and sqrt(3), so that lengths and cross products of
// vectors such as [3e38, 3e38, 3e38] do not overflow (their squares would).
glm::vec3 direction_of(const glm::vec3& v) {
    const float largest = std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z)));
    return largest > 0.0f ? v / largest : v;
}

}  // namespace

const char* camera_problem(const Camera& camera) {
    if (!is_finite(camera.position)) {
        return "camera.position must be finite";
    }
    if (!is_finite(camera.direction) || glm::length(camera.direction) == 0.0f) {
        return "camera.direction must be a finite vector whose length is not zero in float "
               "(a component above about 1e-19)";
    }
    if (!is_finite(camera.world_up) || glm::length(camera.world_up) == 0.0f) {
        return "camera.world_up must be a finite vector whose length is not zero in float "
               "(a component above about 1e-19)";
    }
    const glm::vec3 direction = direction_of(camera.direction);
    const glm::vec3 world_up = direction_of(camera.world_up);
    const glm::vec3 right = glm::cross(direction, world_up);
    if (glm::length(right) <= 1e-6f * glm::length(world_up) * glm::length(direction)) {
        return "camera.direction is parallel to camera.world_up, so the image has no "
               "'right'; choose another world_up";
    }
    if (!(camera.vertical_fov > 0.0f && camera.vertical_fov < 180.0f)) {
        return "camera.vertical_fov must be in (0, 180) degrees";
    }
    if (camera.projection != Projection::perspective &&
        camera.projection != Projection::orthographic) {
        return "camera.projection must be perspective or orthographic";
    }
    if (!(camera.view_height > 0.0f && camera.view_height <= 1e30f)) {
        return "camera.view_height must be a finite number > 0 (metres)";
    }
    if (!(camera.aperture_radius >= 0.0f && std::isfinite(camera.aperture_radius))) {
        return "camera.aperture_radius must be a finite number >= 0 (metres; 0 is a pinhole)";
    }
    if (!(camera.focus_distance > 0.0f && std::isfinite(camera.focus_distance))) {
        return "camera.focus_distance must be a finite number > 0 (metres along the view "
               "direction)";
    }
    return nullptr;
}

namespace {

// The shortest decimal of `value` (at most 17 digits) that reads back as
// `offset` plus a number whose float is `target`: what the scene loader
// does with a position (relative to the origin) or any other number.
std::string shortest(double value, double offset, float target) {
    char text[40];
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, value);
        if (static_cast<float>(std::strtod(text, nullptr) - offset) == target) {
            break;
        }
    }
    return text;
}

std::string json_vec3(const glm::vec3& v, const glm::dvec3& offset) {
    return "[" + shortest(offset.x + v.x, offset.x, v.x) + ", " +
           shortest(offset.y + v.y, offset.y, v.y) + ", " +
           shortest(offset.z + v.z, offset.z, v.z) + "]";
}

std::string json_number(float v) { return shortest(v, 0.0, v); }

}  // namespace

std::string camera_block_json(const Camera& camera, const glm::dvec3& origin) {
    const glm::dvec3 none(0.0);
    return "{\"camera\": {\"position\": " + json_vec3(camera.position, origin) +
           ", \"direction\": " + json_vec3(camera.direction, none) +
           ", \"world_up\": " + json_vec3(camera.world_up, none) +
           (camera.projection == Projection::orthographic
                ? ", \"projection\": \"orthographic\", \"view_height\": " +
                      json_number(camera.view_height)
                : ", \"vertical_fov\": " + json_number(camera.vertical_fov)) +
           ", \"aperture_radius\": " + json_number(camera.aperture_radius) +
           ", \"focus_distance\": " + json_number(camera.focus_distance) + "}}";
}

kernel::CameraRecord make_camera_record(const Camera& camera, int width, int height) {
    if (const char* problem = camera_problem(camera)) {
        throw std::invalid_argument(problem);
    }
    if (width <= 0 || height <= 0) {
        throw std::invalid_argument("image size must be positive, got " + std::to_string(width) +
                                    " x " + std::to_string(height));
    }
    const glm::vec3 forward = glm::normalize(direction_of(camera.direction));
    // Right-handed, as glTF, Blender and OpenGL: looking along -z with y up,
    // +x is on the image's right.
    const glm::vec3 right = glm::normalize(glm::cross(forward, direction_of(camera.world_up)));
    const glm::vec3 up = glm::cross(right, forward);
    const bool orthographic = camera.projection == Projection::orthographic;
    // The image plane's half height: at distance one from a pinhole, or in
    // metres for an orthographic camera.
    const float half_height = orthographic ? 0.5f * camera.view_height
                                           : std::tan(0.5f * glm::radians(camera.vertical_fov));
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    kernel::CameraRecord r;
    r.position = glm::vec4(camera.position, 1.0f);
    r.forward = glm::vec4(forward, orthographic ? 1.0f : 0.0f);
    r.right = glm::vec4(right, 0.0f);
    r.up = glm::vec4(up, 0.0f);
    r.extent = glm::vec4(half_height * aspect, half_height, camera.aperture_radius,
                         camera.focus_distance);
    r.size = glm::uvec4(static_cast<unsigned>(width), static_cast<unsigned>(height), 0u, 0u);
    return r;
}

}  // namespace trac0r
