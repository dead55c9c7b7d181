// A bounding volume hierarchy over triangles: binned SAH build, flattened
// into the node array both backends traverse (kernel/intersect.h).
#ifndef TRAC0R_BVH_H
#define TRAC0R_BVH_H

#include "trac0r/geometry.h"
#include "trac0r/kernel/types.h"

#include <cstdint>
#include <vector>

namespace trac0r {

struct Bvh {
    // Node 0 is the root. An interior node's children are adjacent, at
    // `first` and `first + 1`; a leaf holds `count` triangles from `first`
    // of `order`. See kernel::BvhNode for the packed form.
    std::vector<kernel::BvhNode> nodes;
    // order[i]: which input triangle is the i-th in leaf order.
    std::vector<std::uint32_t> order;
    int depth = 0;  // longest root-to-leaf path, in nodes
};

// Binned SAH (16 bins per axis) in O(n log n). At most `max_leaf_size`
// triangles per leaf; fewer where the SAH says a split does not pay.
Bvh build_bvh(const std::vector<AABB>& triangle_bounds, int max_leaf_size = 4);

// Reads a packed node's fields.
std::uint32_t bvh_node_first(const kernel::BvhNode& node);
std::uint32_t bvh_node_count(const kernel::BvhNode& node);  // 0: interior

}  // namespace trac0r

#endif
