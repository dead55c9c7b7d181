// Host geometry: axis-aligned boxes and triangles.
#ifndef TRAC0R_GEOMETRY_H
#define TRAC0R_GEOMETRY_H

#include <glm/glm.hpp>

#include <limits>

namespace trac0r {

struct AABB {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};

    void extend(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const AABB& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    glm::vec3 center() const { return 0.5f * (min + max); }
};

// A triangle with its normal (from the winding v0 -> v1 -> v2), centroid and
// area precomputed. The area is computed in double so that needle-thin
// triangles are told from degenerate ones: those whose height is below
// FLT_EPSILON of their longest edge get area 0 and normal 0 (geometry.cpp).
struct Triangle {
    glm::vec3 v0, v1, v2;
    glm::vec3 normal{0.0f};
    glm::vec3 centroid{0.0f};
    float area = 0.0f;

    Triangle() = default;
    Triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
    AABB bounds() const;
};

// Whether every component of v is finite.
bool is_finite(const glm::vec3& v);

// The angle (radians) at corner p of the triangle p, a, b; 0 where an
// edge there has no length. For weighting a corner's share of a vertex
// normal (smoothing_groups.h, auto_smooth.h).
double corner_angle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b);

// Whether the renderer can use t: finite vertices and a finite area of at
// least FLT_MIN (not a denormal). pack_scene leaves the others out (and
// counts them); the scene loader refuses a shape that has none left.
bool usable_triangle(const Triangle& t);

}  // namespace trac0r

#endif
