// Building the light tree (kernel/light_tree.h) over a packed scene's
// lights that have a position: emitting triangles, point and spot lamps.
#ifndef TRAC0R_LIGHT_TREE_H
#define TRAC0R_LIGHT_TREE_H

#include "trac0r/packed_scene.h"

namespace trac0r {

// Fills packed.light_nodes over packed.lights from packed.distant_count
// on, and writes each light's path in the tree (LightRecord ids.z). The
// lights' peak intensity (W/sr; a surface's along its normal) is
// `intensity`, by light index. Split at the median of the
// lights' centres along the widest axis: at most 32 levels for up to 2^32
// lights, as the paths' 32 bits need.
void build_light_tree(PackedScene& packed, const std::vector<double>& intensity);

}  // namespace trac0r

#endif
