#include "trac0r/bvh.h"

#include "trac0r/kernel/traverse.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace trac0r {

namespace {

const int bin_count = 16;
// Below this depth splits follow the SAH; deeper (only in pathological
// inputs) they halve the list, so no path is longer than about this plus
// log2(n) nodes and the kernel's fixed traversal stack always suffices.
const int sah_depth_limit = 32;
// What the collapse (Collapser) weighs, per unit of surface area: an 8-wide
// node's test and a packet's. On cornell.json ratios from 1 : 4 to 4 : 1
// give trees within 1 % of each other in packets and nodes a ray (an
// instrumented copy of traverse_bvh), so the simplest stays.
const float node_cost = 1.0f;
const float packet_cost = 1.0f;

// In double: a float area overflows for boxes wider than about 1e19, and
// infinite costs would all tie; in double the SAH is the same at every
// scale (exactly so under scaling by a power of two).
double surface_area(const AABB& b) {
    if (b.empty()) {
        return 0.0;
    }
    const glm::dvec3 d = glm::dvec3(b.max) - glm::dvec3(b.min);
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// A node of the binary tree the SAH builds, down to single triangles,
// before it is collapsed into 8-wide nodes: an interior node's children are
// at first and first + 1 (after it in the array), a leaf holds the
// triangle at first (count 1).
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
    double cost = 0.0;
};

// The binary tree by binned SAH, split down to single triangles: which of
// its subtrees become leaves (packets of up to four) is the collapse's
// choice, made with the wide nodes' costs.
class Builder {
  public:
    explicit Builder(std::vector<BuildItem> items) : items_(std::move(items)) {}

    // The binary tree (node 0 the root) and, in `order`, the items in leaf
    // order.
    std::vector<BinaryNode> build(std::vector<std::uint32_t>& order) {
        nodes_.reserve(2 * items_.size());
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
    // The best binned SAH split of [begin, end), or axis -1 when no split
    // is possible (all centroids in one point). The cost: each side's
    // surface area times its triangles. (Counting packets of four instead,
    // as when the binary tree's leaves were the wide tree's, makes the
    // tree jump with the bin count: on cornell.json 1.44 packets a bounce
    // ray with 16 bins, 2.53 with 32.)
    Split find_split(std::size_t begin, std::size_t end, const AABB& centroid_bounds) const {
        if (end - begin <= static_cast<std::size_t>(bin_count)) {
            return find_split_exact(begin, end);
        }
        Split best;
        best.cost = std::numeric_limits<double>::max();
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
            double cost = 0.0;
            const int cut = cheapest_cut(
                bins, counts, bin_count, [](int) { return true; }, &cost);
            if (cut > 0 && cost < best.cost) {
                best.cost = cost;
                best.axis = axis;
                best.position = lo + cut / scale;
            }
        }
        return best;
    }

    // The same for at most bin_count items, exactly: every split between
    // two centroids in turn on each axis (cheaper than binning so few, and
    // most of the tree's nodes are this small).
    Split find_split_exact(std::size_t begin, std::size_t end) const {
        Split best;
        best.cost = std::numeric_limits<double>::max();
        const int count = static_cast<int>(end - begin);
        std::uint32_t sorted[bin_count];
        AABB boxes[bin_count];
        int ones[bin_count];  // one triangle an item
        std::fill(ones, ones + bin_count, 1);
        for (int axis = 0; axis < 3; ++axis) {
            for (int i = 0; i < count; ++i) {
                sorted[i] = static_cast<std::uint32_t>(begin) + static_cast<std::uint32_t>(i);
            }
            std::sort(sorted, sorted + count, [&](std::uint32_t a, std::uint32_t b) {
                return items_[a].centroid[axis] < items_[b].centroid[axis];
            });
            for (int i = 0; i < count; ++i) {
                boxes[i] = items_[sorted[i]].bounds;
            }
            // A split must put items with the same centroid on one side.
            auto centroid = [&](int i) { return items_[sorted[i]].centroid[axis]; };
            double cost = 0.0;
            const int cut = cheapest_cut(
                boxes, ones, count, [&](int i) { return centroid(i - 1) < centroid(i); }, &cost);
            if (cut > 0 && cost < best.cost) {
                best.cost = cost;
                best.axis = axis;
                best.position = centroid(cut);  // left: centroids below it
            }
        }
        return best;
    }

