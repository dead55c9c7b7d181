// Vertex normals by angle, for meshes whose files give neither normals nor
// smoothing groups: Blender's "auto smooth" (a mesh's "smooth_angle").
#ifndef TRAC0R_AUTO_SMOOTH_H
#define TRAC0R_AUTO_SMOOTH_H

#include "trac0r/shape.h"

#include <vector>

namespace trac0r {

// Gives each triangle of `shapes` that has no vertex normals (all zero, or
// a shape without any) normals at its corners: the angle-weighted mean of
// the normals of the triangles without normals that share the corner's
// position (in any of the shapes, as a mesh's parts by material share
// their edges) and whose normal is within `degrees` of its own; so an edge
// between faces at a sharper angle stays sharp. Triangles with normals
// keep them and take no part. `degrees` in [0, 180].
void auto_smooth(std::vector<Shape>& shapes, float degrees);

}  // namespace trac0r

#endif
