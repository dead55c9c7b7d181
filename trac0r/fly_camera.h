// Moving a camera the way a first-person ("fly") viewer does: the viewer's
// navigation keys and mouse-look, kept here as pure functions so they can
// be tested and can never produce a camera that camera_problem() rejects.
#ifndef TRAC0R_FLY_CAMERA_H
#define TRAC0R_FLY_CAMERA_H

#include "trac0r/camera.h"

#include <glm/glm.hpp>

namespace trac0r {

// The closest the view direction may come to world_up (or its opposite), in
// radians. Nearer, the image's 'right' (cross(direction, world_up)) becomes
// ill-defined and mouse-look would spin.
constexpr float fly_camera_min_pole_angle = 0.02f;  // about 1 degree

// The field of view the wheel may reach, in degrees.
constexpr float fly_camera_min_fov = 1.0f;
constexpr float fly_camera_max_fov = 170.0f;

// Translates by `local` in the camera's frame: x along image right, y along
// world_up (so up/down keys move level, whatever the pitch), z along the
// view direction.
Camera move_camera(const Camera& camera, const glm::vec3& local);

// Turns the view: yaw about world_up (positive turns right), then pitch
// about image right (positive looks up), clamped to keep
// fly_camera_min_pole_angle from world_up.
Camera turn_camera(const Camera& camera, float yaw_radians, float pitch_radians);

// Multiplies the vertical field of view by `factor`, clamped to
// [fly_camera_min_fov, fly_camera_max_fov]; an orthographic camera's
// view_height instead, where the product stays finite and positive.
Camera zoom_camera(const Camera& camera, float factor);

}  // namespace trac0r

#endif
