// The light list that next-event estimation picks from (kernel/types.h's
// LightRecord), built when a scene is packed.
#ifndef TRAC0R_LIGHT_LIST_H
#define TRAC0R_LIGHT_LIST_H

#include "trac0r/packed_scene.h"

#include <cstdint>
#include <vector>

namespace trac0r {

// Fills packed.lights from the scene's environment and lamps and the
// packed triangles and materials (their coordinates times packed.scale
// already), with packed.environment and packed.distant_count, and sets
// T0_FEATURE_ENVIRONMENT and T0_FEATURE_LAMPS where they are used;
// packed_index maps the scene's usable triangles, in the scene's order, to
// the packed ones.
// With the light sampler's tree (T0_FEATURE_LIGHT_TREE: LightSampler::tree
// where any light has a position, or automatic from light_tree_min_lights
// of them), the tree too (light_tree.h).
void pack_lights(const Scene& scene, PackedScene& packed,
                 const std::vector<std::uint32_t>& packed_index, LightSampler sampler);

}  // namespace trac0r

#endif
