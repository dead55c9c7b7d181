// Vertex normals from OBJ smoothing groups (`s 1`, `s off`), for files
// that give none (`vn`): the shading their authors' programs show.
#ifndef TRAC0R_SMOOTHING_GROUPS_H
#define TRAC0R_SMOOTHING_GROUPS_H

#include "trac0r/shape.h"

#include <array>
#include <cstdint>
#include <vector>

namespace trac0r {

// A triangle by its vertices' indices, in its smoothing group (0: none,
// `s off` or `s 0`: flat).
struct GroupedTriangle {
    std::array<std::uint32_t, 3> vertex;
    std::uint32_t group = 0;
};

// Per triangle, the normals at its corners: at each, the mean of the unit
// normals of the triangles of its group that share the vertex, each
// weighted by its angle there (as Blender and 3ds Max smooth); all zero
// (flat) for group 0, and where the mean cancels or a triangle has no
// area. `positions` are the vertices the indices name (each in range).
std::vector<VertexNormalTriple> smoothing_group_normals(
    const std::vector<glm::vec3>& positions, const std::vector<GroupedTriangle>& triangles);

}  // namespace trac0r

#endif
