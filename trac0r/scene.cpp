#include "trac0r/scene.h"

#include <cmath>

namespace trac0r {

std::size_t Scene::triangle_count() const {
    std::size_t n = 0;
    for (const Shape& s : shapes) {
        n += s.triangles.size();
    }
    return n;
}

glm::dvec3 local_origin(const glm::dvec3& position) {
    const double grid = 1024.0;
    return glm::dvec3(grid * std::round(position.x / grid), grid * std::round(position.y / grid),
                      grid * std::round(position.z / grid));
}

}  // namespace trac0r
