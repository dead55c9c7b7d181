#include "trac0r/projection.h"

#include <algorithm>

namespace trac0r {

namespace {

glm::vec3 xyz(const glm::vec4& v) { return glm::vec3(v); }

// Cuts the part of the segment closer than near_distance; false when all
// of it is.
bool clip_at_near_plane(glm::vec3* a, glm::vec3* b, float near_distance) {
    const bool a_in = a->z >= near_distance;
    const bool b_in = b->z >= near_distance;
    if (!a_in && !b_in) {
        return false;
    }
    if (a_in != b_in) {
        glm::vec3& outside = a_in ? *b : *a;
        const glm::vec3& inside = a_in ? *a : *b;
        const float t = (near_distance - inside.z) / (outside.z - inside.z);
        outside = inside + t * (outside - inside);
        outside.z = near_distance;  // exactly on the plane despite rounding
    }
    return true;
}

}  // namespace

glm::vec3 to_camera_space(const kernel::CameraRecord& camera, const glm::vec3& world) {
    const glm::vec3 offset = world - xyz(camera.position);
    return glm::vec3(glm::dot(offset, xyz(camera.right)), glm::dot(offset, xyz(camera.up)),
                     glm::dot(offset, xyz(camera.forward)));
}

// camera_ray shoots forward + right * sx + up * sy with
// sx = (2 x / width - 1) * extent.x and sy = (1 - 2 y / height) * extent.y;
// a point on that ray has sx = x_cam / z_cam and sy = y_cam / z_cam. An
// orthographic camera's ray starts at right * sx + up * sy: a point on it
// has sx = x_cam and sy = y_cam.
glm::vec2 camera_space_to_image(const kernel::CameraRecord& camera, const glm::vec3& point) {
    const bool orthographic = kernel::camera_is_orthographic(camera);
    const float sx = orthographic ? point.x : point.x / point.z;
    const float sy = orthographic ? point.y : point.y / point.z;
    const float width = static_cast<float>(camera.size.x);
    const float height = static_cast<float>(camera.size.y);
    return glm::vec2(0.5f * width * (sx / camera.extent.x + 1.0f),
                     0.5f * height * (1.0f - sy / camera.extent.y));
}

bool project_point(const kernel::CameraRecord& camera, const glm::vec3& world, float near_distance,
                   glm::vec2* image_position) {
    const glm::vec3 p = to_camera_space(camera, world);
    if (!(p.z >= near_distance)) {
        return false;
    }
    *image_position = camera_space_to_image(camera, p);
    return true;
}

bool clip_segment_to_image(Segment2* segment, float width, float height) {
    const glm::vec2 d = segment->b - segment->a;
    float t0 = 0.0f;
    float t1 = 1.0f;
    // Each boundary as p * t <= q: left, right, top, bottom.
    const float p[4] = {-d.x, d.x, -d.y, d.y};
    const float q[4] = {segment->a.x, width - segment->a.x, segment->a.y, height - segment->a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0f) {
            if (q[i] < 0.0f) {
                return false;  // parallel to this boundary and outside it
            }
            continue;
        }
        const float t = q[i] / p[i];
        if (p[i] < 0.0f) {
            t0 = std::max(t0, t);
        } else {
            t1 = std::min(t1, t);
        }
        if (t0 > t1) {
            return false;
        }
    }
    const glm::vec2 a = segment->a;
    segment->a = a + t0 * d;
    segment->b = a + t1 * d;
    return true;
}

std::vector<Segment2> project_aabb_wireframe(const kernel::CameraRecord& camera, const AABB& box,
                                             float near_distance) {
    std::vector<Segment2> segments;
    if (box.empty()) {
        return segments;
    }
    // Corner i takes max on axis k when bit k of i is set; an edge joins two
    // corners that differ in one bit.
    glm::vec3 corners[8];
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 world((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                              (i & 4) ? box.max.z : box.min.z);
        corners[i] = to_camera_space(camera, world);
    }
    const float width = static_cast<float>(camera.size.x);
    const float height = static_cast<float>(camera.size.y);
    for (int i = 0; i < 8; ++i) {
        for (int bit = 1; bit < 8; bit <<= 1) {
            if (i & bit) {
                continue;  // each edge once, from its corner with the bit clear
            }
            glm::vec3 a = corners[i];
            glm::vec3 b = corners[i | bit];
            if (!clip_at_near_plane(&a, &b, near_distance)) {
                continue;
            }
            Segment2 s{camera_space_to_image(camera, a), camera_space_to_image(camera, b)};
            if (clip_segment_to_image(&s, width, height)) {
                segments.push_back(s);
            }
        }
    }
    return segments;
}

}  // namespace trac0r
