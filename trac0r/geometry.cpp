#include "trac0r/geometry.h"

namespace trac0r {

Triangle::Triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c)
    : v0(a), v1(b), v2(c), centroid((a + b + c) / 3.0f) {
    const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a);
    const glm::dvec3 e2 = glm::dvec3(c) - glm::dvec3(a);
    const glm::dvec3 n = glm::cross(e1, e2);
    const double twice_area = glm::length(n);
    area = static_cast<float>(0.5 * twice_area);
    normal = twice_area > 0.0 ? glm::vec3(n / twice_area) : glm::vec3(0.0f);
}

AABB Triangle::bounds() const {
    AABB b;
    b.extend(v0);
    b.extend(v1);
    b.extend(v2);
    return b;
}

}  // namespace trac0r
