// A bounding volume hierarchy over triangles: a binary tree by binned SAH,
// collapsed at least SAH cost into the 8-wide node array both backends
// traverse (kernel/traverse.h).
#ifndef TRAC0R_BVH_H
#define TRAC0R_BVH_H

#include "trac0r/geometry.h"
#include "trac0r/kernel/types.h"

#include <cstdint>
#include <vector>

namespace trac0r {

// A leaf: `count` (1 to 4) triangles from `first` of Bvh::order.
struct BvhLeaf {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

struct Bvh {
    // Node 0 is the root. Each node has up to eight children (lanes), each
    // a node or, with count > 0, leaf `child & ~T0_BVH_LEAF` of `leaves`:
    // see kernel::BvhNode. The packer turns leaf i into TrianglePacket i.
    std::vector<kernel::BvhNode> nodes;
    std::vector<BvhLeaf> leaves;
    // order[i]: which input triangle is the i-th in leaf order.
    std::vector<std::uint32_t> order;
    int depth = 0;  // longest path from the root to a node with only leaves, in nodes
    // Collapsed by levels (three binary levels per node) because the
    // optimal collapse was too deep for the traversal stack (bvh.cpp).
    bool by_levels = false;
};

// Binned SAH (16 bins per axis; exact for 16 triangles or fewer) in
// O(n log n), down to single triangles,
// then the collapse: at most `max_leaf_size` triangles per leaf (1 to 4:
// one packet), fewer where the wide tree's SAH cost says so. Throws
// std::invalid_argument for no triangles or too many.
Bvh build_bvh(const std::vector<AABB>& triangle_bounds, int max_leaf_size = 4);

}  // namespace trac0r

#endif
