#include "trac0r/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace trac0r {

namespace {

struct Frame {
    glm::vec3 forward;
    glm::vec3 right;
    glm::vec3 up;  // world_up, normalised
};

Frame frame_of(const Camera& camera) {
    Frame f;
    f.forward = glm::normalize(camera.direction);
    f.up = glm::normalize(camera.world_up);
    f.right = glm::normalize(glm::cross(f.forward, f.up));
    return f;
}

}  // namespace

Camera move_camera(const Camera& camera, const glm::vec3& local) {
    const Frame f = frame_of(camera);
    Camera moved = camera;
    moved.position += local.x * f.right + local.y * f.up + local.z * f.forward;
    return moved;
}

Camera turn_camera(const Camera& camera, float yaw_radians, float pitch_radians) {
    const Frame f = frame_of(camera);
    // Elevation above the horizontal plane, and the heading within it; the
    // heading is well defined because the direction is never along world_up.
    const float elevation = std::asin(std::max(-1.0f, std::min(1.0f, glm::dot(f.forward, f.up))));
    const glm::vec3 heading = glm::normalize(f.forward - glm::dot(f.forward, f.up) * f.up);
    // Yaw about world_up: heading turns towards right for positive angles.
    const glm::vec3 turned = std::cos(yaw_radians) * heading + std::sin(yaw_radians) * f.right;
    const float max_elevation = 0.5f * 3.14159265f - fly_camera_min_pole_angle;
    const float new_elevation =
        std::max(-max_elevation, std::min(max_elevation, elevation + pitch_radians));
    Camera result = camera;
    result.direction =
        glm::normalize(std::cos(new_elevation) * turned + std::sin(new_elevation) * f.up);
    return result;
}

Camera zoom_camera(const Camera& camera, float factor) {
    Camera result = camera;
    if (camera.projection == Projection::orthographic) {
        result.view_height = camera.view_height * factor;
        return camera_problem(result) == nullptr ? result : camera;
    }
    result.vertical_fov =
        std::max(fly_camera_min_fov, std::min(fly_camera_max_fov, camera.vertical_fov * factor));
    return result;
}

}  // namespace trac0r