    // The cheapest cut of `count` (at most bin_count) buckets in a row along
    // an axis, bucket i the box boxes[i] of triangles[i] triangles, into a
    // left and a right side, each costing its surface area times its
    // triangles: the right side's first bucket (1 to count - 1; the first
    // of equal costs), its cost in *cost, or 0 where no cut leaves
    // triangles on both sides with allowed(first bucket).
    template <typename Allowed>
    static int cheapest_cut(const AABB* boxes, const int* triangles, int count, Allowed allowed,
                            double* cost) {
        // Sweep from the right for the right-hand areas, then from the left.
        double right_area[bin_count];
        int right_triangles[bin_count];
        AABB acc;
        int n = 0;
        for (int i = count - 1; i > 0; --i) {
            acc.extend(boxes[i]);
            n += triangles[i];
            right_area[i] = surface_area(acc);
            right_triangles[i] = n;
        }
        acc = AABB();
        n = 0;
        int best = 0;
        for (int i = 1; i < count; ++i) {
            acc.extend(boxes[i - 1]);
            n += triangles[i - 1];
            if (n == 0 || right_triangles[i] == 0 || !allowed(i)) {
                continue;
            }
            const double c = surface_area(acc) * n + right_area[i] * right_triangles[i];
            if (best == 0 || c < *cost) {
                *cost = c;
                best = i;
            }
        }
        return best;
    }

    // Clamped before the conversion, which is undefined for NaN and for
    // floats out of int's range (an extent near 0 or above FLT_MAX makes
    // scale infinite or 0).
    static int bin_of(float c, float lo, float scale) {
        const float f = (c - lo) * scale;
        return f > 0.0f ? (f < static_cast<float>(bin_count) ? static_cast<int>(f) : bin_count - 1)
                        : 0;
    }

