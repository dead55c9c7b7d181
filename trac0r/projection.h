// Projecting world-space points and boxes onto the image: the inverse of
// camera_ray (kernel/trace.h), for drawing on top of a render (the viewer's
// AABB overlay). Pure functions of a CameraRecord from make_camera_record.
//
// Image coordinates are continuous pixels: x to the right, y down, (0, 0)
// the top-left corner of the top-left pixel, so pixel (i, j) covers
// [i, i + 1) x [j, j + 1), as the jittered camera rays sample it.
#ifndef TRAC0R_PROJECTION_H
#define TRAC0R_PROJECTION_H

#include "trac0r/geometry.h"
#include "trac0r/kernel/types.h"

#include <glm/glm.hpp>

#include <vector>

namespace trac0r {

// A point in the camera's frame: x along right, y along up, z along
// forward (the depth).
glm::vec3 to_camera_space(const kernel::CameraRecord& camera, const glm::vec3& world);

// The image position of a camera-space point; its depth z must be > 0
// (for a perspective camera).
glm::vec2 camera_space_to_image(const kernel::CameraRecord& camera, const glm::vec3& point);

// The image position of a world point, or false when the point lies closer
// than `near_distance` along the view direction (behind the camera
// included), where a perspective projection would flip or blow up.
bool project_point(const kernel::CameraRecord& camera, const glm::vec3& world, float near_distance,
                   glm::vec2* image_position);

struct Segment2 {
    glm::vec2 a;
    glm::vec2 b;
};

// Clips a 2D segment to the rectangle [0, width] x [0, height]; false when
// nothing of it is inside (Liang-Barsky).
bool clip_segment_to_image(Segment2* segment, float width, float height);

// The 12 edges of the box as image segments: each edge is clipped in 3D at
// the plane z = near_distance in front of the camera (so boxes partly behind
// the camera are drawn correctly, not across the screen), projected, and
// clipped to the image rectangle. Edges with nothing visible are left out.
std::vector<Segment2> project_aabb_wireframe(const kernel::CameraRecord& camera, const AABB& box,
                                             float near_distance);

}  // namespace trac0r

#endif
