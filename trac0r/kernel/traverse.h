// A ray through the scene: the flat list of shapes (traverse_flat), the
// 8-wide BVH (traverse_bvh), and on either the nearest hit (intersect_scene)
// or whether anything is in the way (occluded).
#ifndef TRAC0R_KERNEL_TRAVERSE_H
#define TRAC0R_KERNEL_TRAVERSE_H

#include "aabb.h"
#include "alpha.h"
#include "lanes.h"
#include "ray.h"
#include "triangle.h"
#include "tuning.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// The thesis' structure: every shape's AABB, then its triangles. Nearest
// hit below t_max; with any_hit, the first one found (shadow rays).
T0_INLINE Hit traverse_flat(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
    Hit hit = no_hit(t_max);
    for (t0_u32 s = 0; s < scene->shape_count; ++s) {
        T0_GLOBAL const ShapeRecord* shape = &scene->shapes[s];
        if (!intersect_aabb(xyz(shape->aabb_min), xyz(shape->aabb_max), *ray, hit.t)) {
            continue;
        }
        const t0_u32 end = shape->range.x + shape->range.y;
        for (t0_u32 i = shape->range.x; i < end; ++i) {
            float u = 0.0f;
            float v = 0.0f;
            const float t = intersect_triangle(&scene->triangles[i], *ray, &u, &v);
            if (T0_HAS_FEATURE(scene, T0_FEATURE_ALPHA) && t < hit.t &&
                passes_through(scene, ray, (int)i, u, v)) {
                continue;
            }
            if (t < hit.t) {
                hit.t = t;
                hit.u = u;
                hit.v = v;
                hit.triangle = (int)i;
                if (any_hit) {
                    return hit;
                }
            }
        }
    }
    return hit;
}

// Entries the traversal stack holds: a node leaves at most seven children
// there (its nearest is visited next; all eight may be there for a moment
// while they are put in order), so 7 x the tree's depth in nodes + 1,
// which trac0r/bvh.cpp checks (SAH to binary depth 32, then halving, and
// three binary levels per 8-wide node: at most 21 levels).
#define T0_BVH_STACK_SIZE 148

// Plane p's coordinate of node n's child i (0 to 7): lane i of the plane.
T0_INLINE float node_plane(T0_GLOBAL const BvhNode* n, int p, int i) {
    return buffer_component(&n->bounds[2 * p + (i >> 2)], i & 3);
}

// Node n's child word i (0 to 7): a node index, or T0_BVH_LEAF | a packet.
// The eight words are consecutive: read as one array, not as lane i % 4
// of vector i / 4, which costs three more operations between a node's test
// and the next node's address.
T0_INLINE t0_u32 node_child(T0_GLOBAL const BvhNode* n, int i) {
    return ((T0_GLOBAL const t0_u32*)n->child)[i];
}

// The distances along the ray to the eight planes `offset` bytes into
// n->bounds (the children's planes across `axis`), with inv as the ray's
// inverse direction there.
T0_INLINE t0_wide plane_distances(T0_GLOBAL const BvhNode* n, size_t offset, const RayLanes* l,
                                  int axis, t0_wide inv) {
    T0_GLOBAL const float4* planes =
        (T0_GLOBAL const float4*)((T0_GLOBAL const char*)n->bounds + offset);
    return wide_mul(wide_sub(wide_load(planes), l->origin[axis]), inv);
}

// The ray against the boxes of node n's eight children over [0, t_max]
// (limit: t_max in every lane): bit i of the result is set when it enters
// child i's box, at entry[i] (the others' entries mean nothing).
// aabb_entry, eight boxes per operation, with one difference: the exits are
// widened by taking them with inv_direction (1 + 2 gamma(4)), made once per
// ray, not by multiplying each one by 1 + 2 gamma(3), which is one
// operation less in the chain from a node's load to the choice of the next.
// The factor's own rounding makes four in an exit, three in an entry:
// (1 + u)^3 / (1 - u)^4 < 1 + 8u = 1 + 2 gamma(4) rounded, so an exit is
// still never below an entry that rounding has moved out (pbrt-v4,
// Bounds3::IntersectP).
T0_INLINE int child_entries(T0_GLOBAL const BvhNode* n, const Ray* ray, const RayLanes* l,
                            float t_max, t0_wide limit, float* entry) {
    if (ray->any_parallel) {
        // aabb_entry's slow path, one lane at a time; unused lanes (their
        // box is inverted) are skipped.
        int mask = 0;
        for (int i = 0; i < T0_BVH_WIDTH; ++i) {
            const float3 lo =
                make_float3(node_plane(n, 0, i), node_plane(n, 2, i), node_plane(n, 4, i));
            const float3 hi =
                make_float3(node_plane(n, 1, i), node_plane(n, 3, i), node_plane(n, 5, i));
            const float t = lo.x <= hi.x ? aabb_entry(lo, hi, *ray, t_max) : T0_NO_HIT;
            entry[i] = t;
            mask |= (t < T0_NO_HIT ? 1 : 0) << i;
        }
        return mask;
    }
    // The near plane of each slab is the minimum for a positive direction
    // and the maximum for a negative one: for a box, the same floats as the
    // min and max of aabb_entry (rounding is monotonic), and for an unused
    // lane's inverted box an entry beyond the exit.
    const t0_wide near_x = plane_distances(n, l->near[0], l, 0, l->inv_direction[0]);
    const t0_wide far_x = plane_distances(n, l->far[0], l, 0, l->inv_direction_far[0]);
    const t0_wide near_y = plane_distances(n, l->near[1], l, 1, l->inv_direction[1]);
    const t0_wide far_y = plane_distances(n, l->far[1], l, 1, l->inv_direction_far[1]);
    const t0_wide near_z = plane_distances(n, l->near[2], l, 2, l->inv_direction[2]);
    const t0_wide far_z = plane_distances(n, l->far[2], l, 2, l->inv_direction_far[2]);
    const t0_wide t_near = wide_max(wide_max(near_x, near_y), wide_max(near_z, wide_splat(0.0f)));
    const t0_wide t_far = wide_min(wide_min(far_x, far_y), far_z);
    wide_store(t_near, entry);
    return wide_mask_bits(wide_le(t_near, wide_min(t_far, limit)));
}

