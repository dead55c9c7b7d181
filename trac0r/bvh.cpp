#include "trac0r/bvh.h"

#include "trac0r/kernel/intersect.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

namespace trac0r {

namespace {

const int bin_count = 16;
// Below this depth splits follow the SAH; deeper (only in pathological
// inputs) they halve the list, so no path is longer than about this plus
// log2(n) nodes and the kernel's fixed traversal stack always suffices.
const int sah_depth_limit = 32;
// Relative costs, for the SAH, of a binary node and of testing a packet of
// up to four triangles: 1 : 4, chosen when nodes were 4-wide (a binary node
// half a wide node, a packet test about two wide nodes' instructions). On
// cornell.json, against 1 : 2, it splits pairs of walls that shared a
// room-sized leaf box: 0.7 fewer packet tests per ray for 0.4 more nodes,
// and 7 % fewer instructions a ray (README, "Performance"). With 8-wide
// nodes (a binary node a third of one), 1 : 6 to 1 : 12 give the same
// packet tests a bounce ray (1.62 to 1.63) and a few more nodes (2.22 to
// 2.23 against 2.20), 1 : 2 many more packet tests (2.50): 1 : 4 stays.
const float traversal_cost = 0.5f;
const float intersection_cost = 2.0f;

float surface_area(const AABB& b) {
    if (b.empty()) {
        return 0.0f;
    }
    const glm::vec3 d = b.max - b.min;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// A node of the binary tree the SAH builds, before it is collapsed into
// 8-wide nodes: an interior node's children are at first and first + 1,
// a leaf holds count triangles from first.
struct BinaryNode {
    AABB bounds;
    std::uint32_t first = 0;
    std::uint32_t count = 0;  // 0: interior
};

struct BuildItem {
    AABB bounds;
    glm::vec3 centroid;
    std::uint32_t index;
};

struct Split {
    int axis = -1;
    float position = 0.0f;  // centroid coordinate: left is < position
    float cost = 0.0f;
};

class Builder {
  public:
    Builder(std::vector<BuildItem> items, int max_leaf_size)
        : items_(std::move(items)), max_leaf_(max_leaf_size) {}

    // The binary tree (node 0 the root) and, in `order`, the items in leaf
    // order.
    std::vector<BinaryNode> build(std::vector<std::uint32_t>& order) {
        nodes_.reserve(2 * items_.size() / static_cast<std::size_t>(std::max(1, max_leaf_ / 2)) +
                       1);
        nodes_.emplace_back();
        build_node(0, 0, items_.size(), 1);
        order.clear();
        order.reserve(items_.size());
        for (const BuildItem& item : items_) {
            order.push_back(item.index);
        }
        return std::move(nodes_);
    }

  private:
    void set_node(std::size_t node, const AABB& bounds, std::uint32_t first, std::uint32_t count) {
        nodes_[node].bounds = bounds;
        nodes_[node].first = first;
        nodes_[node].count = count;
    }

    // The best binned SAH split of [begin, end), or axis -1 when no split
    // is possible (all centroids in one point).
    Split find_split(std::size_t begin, std::size_t end, const AABB& centroid_bounds) const {
        Split best;
        best.cost = std::numeric_limits<float>::max();
        for (int axis = 0; axis < 3; ++axis) {
            const float lo = centroid_bounds.min[axis];
            const float extent = centroid_bounds.max[axis] - lo;
            if (!(extent > 0.0f)) {
                continue;
            }
            AABB bins[bin_count];
            int counts[bin_count] = {};
            const float scale = bin_count / extent;
            for (std::size_t i = begin; i < end; ++i) {
                const int b = bin_of(items_[i].centroid[axis], lo, scale);
                bins[b].extend(items_[i].bounds);
                ++counts[b];
            }
            // Sweep from the right for the right-hand areas, then from the left.
            float right_area[bin_count];
            int right_count[bin_count];
            AABB acc;
            int n = 0;
            for (int b = bin_count - 1; b > 0; --b) {
                acc.extend(bins[b]);
                n += counts[b];
                right_area[b] = surface_area(acc);
                right_count[b] = n;
            }
            acc = AABB();
            n = 0;
            for (int b = 0; b < bin_count - 1; ++b) {
                acc.extend(bins[b]);
                n += counts[b];
                if (n == 0 || right_count[b + 1] == 0) {
                    continue;
                }
                const float cost = surface_area(acc) * packets(n) +
                                   right_area[b + 1] * packets(right_count[b + 1]);
                if (cost < best.cost) {
                    best.cost = cost;
                    best.axis = axis;
                    best.position = lo + (b + 1) / scale;
                }
            }
        }
        return best;
    }

    // What intersecting n triangles costs: one packet test per four.
    static float packets(std::size_t n) { return static_cast<float>((n + 3) / 4); }

    static int bin_of(float c, float lo, float scale) {
        const int b = static_cast<int>((c - lo) * scale);
        return std::min(std::max(b, 0), bin_count - 1);
    }

    void build_node(std::size_t node, std::size_t begin, std::size_t end, int depth) {
        AABB bounds;
        AABB centroid_bounds;
        for (std::size_t i = begin; i < end; ++i) {
            bounds.extend(items_[i].bounds);
            centroid_bounds.extend(items_[i].centroid);
        }
        const std::size_t count = end - begin;
        if (depth >= sah_depth_limit && count > static_cast<std::size_t>(max_leaf_)) {
            return median_split(node, bounds, centroid_bounds, begin, end, depth);
        }
        const Split split = count > 1 ? find_split(begin, end, centroid_bounds) : Split();
        const float leaf_cost = intersection_cost * packets(count);
        const float split_cost =
            split.axis < 0 ? leaf_cost
                           : traversal_cost + intersection_cost * split.cost / surface_area(bounds);
        const bool must_split = count > static_cast<std::size_t>(max_leaf_);
        if (split.axis < 0 && must_split) {
            // Every centroid in one point: split the list in the middle.
            return make_children(node, bounds, begin, begin + count / 2, end, depth);
        }
        if (split.axis < 0 || (!must_split && split_cost >= leaf_cost)) {
            set_node(node, bounds, static_cast<std::uint32_t>(begin),
                     static_cast<std::uint32_t>(count));
            return;
        }
        const auto middle = std::partition(
            items_.begin() + static_cast<std::ptrdiff_t>(begin),
            items_.begin() + static_cast<std::ptrdiff_t>(end),
            [&](const BuildItem& it) { return it.centroid[split.axis] < split.position; });
        std::size_t mid = static_cast<std::size_t>(middle - items_.begin());
        if (mid == begin || mid == end) {
            mid = begin + count / 2;  // rounding put everything on one side
        }
        make_children(node, bounds, begin, mid, end, depth);
    }

    void median_split(std::size_t node, const AABB& bounds, const AABB& centroid_bounds,
                      std::size_t begin, std::size_t end, int depth) {
        const glm::vec3 extent = centroid_bounds.max - centroid_bounds.min;
        const int axis =
            extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const std::size_t mid = begin + (end - begin) / 2;
        std::nth_element(items_.begin() + static_cast<std::ptrdiff_t>(begin),
                         items_.begin() + static_cast<std::ptrdiff_t>(mid),
                         items_.begin() + static_cast<std::ptrdiff_t>(end),
                         [axis](const BuildItem& a, const BuildItem& b) {
                             return a.centroid[axis] < b.centroid[axis];
                         });
        make_children(node, bounds, begin, mid, end, depth);
    }

    void make_children(std::size_t node, const AABB& bounds, std::size_t begin, std::size_t mid,
                       std::size_t end, int depth) {
        const std::size_t left = nodes_.size();
        nodes_.emplace_back();
        nodes_.emplace_back();
        set_node(node, bounds, static_cast<std::uint32_t>(left), 0u);
        build_node(left, begin, mid, depth + 1);
        build_node(left + 1, mid, end, depth + 1);
    }

    std::vector<BuildItem> items_;
    std::vector<BinaryNode> nodes_;
    int max_leaf_;
};

// Lane `lane` of plane `plane` of a node (the layout kernel::node_plane reads).
void set_node_plane(kernel::BvhNode& n, int plane, int lane, float value) {
    n.bounds[2 * plane + lane / 4][lane % 4] = value;
}

// Collapses the binary tree into 8-wide nodes. Greedy: a wide node starts
// from its binary node and opens the interior lane of largest surface area
// (the one most rays enter) into its two children until it has eight lanes
// or only leaves. Or by levels: a wide node's lanes are the binary nodes
// three levels below one (or above, where a leaf comes first), so each wide
// level takes three binary levels, which bounds the depth on any input.
class Collapser {
  public:
    Collapser(const std::vector<BinaryNode>& binary, bool greedy)
        : binary_(binary), greedy_(greedy) {}

    void collapse(Bvh& bvh) {
        wide_.emplace_back();
        bvh.depth = fill(0, 0);
        bvh.nodes = std::move(wide_);
        bvh.leaves = std::move(leaves_);
    }

  private:
    // The lanes of the wide node made from binary node b: lanes[0..count).
    int choose_lanes(std::uint32_t b, std::uint32_t* lanes) const {
        int lane_count = 0;
        lanes[lane_count++] = b;
        if (greedy_) {
            while (lane_count < T0_BVH_WIDTH) {
                int widest = -1;
                float widest_area = -1.0f;
                for (int i = 0; i < lane_count; ++i) {
                    const BinaryNode& n = binary_[lanes[i]];
                    if (n.count == 0 && surface_area(n.bounds) > widest_area) {
                        widest = i;
                        widest_area = surface_area(n.bounds);
                    }
                }
                if (widest < 0) {
                    break;  // only leaves
                }
                const std::uint32_t first = binary_[lanes[widest]].first;
                lanes[widest] = first;
                lanes[lane_count++] = first + 1;
            }
            return lane_count;
        }
        // 2^3 = T0_BVH_WIDTH: each round opens every interior lane.
        for (int level = 0; level < 3; ++level) {
            const int before = lane_count;
            for (int i = 0; i < before; ++i) {
                const BinaryNode& n = binary_[lanes[i]];
                if (n.count == 0) {
                    lanes[i] = n.first;
                    lanes[lane_count++] = n.first + 1;
                }
            }
        }
        return lane_count;
    }

    // Fills wide node `wide` from binary node `b`; returns the depth of the
    // wide subtree, in nodes.
    int fill(std::size_t wide, std::uint32_t b) {
        std::uint32_t lanes[T0_BVH_WIDTH];
        const int lane_count = choose_lanes(b, lanes);
        kernel::BvhNode node;
        for (int plane = 0; plane < 6; ++plane) {
            // Even planes are minima: +FLT_MAX, and maxima -FLT_MAX, unused.
            const float unused = plane % 2 == 0 ? std::numeric_limits<float>::max()
                                                : -std::numeric_limits<float>::max();
            node.bounds[2 * plane] = glm::vec4(unused);
            node.bounds[2 * plane + 1] = glm::vec4(unused);
        }
        node.child[0] = node.child[1] = glm::uvec4(0u);
        node.count[0] = node.count[1] = glm::uvec4(0u);
        std::vector<std::pair<int, std::uint32_t>> interior;  // (lane, binary node)
        for (int i = 0; i < lane_count; ++i) {
            const BinaryNode& n = binary_[lanes[i]];
            for (int axis = 0; axis < 3; ++axis) {
                set_node_plane(node, 2 * axis, i, n.bounds.min[axis]);
                set_node_plane(node, 2 * axis + 1, i, n.bounds.max[axis]);
            }
            if (n.count > 0) {
                node.child[i / 4][i % 4] = T0_BVH_LEAF | static_cast<std::uint32_t>(leaves_.size());
                node.count[i / 4][i % 4] = n.count;
                leaves_.push_back(BvhLeaf{n.first, n.count});
            } else {
                interior.emplace_back(i, lanes[i]);
            }
        }
        // Children nodes side by side, then their subtrees.
        const std::size_t first_child = wide_.size();
        wide_.resize(wide_.size() + interior.size());
        int depth = 1;
        for (std::size_t k = 0; k < interior.size(); ++k) {
            const int i = interior[k].first;
            node.child[i / 4][i % 4] = static_cast<std::uint32_t>(first_child + k);
            depth = std::max(depth, 1 + fill(first_child + k, interior[k].second));
        }
        wide_[wide] = node;
        return depth;
    }

    const std::vector<BinaryNode>& binary_;
    bool greedy_;
    std::vector<kernel::BvhNode> wide_;
    std::vector<BvhLeaf> leaves_;
};

}  // namespace

Bvh build_bvh(const std::vector<AABB>& triangle_bounds, int max_leaf_size) {
    if (triangle_bounds.empty()) {
        throw std::invalid_argument("build_bvh: no triangles");
    }
    if (triangle_bounds.size() > 0xffffffffu / 2) {
        throw std::invalid_argument("build_bvh: too many triangles");
    }
    std::vector<BuildItem> items;
    items.reserve(triangle_bounds.size());
    for (std::size_t i = 0; i < triangle_bounds.size(); ++i) {
        items.push_back(
            {triangle_bounds[i], triangle_bounds[i].center(), static_cast<std::uint32_t>(i)});
    }
    Bvh bvh;
    const int leaf_size = std::min(std::max(1, max_leaf_size), 4);  // one packet
    const std::vector<BinaryNode> binary = Builder(std::move(items), leaf_size).build(bvh.order);
    // The traversal stack holds at most seven entries per level, and one
    // more for a moment (kernel/intersect.h). A greedy tree may be as deep
    // as the binary one; where that is too deep, the collapse by levels
    // divides the depth by three.
    Collapser(binary, true).collapse(bvh);
    if (7 * bvh.depth + 1 > T0_BVH_STACK_SIZE) {
        Collapser(binary, false).collapse(bvh);
        bvh.by_levels = true;
    }
    if (7 * bvh.depth + 1 > T0_BVH_STACK_SIZE) {
        throw std::runtime_error("build_bvh: tree too deep for the traversal stack");
    }
    return bvh;
}

}  // namespace trac0r
