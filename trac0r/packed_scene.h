// A scene packed once per change into the flat arrays both backends read,
// with the feature mask of what it uses.
#ifndef TRAC0R_PACKED_SCENE_H
#define TRAC0R_PACKED_SCENE_H

#include "trac0r/kernel/types.h"
#include "trac0r/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace trac0r {

struct PackedScene {
    std::vector<kernel::TriangleRecord> triangles;
    std::vector<kernel::ShapeRecord> shapes;
    std::vector<kernel::MaterialRecord> materials;
    std::uint32_t features = 0;
    std::size_t dropped_degenerate_triangles = 0;  // zero-area or non-finite

    kernel::SceneView view() const;
};

// Packs the scene: the flat structure (shapes with AABBs), triangles with
// precomputed edges, materials, and the feature mask. Degenerate triangles
// (zero area, non-finite vertices) can never be hit and are left out.
PackedScene pack_scene(const Scene& scene);

// "diffuse glass emittance flat" etc.: the names of the set bits.
std::string feature_names(std::uint32_t features);
// The names of the bits a full build has and this mask does not.
std::string left_out_feature_names(std::uint32_t features);

}  // namespace trac0r

#endif