// The triangles of leaf packet `packet` in order, as the flat list tests
// them (ties go to the first): the nearest that the ray hits below *limit
// (hit->t in every lane) replaces *hit and narrows *limit. Whether one
// did.
T0_INLINE int leaf_hits(const SceneView* scene, t0_u32 packet, const Ray* ray, const RayLanes* l,
                        t0_lanes* limit, Hit* hit) {
    T0_GLOBAL const TrianglePacket* p = &scene->packets[packet];
    float t[4];
    float u[4];
    float v[4];
    int hits = intersect_packet(p, ray, l, *limit, t, u, v);
    if (hits == 0) {
        return 0;
    }
    int found = 0;
    do {
        const int i = lowest_set_bit(hits);
        hits &= hits - 1;
        if (t[i] < hit->t) {
            const int triangle = (int)buffer_uint_component(&p->triangle, i);
            if (T0_HAS_FEATURE(scene, T0_FEATURE_ALPHA) &&
                passes_through(scene, ray, triangle, u[i], v[i])) {
                continue;
            }
            hit->t = t[i];
            hit->u = u[i];
            hit->v = v[i];
            hit->triangle = triangle;
            found = 1;
        }
    } while (hits != 0);
    if (found) {
        *limit = lanes_splat(hit->t);
    }
    return found;
}

// Nearest hit below t_max through the 8-wide BVH; with any_hit, stops at
// the first hit (shadow rays). Of a node's children that the ray enters,
// the nearest is visited next and the others wait on the stack with their
// entry distances, farthest at the bottom; one is skipped if a hit has come
// closer since.
T0_INLINE Hit traverse_bvh(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
    Hit hit = no_hit(t_max);
    t0_u32 stack_child[T0_BVH_STACK_SIZE];
    float stack_entry[T0_BVH_STACK_SIZE];
    int top = 0;
    const RayLanes lanes = make_ray_lanes(*ray);
    t0_lanes limit = lanes_splat(t_max);     // hit.t in every lane of a packet
    t0_wide node_limit = wide_splat(t_max);  // and of a node
    t0_u32 child = 0u;  // what is visited: node 0, the root, or a leaf (T0_BVH_LEAF)
    for (;;) {
        if ((child & T0_BVH_LEAF) != 0u) {
            if (leaf_hits(scene, child & ~T0_BVH_LEAF, ray, &lanes, &limit, &hit)) {
                if (any_hit) {
                    return hit;
                }
                node_limit = wide_splat(hit.t);
            }
        } else {
            T0_GLOBAL const BvhNode* n = &scene->nodes[child];
            float entry[T0_BVH_WIDTH];
            const int mask = child_entries(n, ray, &lanes, hit.t, node_limit, entry);
            if (mask != 0) {
                const int first = lowest_set_bit(mask);
                const int rest = mask & (mask - 1);
                if (T0_ONE_CHILD_APART && rest == 0) {
                    // One child entered (most nodes): no sort.
                    child = node_child(n, first);
                    continue;
                }
                if ((rest & (rest - 1)) == 0) {
                    // Two: the farther waits. Or one (T0_ONE_CHILD_APART
                    // 0), taken as two of the same child: it is written
                    // above the top of the stack and not counted, and the
                    // next push overwrites it.
                    const int second = lowest_set_bit(rest != 0 ? rest : mask);
                    const int first_nearer = entry[first] <= entry[second];
                    const int near = first_nearer ? first : second;
                    const int far = first_nearer ? second : first;
                    stack_child[top] = node_child(n, far);
                    stack_entry[top] = entry[far];
                    top += rest != 0 ? 1 : 0;
                    child = node_child(n, near);
                    continue;
                }
                // Three or more: each is inserted into the stack above the
                // ones farther than it, so the nearest ends on top, and is
                // visited next.
                const int bottom = top;
                for (int m = mask; m != 0; m &= m - 1) {
                    const int i = lowest_set_bit(m);
                    const float e = entry[i];
                    int k = top;
                    while (k > bottom && stack_entry[k - 1] < e) {
                        stack_entry[k] = stack_entry[k - 1];
                        stack_child[k] = stack_child[k - 1];
                        --k;
                    }
                    stack_entry[k] = e;
                    stack_child[k] = node_child(n, i);
                    ++top;
                }
                --top;
                child = stack_child[top];
                continue;
            }
        }
        // Pop the next subtree that can still hold a nearer hit.
        for (;;) {
            if (top == 0) {
                return hit;
            }
            --top;
            if (stack_entry[top] < hit.t) {
                child = stack_child[top];
                break;
            }
        }
    }
}

T0_INLINE Hit intersect_scene(const SceneView* scene, const Ray* ray) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_BVH)) {
        return traverse_bvh(scene, ray, T0_NO_HIT, 0);
    }
    return traverse_flat(scene, ray, T0_NO_HIT, 0);
}

// Whether anything lies on the ray before t_max.
T0_INLINE int occluded(const SceneView* scene, const Ray* ray, float t_max) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_BVH)) {
        return traverse_bvh(scene, ray, t_max, 1).triangle >= 0;
    }
    return traverse_flat(scene, ray, t_max, 1).triangle >= 0;
}

T0_NAMESPACE_END

#endif
