#include "trac0r/bvh.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace trac0r {

namespace {

const int bin_count = 16;
// Below this depth splits follow the SAH; deeper (only in pathological
// inputs) they halve the list, so no path is longer than about this plus
// log2(n) nodes and the kernel's fixed traversal stack always suffices.
const int sah_depth_limit = 32;
// Relative costs of visiting a node and testing a triangle, for the SAH.
const float traversal_cost = 1.0f;
const float intersection_cost = 1.0f;

float surface_area(const AABB& b) {
    if (b.empty()) {
        return 0.0f;
    }
    const glm::vec3 d = b.max - b.min;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

float as_float_bits(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

std::uint32_t as_uint_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

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

    Bvh build() {
        Bvh bvh;
        nodes_.reserve(2 * items_.size() / static_cast<std::size_t>(std::max(1, max_leaf_ / 2)) + 1);
        nodes_.emplace_back();
        build_node(0, 0, items_.size(), 1);
        bvh.nodes = std::move(nodes_);
        bvh.order.reserve(items_.size());
        for (const BuildItem& item : items_) {
            bvh.order.push_back(item.index);
        }
        bvh.depth = depth_;
        return bvh;
    }

  private:
    void set_node(std::size_t node, const AABB& bounds, std::uint32_t first, std::uint32_t count) {
        nodes_[node].aabb_min = glm::vec4(bounds.min, as_float_bits(first));
        nodes_[node].aabb_max = glm::vec4(bounds.max, as_float_bits(count));
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
                const float cost = surface_area(acc) * n + right_area[b + 1] * right_count[b + 1];
                if (cost < best.cost) {
                    best.cost = cost;
                    best.axis = axis;
                    best.position = lo + (b + 1) / scale;
                }
            }
        }
        return best;
    }

    static int bin_of(float c, float lo, float scale) {
        const int b = static_cast<int>((c - lo) * scale);
        return std::min(std::max(b, 0), bin_count - 1);
    }

    void build_node(std::size_t node, std::size_t begin, std::size_t end, int depth) {
        depth_ = std::max(depth_, depth);
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
        const float leaf_cost = intersection_cost * static_cast<float>(count);
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
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
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
    std::vector<kernel::BvhNode> nodes_;
    int max_leaf_;
    int depth_ = 0;
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
        items.push_back({triangle_bounds[i], triangle_bounds[i].center(),
                         static_cast<std::uint32_t>(i)});
    }
    return Builder(std::move(items), std::max(1, max_leaf_size)).build();
}

std::uint32_t bvh_node_first(const kernel::BvhNode& node) { return as_uint_bits(node.aabb_min.w); }

std::uint32_t bvh_node_count(const kernel::BvhNode& node) { return as_uint_bits(node.aabb_max.w); }

}  // namespace trac0r
