// Tangents for normal maps where a file gives none, computed from the
// texture coordinates as MikkTSpace (the convention of glTF, Blender and
// the bakers that make normal maps) computes them.
#ifndef TRAC0R_TANGENTS_H
#define TRAC0R_TANGENTS_H

#include "trac0r/shape.h"

#include <vector>

namespace trac0r {

// One VertexTangentTriple per triangle of `shape`. Each triangle's own
// tangent is its positions' derivative with respect to u, and its sign
// says whether its UV layout is mirrored (whether the derivative with
// respect to v is on the side of cross(normal, tangent) or not). At each
// corner that tangent is projected onto the plane of the corner's normal
// (its vertex normal, or the triangle's where it is flat) and normalised;
// then the corners that are one vertex (the same position, normal,
// texture coordinates and sign) share the average of their triangles'
// tangents, each weighted by its triangle's angle at the corner, as
// MikkTSpace does. A triangle without texture coordinates, or whose
// coordinates or tangents are degenerate, gets all zero (no normal map).
std::vector<VertexTangentTriple> uv_tangents(const Shape& shape);

}  // namespace trac0r

#endif
