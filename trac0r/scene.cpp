#include "trac0r/scene.h"

namespace trac0r {

std::size_t Scene::triangle_count() const {
    std::size_t n = 0;
    for (const Shape& s : shapes) {
        n += s.triangles.size();
    }
    return n;
}

}  // namespace trac0r
