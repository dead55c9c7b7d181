// A tile's camera rays bounded together (RayBundle): the BVH leaves any of
// them may enter, found once (bundle_leaves), and a ray's hit among them.
#ifndef TRAC0R_KERNEL_BUNDLE_H
#define TRAC0R_KERNEL_BUNDLE_H

#include "lanes.h"
#include "ray.h"
#include "traverse.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// Rays that share an origin (a tile's camera rays), bounded together:
// per axis the least and the greatest of their inverse directions (none
// parallel: Ray.any_parallel rays are left out of a bundle).
typedef struct RayBundle {
    float3 origin;
    float3 inv_min;
    float3 inv_max;
    int rays;  // how many rays the bounds hold
} RayBundle;

T0_INLINE void bundle_start(RayBundle* b, float3 origin) {
    b->origin = origin;
    b->inv_min = float3_splat(0.0f);
    b->inv_max = float3_splat(0.0f);
    b->rays = 0;
}

// Adds a ray that starts at b->origin, bit for bit (the bounds are exact
// only so: a tile's camera rays start at the camera's position), is not
// parallel to an axis (Ray.any_parallel), and has inverse direction inv
// (Ray.inv_direction).
T0_INLINE void bundle_add(RayBundle* b, float3 inv) {
    if (b->rays == 0) {
        b->inv_min = inv;
        b->inv_max = inv;
    } else {
        b->inv_min = make_float3(min_f(b->inv_min.x, inv.x), min_f(b->inv_min.y, inv.y),
                                 min_f(b->inv_min.z, inv.z));
        b->inv_max = make_float3(max_f(b->inv_max.x, inv.x), max_f(b->inv_max.y, inv.y),
                                 max_f(b->inv_max.z, inv.z));
    }
    ++b->rays;
}

// Whether the bounds along `axis` may be used: every ray's inverse
// direction there of one sign.
T0_INLINE int bundle_axis_usable(const RayBundle* b, int axis) {
    return component3(b->inv_min, axis) > 0.0f || component3(b->inv_max, axis) < 0.0f;
}

// A leaf that some ray of a bundle may enter, and a lower bound of the
// distance at which any of them enters its box.
typedef struct LeafCandidate {
    t0_u32 packet;
    float entry;
} LeafCandidate;

// The most leaves a bundle keeps; a bundle that meets more is not used.
#define T0_BUNDLE_LEAVES 16

// Over the eight children of node n, for one usable axis of the bundle:
// the least distance at which any of its rays meets each child's near
// plane, and the greatest at which any meets its far plane. A ray's own
// distances in child_entries are (plane - origin) * inv and (plane -
// origin) * inv_far, rounded; rounding is monotonic, so over the rays their
// least and greatest are those of the two extreme inverses: the same
// floats, no margin needed.
T0_INLINE void bundle_axis(T0_GLOBAL const BvhNode* n, const RayBundle* b, int axis,
                           t0_wide* near_lo, t0_wide* far_hi) {
    const float inv_min = component3(b->inv_min, axis);
    const float inv_max = component3(b->inv_max, axis);
    const size_t plane = 2 * sizeof(float4);
    // As make_ray_lanes: minima first for a positive direction.
    const size_t near = (size_t)(2 * axis + (inv_max < 0.0f ? 1 : 0)) * plane;
    const size_t far = (size_t)(4 * axis + 1) * plane - near;
    const t0_wide origin = wide_splat(component3(b->origin, axis));
    const float widen = 1.0f + 2.0f * T0_GAMMA4;
    T0_GLOBAL const float4* near_planes =
        (T0_GLOBAL const float4*)((T0_GLOBAL const char*)n->bounds + near);
    T0_GLOBAL const float4* far_planes =
        (T0_GLOBAL const float4*)((T0_GLOBAL const char*)n->bounds + far);
    const t0_wide to_near = wide_sub(wide_load(near_planes), origin);
    const t0_wide to_far = wide_sub(wide_load(far_planes), origin);
    *near_lo =
        wide_min(wide_mul(to_near, wide_splat(inv_min)), wide_mul(to_near, wide_splat(inv_max)));
    *far_hi = wide_max(wide_mul(to_far, wide_splat(inv_min * widen)),
                       wide_mul(to_far, wide_splat(inv_max * widen)));
}

