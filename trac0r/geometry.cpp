#include "trac0r/geometry.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace trac0r {

Triangle::Triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c)
    : v0(a), v1(b), v2(c), centroid((a + b + c) / 3.0f) {
    const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a);
    const glm::dvec3 e2 = glm::dvec3(c) - glm::dvec3(a);
    const glm::dvec3 n = glm::cross(e1, e2);
    const double twice_area = glm::length(n);
    const double longest2 =
        glm::max(glm::max(glm::dot(e1, e1), glm::dot(e2, e2)), glm::dot(e2 - e1, e2 - e1));
    // Degenerate when its height over its longest edge, twice_area /
    // longest^2, is below float resolution (FLT_EPSILON = 2^-23): the third
    // vertex is within rounding of the line of the other two, as when it was
    // computed to be on it, and the normal would be rounding noise. Relative,
    // so it does not depend on the scene's scale; then area and normal are
    // zero, pack_scene drops it and the kernel never hits it.
    if (!(twice_area > static_cast<double>(FLT_EPSILON) * longest2)) {
        return;
    }
    area = static_cast<float>(0.5 * twice_area);
    normal = glm::vec3(n / twice_area);
}

AABB Triangle::bounds() const {
    AABB b;
    b.extend(v0);
    b.extend(v1);
    b.extend(v2);
    return b;
}

bool is_finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double corner_angle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 e1 = a - p;
    const glm::dvec3 e2 = b - p;
    const double l = glm::length(e1) * glm::length(e2);
    return l > 0.0 ? std::acos(std::min(1.0, std::max(-1.0, glm::dot(e1, e2) / l))) : 0.0;
}

bool usable_triangle(const Triangle& t) {
    // An area below FLT_MIN is a denormal, which a device that flushes them
    // (and the CPU backend, DenormalsAreZero) reads as 0: never hit.
    return is_finite(t.v0) && is_finite(t.v1) && is_finite(t.v2) && t.area >= FLT_MIN &&
           std::isfinite(t.area);
}

}  // namespace trac0r