    void build_node(std::size_t node, std::size_t begin, std::size_t end, int depth) {
        AABB bounds;
        AABB centroid_bounds;
        for (std::size_t i = begin; i < end; ++i) {
            bounds.extend(items_[i].bounds);
            centroid_bounds.extend(items_[i].centroid);
        }
        const std::size_t count = end - begin;
        if (count == 1) {
            set_node(node, bounds, static_cast<std::uint32_t>(begin), 1u);
            return;
        }
        if (depth >= sah_depth_limit) {
            return median_split(node, bounds, centroid_bounds, begin, end, depth);
        }
        const Split split = find_split(begin, end, centroid_bounds);
        if (split.axis < 0) {
            // Every centroid in one point: split the list in the middle.
            return make_children(node, bounds, begin, begin + count / 2, end, depth);
        }
        if (!(split.cost > 0.0)) {
            // No area to tell the splits apart (boxes without area, as of
            // points on a line; the first would win every time, and the
            // tree would be a spine): halve along the centroids' widest
            // axis.
            return median_split(node, bounds, centroid_bounds, begin, end, depth);
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

    void set_node(std::size_t node, const AABB& bounds, std::uint32_t first, std::uint32_t count) {
        nodes_[node].bounds = bounds;
        nodes_[node].first = first;
        nodes_[node].count = count;
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
};

// Lane `lane` of plane `plane` of a node (the layout kernel::node_plane reads).
void set_node_plane(kernel::BvhNode& n, int plane, int lane, float value) {
    n.bounds[2 * plane + lane / 4][lane % 4] = value;
}

// Collapses the binary tree into 8-wide nodes whose leaves are packets of
// up to max_leaf triangles. Optimal: the wide tree of least SAH cost that
// the binary tree's subtrees can make (Ylitie, Karras and Laine 2017,
// "Efficient incoherent ray traversal on GPUs through compressed wide
// BVHs", section 4.1): by dynamic programming from the leaves up, each
// binary subtree becomes a wide node, a leaf or several lanes of its
// parent, whichever costs least. Or by levels: a wide node's lanes are the
// binary nodes three levels below one (or above, where a subtree fits in a
// leaf), so each wide level takes three binary levels, which bounds the
// depth on any input.
class Collapser {
  public:
    Collapser(const std::vector<BinaryNode>& binary, bool optimal, int max_leaf)
        : binary_(binary), optimal_(optimal), max_leaf_(static_cast<std::uint32_t>(max_leaf)) {
        const std::size_t count = binary_.size();
        first_.assign(count, 0);
        count_.assign(count, 0);
        // Children come after their parents in the array.
        for (std::size_t m = count; m-- > 0;) {
            const BinaryNode& b = binary_[m];
            first_[m] = b.count > 0 ? b.first : first_[b.first];
            count_[m] = b.count > 0 ? b.count : count_[b.first] + count_[b.first + 1];
        }
        if (optimal_) {
            plan();
        }
    }

    void collapse(Bvh& bvh) {
        wide_.emplace_back();
        bvh.depth = fill(0, 0);
        bvh.nodes = std::move(wide_);
        bvh.leaves = std::move(leaves_);
    }

  private:
    struct Lane {
        std::uint32_t b;  // binary node
        bool leaf;        // its subtree's triangles as one packet
    };

    bool fits_leaf(std::uint32_t b) const { return count_[b] <= max_leaf_; }

    // cost(n, i): the least SAH cost (area-weighted node and packet tests)
    // of binary node n's subtree as at most i lanes (1 to 8) of a wide node.
    float& cost(std::uint32_t n, int i) {
        return cost_[T0_BVH_WIDTH * std::size_t{n} + static_cast<std::size_t>(i - 1)];
    }
    // How that cost is had: for i = 1, 1 as a leaf, 0 as a wide node; for
    // i > 1, 0 as with i - 1 lanes, else k: k lanes to the left child's
    // subtree, i - k to the right one's.
    std::uint8_t& how(std::uint32_t n, int i) {
        return how_[T0_BVH_WIDTH * std::size_t{n} + static_cast<std::size_t>(i - 1)];
    }

    void plan() {
        const std::size_t count = binary_.size();
        cost_.assign(T0_BVH_WIDTH * count, 0.0f);
        how_.assign(T0_BVH_WIDTH * count, 0);
        lanes_split_.assign(count, 0);
        const float infinite = std::numeric_limits<float>::infinity();
        // Areas over the root's (0 to 1), so that float costs suffice, and
        // at least min_area: where boxes have no area (points, segments, a
        // scene in one plane's line), or one that underflows, costs would
        // all tie at 0 and ties take fewer lanes, two a node, as deep as the
        // binary tree; with the floor, such subtrees take the fewest node
        // and packet tests.
        const double root_area = surface_area(binary_[0].bounds);
        const double area_scale = root_area > 0.0 ? 1.0 / root_area : 0.0;
        const double min_area = std::ldexp(1.0, -100);
        for (std::size_t m = count; m-- > 0;) {
            const std::uint32_t n = static_cast<std::uint32_t>(m);
            const BinaryNode& b = binary_[n];
            const float area =
                static_cast<float>(std::max(surface_area(b.bounds) * area_scale, min_area));
            const float as_leaf = fits_leaf(n) ? area * packet_cost : infinite;
            if (b.count > 0) {
                for (int i = 1; i <= T0_BVH_WIDTH; ++i) {
                    cost(n, i) = as_leaf;
                    how(n, i) = i == 1 ? 1 : 0;
                }
                continue;
            }
            // split[j]: the subtree as j lanes, k of them the left child's.
            float split[T0_BVH_WIDTH + 1];
            std::uint8_t split_k[T0_BVH_WIDTH + 1];
            for (int j = 2; j <= T0_BVH_WIDTH; ++j) {
                split[j] = infinite;
                split_k[j] = 1;
                for (int k = 1; k < j; ++k) {
                    const float c = cost(b.first, k) + cost(b.first + 1, j - k);
                    if (c < split[j]) {
                        split[j] = c;
                        split_k[j] = static_cast<std::uint8_t>(k);
                    }
                }
            }
            lanes_split_[n] = split_k[T0_BVH_WIDTH];
            const float as_node = area * node_cost + split[T0_BVH_WIDTH];
            const bool leaf = fits_leaf(n) && as_leaf <= as_node;
            cost(n, 1) = leaf ? as_leaf : as_node;
            how(n, 1) = leaf ? 1 : 0;
            for (int i = 2; i <= T0_BVH_WIDTH; ++i) {
                const bool fewer = !(split[i] < cost(n, i - 1));
                cost(n, i) = fewer ? cost(n, i - 1) : split[i];
                how(n, i) = fewer ? 0 : split_k[i];
            }
        }
    }

    // Appends the lanes that binary node n's subtree makes with `budget`.
    void gather(std::uint32_t n, int budget, Lane* lanes, int& lane_count) {
        while (budget > 1 && how(n, budget) == 0) {
            --budget;
        }
        if (budget == 1) {
            lanes[lane_count++] = Lane{n, how(n, 1) == 1};
            return;
        }
        const int k = how(n, budget);
        gather(binary_[n].first, k, lanes, lane_count);
        gather(binary_[n].first + 1, budget - k, lanes, lane_count);
    }

    // The lanes of the wide node made from binary node b: lanes[0..count).
    int choose_lanes(std::uint32_t b, Lane* lanes) {
        int lane_count = 0;
        if (b == 0 && fits_leaf(0)) {
            lanes[lane_count++] = Lane{0, true};  // the whole scene in one packet
            return lane_count;
        }
        if (optimal_) {
            const int k = lanes_split_[b];
            gather(binary_[b].first, k, lanes, lane_count);
            gather(binary_[b].first + 1, T0_BVH_WIDTH - k, lanes, lane_count);
            return lane_count;
        }
        lanes[lane_count++] = Lane{binary_[b].first, fits_leaf(binary_[b].first)};
        lanes[lane_count++] = Lane{binary_[b].first + 1, fits_leaf(binary_[b].first + 1)};
        // Two more rounds (2^3 = T0_BVH_WIDTH): each opens every lane that
        // is not a leaf.
        for (int level = 1; level < 3; ++level) {
            const int before = lane_count;
            for (int i = 0; i < before; ++i) {
                if (!lanes[i].leaf) {
                    const std::uint32_t first = binary_[lanes[i].b].first;
                    lanes[i] = Lane{first, fits_leaf(first)};
                    lanes[lane_count++] = Lane{first + 1, fits_leaf(first + 1)};
                }
            }
        }
        return lane_count;
    }

    // Fills wide node `wide` from binary node `b`; returns the depth of the
    // wide subtree, in nodes.
    int fill(std::size_t wide, std::uint32_t b) {
        Lane lanes[T0_BVH_WIDTH];
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
            const std::uint32_t n = lanes[i].b;
            for (int axis = 0; axis < 3; ++axis) {
                set_node_plane(node, 2 * axis, i, binary_[n].bounds.min[axis]);
                set_node_plane(node, 2 * axis + 1, i, binary_[n].bounds.max[axis]);
            }
            if (lanes[i].leaf) {
                node.child[i / 4][i % 4] = T0_BVH_LEAF | static_cast<std::uint32_t>(leaves_.size());
                node.count[i / 4][i % 4] = count_[n];
                leaves_.push_back(BvhLeaf{first_[n], count_[n]});
            } else {
                interior.emplace_back(i, n);
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
    bool optimal_;
    std::uint32_t max_leaf_;
    // Per binary node: its subtree's triangles, count_ of them from first_.
    std::vector<std::uint32_t> first_;
    std::vector<std::uint32_t> count_;
    std::vector<float> cost_;
    std::vector<std::uint8_t> how_;
    // Per binary node made a wide node: how many of its lanes are the left
    // child's subtree's.
    std::vector<std::uint8_t> lanes_split_;
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
    const std::vector<BinaryNode> binary = Builder(std::move(items)).build(bvh.order);
    // The traversal stack holds at most seven entries per level, and one
    // more for a moment (kernel/traverse.h; the GPU's, one per level). The
    // optimal tree may be as deep as the binary one; where that is too
    // deep, the collapse by levels divides the depth by three.
    Collapser(binary, true, leaf_size).collapse(bvh);
    if (7 * bvh.depth + 1 > T0_BVH_STACK_SIZE) {
        Collapser(binary, false, leaf_size).collapse(bvh);
        bvh.by_levels = true;
    }
    if (7 * bvh.depth + 1 > T0_BVH_STACK_SIZE) {
        throw std::runtime_error("build_bvh: tree too deep for the traversal stack");
    }
    // The GPU's stack entry names its node in 24 bits (node_group).
    if (bvh.nodes.size() > (std::size_t{1} << 24)) {
        throw std::runtime_error("build_bvh: " + std::to_string(bvh.nodes.size()) +
                                 " nodes, more than the 2^24 that the traversal can name");
    }
    return bvh;
}

}  // namespace trac0r