// The BVH's leaves that a ray of bundle b may enter, with a lower bound of
// each one's entry, nearest first, into out[0, T0_BUNDLE_LEAVES): their
// count, or -1 where there are more (a wide bundle; its rays traverse the
// tree one by one). A child is left out only where its box's entry bound
// lies beyond its exit bound, so a ray that child_entries would take into a
// leaf finds it here; with it every triangle that ray hits.
T0_INLINE int bundle_leaves(const SceneView* scene, const RayBundle* b,
                            T0_LOCAL LeafCandidate* out) {
    // Depth first, the last child first: a node's inner children that wait
    // are one stack entry (node_group), as in traverse_bvh.
    t0_u32 stack[T0_BVH_GROUP_STACK_SIZE];
    int top = 0;
    int count = 0;
    t0_u32 node = 0u;
    for (;;) {
        T0_GLOBAL const BvhNode* n = &scene->nodes[node];
        t0_wide entry = wide_splat(0.0f);
        t0_wide exit = wide_splat(T0_INFINITY);
        for (int axis = 0; axis < 3; ++axis) {
            if (bundle_axis_usable(b, axis)) {
                t0_wide near_lo;
                t0_wide far_hi;
                bundle_axis(n, b, axis, &near_lo, &far_hi);
                entry = wide_max(entry, near_lo);
                exit = wide_min(exit, far_hi);
            }
        }
        int inner = 0;
        for (int m = wide_mask_bits(wide_le(entry, exit)); m != 0; m &= m - 1) {
            const int i = lowest_set_bit(m);
            const t0_u32 child = node_child(n, i);
            if ((child & T0_BVH_LEAF) == 0u) {
                inner |= 1 << i;
                continue;
            }
            if (count == T0_BUNDLE_LEAVES) {
                return -1;
            }
            // Kept in order of entry (insertion; ties keep the order found).
            int k = count++;
            const float e = wide_lane(entry, i);
            while (k > 0 && out[k - 1].entry > e) {
                out[k] = out[k - 1];
                --k;
            }
            out[k].packet = child & ~T0_BVH_LEAF;
            out[k].entry = e;
        }
        if (inner != 0) {
            stack[top++] = node_group(node, inner);
        }
        if (top == 0) {
            return count;
        }
        // The top entry's last child next; its others go on waiting.
        const t0_u32 group = stack[top - 1];
        const int waiting = group_waiting(group);
        const int last = highest_set_bit(waiting);
        node = node_child(&scene->nodes[group_node(group)], last);
        keep_waiting(stack, &top, group, waiting & ~(1 << last));
    }
}

// The leaves that the rays of bundle b may enter (bundle_leaves), or -1
// where it cannot be used (no ray, no axis along which all have one sign,
// or more leaves than T0_BUNDLE_LEAVES).
T0_INLINE int bundle_finish_leaves(const SceneView* scene, const RayBundle* b,
                                   T0_LOCAL LeafCandidate* out) {
    const int usable =
        bundle_axis_usable(b, 0) || bundle_axis_usable(b, 1) || bundle_axis_usable(b, 2);
    return b->rays > 0 && usable ? bundle_leaves(scene, b, out) : -1;
}

// The nearest hit of a ray of a bundle among the bundle's leaves
// (bundle_leaves): traverse_bvh's hit, found without the tree. The leaves
// are tested nearest bound first, up to the first whose bound is not below
// the hit (as traverse_bvh pops its stack), each with traverse_bvh's packet
// test: the same floats. The two test the leaves in different orders, so
// only where two triangles of different leaves are hit within rounding of
// each other (an edge they share; a triangle in the face of its flat leaf
// box, whose hit may lie an ulp before the box's entry) may they pick
// different ones: both are hits there.
T0_INLINE Hit intersect_bundle_leaves(const SceneView* scene, T0_LOCAL const LeafCandidate* leaves,
                                      int count, const Ray* ray) {
    Hit hit = no_hit(T0_NO_HIT);
#if T0_LANE_TRAVERSAL
    // A GPU's: a triangle at a time (leaf_lane_hits), the same hits.
    for (int k = 0; k < count && leaves[k].entry < hit.t; ++k) {
        leaf_lane_hits(scene, leaves[k].packet, ray, &hit);
    }
#else
    const RayLanes lanes = make_ray_lanes(*ray);
    t0_lanes limit = lanes_splat(T0_NO_HIT);
    for (int k = 0; k < count && leaves[k].entry < hit.t; ++k) {
        leaf_hits(scene, leaves[k].packet, ray, &lanes, &limit, &hit);
    }
#endif
    return hit;
}

T0_NAMESPACE_END

#endif
