// Meshes built in code: a triangle mesh from flat arrays (positions,
// triangle indices, and optionally vertex normals and texture coordinates),
// placed in a scene as the scene format's "mesh" shape places a file. The
// Python module's Scene.add_mesh takes NumPy arrays through it.
#ifndef TRAC0R_MESH_ARRAYS_H
#define TRAC0R_MESH_ARRAYS_H

#include "trac0r/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace trac0r {

struct MeshArrays {
    std::vector<float> positions;        // x, y, z of each vertex
    std::vector<std::uint32_t> indices;  // three vertices a triangle, counter-clockwise
    std::vector<float> normals;          // none, or x, y, z of each vertex (smooth shading)
    std::vector<float> uvs;              // none, or u, v of each vertex (v up)
};

// Where a mesh goes, as a scene file's mesh shape says it (docs/scene-format.md).
struct MeshPlacement {
    std::string material;  // a material of the scene by name; "": its "default",
                           // else a grey diffuse, as for a mesh without "material"
    glm::dvec3 position{0.0};
    glm::vec3 orientation{0.0f};  // radians, about x, y, z
    glm::vec3 scale{1.0f};
};

// Adds the mesh to `scene` as one shape. Throws std::invalid_argument whose
// message names the array or argument and what was expected: a count that
// is not a multiple of 3 (2 for uvs) or differs from the vertices', an
// index past the vertices, a number that is not finite, an unknown
// material (with the scene's names), no triangle that can be rendered.
void add_mesh(Scene& scene, const MeshArrays& mesh, const MeshPlacement& placement);

}  // namespace trac0r

#endif
