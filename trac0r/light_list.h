// The light list that next-event estimation picks from (kernel/types.h's
// LightRecord), built when a scene is packed.
#ifndef TRAC0R_LIGHT_LIST_H
#define TRAC0R_LIGHT_LIST_H

#include "trac0r/packed_scene.h"

#include <cstdint>
#include <vector>

namespace trac0r {

// Fills packed.lights from the packed triangles and materials;
// packed_index maps the scene's usable triangles, in the scene's order, to
// the packed ones.
void pack_lights(PackedScene& packed, const std::vector<std::uint32_t>& packed_index);

}  // namespace trac0r

#endif
