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

// Entries the GPU's traversal stack holds (T0_LANE_TRAVERSAL): one per level
// of the tree at most (a node's children that wait are one entry, a node
// group), 21 by the bound above.
#define T0_BVH_GROUP_STACK_SIZE ((T0_BVH_STACK_SIZE - 1) / 7)

// A stack entry: node `node`'s children whose bits `waiting` holds (bit i:
// child i), in one word (bvh.cpp keeps node indices below 2^24).
T0_INLINE t0_u32 node_group(t0_u32 node, int waiting) { return (node << 8) | (t0_u32)waiting; }
T0_INLINE t0_u32 group_node(t0_u32 group) { return group >> 8; }
T0_INLINE int group_waiting(t0_u32 group) { return (int)(group & 0xffu); }

// The top entry, `group`, after one of its children is taken: its children
// in `rest` go on waiting, or it leaves the stack where none is left.
T0_INLINE void keep_waiting(t0_u32* stack, int* top, t0_u32 group, int rest) {
    if (rest != 0) {
        stack[*top - 1] = node_group(group_node(group), rest);
    } else {
        --*top;
    }
}

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

// Nearest hit below t_max through the 8-wide BVH (the CPU's: T0_LANE_TRAVERSAL
// 0); with any_hit, stops at the first hit (shadow rays). Of a node's children that the ray enters,
// the nearest is visited next and the others wait on the stack with their
// entry distances, farthest at the bottom; one is skipped if a hit has come
// closer since.
T0_INLINE Hit traverse_bvh_sorted(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
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

// leaf_hits for a GPU: the packet's triangles one at a time
// (packet_lane_hit), the same hits in the same order.
T0_INLINE int leaf_lane_hits(const SceneView* scene, t0_u32 packet, const Ray* ray, Hit* hit) {
    T0_GLOBAL const TrianglePacket* p = &scene->packets[packet];
    int found = 0;
    for (int i = 0; i < 4; ++i) {
        float u = 0.0f;
        float v = 0.0f;
        const float t = packet_lane_hit(p, ray, i, hit->t, &u, &v);
        if (t < hit->t) {
            const int triangle = (int)buffer_uint_component(&p->triangle, i);
            if (T0_HAS_FEATURE(scene, T0_FEATURE_ALPHA) &&
                passes_through(scene, ray, triangle, u, v)) {
                continue;
            }
            hit->t = t;
            hit->u = u;
            hit->v = v;
            hit->triangle = triangle;
            found = 1;
        }
    }
    return found;
}

// child_entries' lane i alone, the same floats: the distance at which the
// ray enters child i's box, and in *entered whether it does over [0, t_max]
// (inv_far: the ray's inv_direction widened, as RayLanes.inv_direction_far).
// The near plane of each slab is the minimum (plane 2 axis) for a positive
// direction component, else the maximum (2 axis + 1), as make_ray_lanes
// picks them.
T0_INLINE float child_entry(T0_GLOBAL const BvhNode* n, const Ray* ray, float3 inv_far, int i,
                            float t_max, int* entered) {
    const float3 lo = make_float3(node_plane(n, 0, i), node_plane(n, 2, i), node_plane(n, 4, i));
    const float3 hi = make_float3(node_plane(n, 1, i), node_plane(n, 3, i), node_plane(n, 5, i));
    if (ray->any_parallel) {
        const float t = lo.x <= hi.x ? aabb_entry(lo, hi, *ray, t_max) : T0_NO_HIT;
        *entered = t < T0_NO_HIT;
        return t;
    }
    const float near_x = ((ray->inv_direction.x < 0.0f ? hi.x : lo.x) - ray->origin.x) *
                         ray->inv_direction.x;
    const float far_x = ((ray->inv_direction.x < 0.0f ? lo.x : hi.x) - ray->origin.x) * inv_far.x;
    const float near_y = ((ray->inv_direction.y < 0.0f ? hi.y : lo.y) - ray->origin.y) *
                         ray->inv_direction.y;
    const float far_y = ((ray->inv_direction.y < 0.0f ? lo.y : hi.y) - ray->origin.y) * inv_far.y;
    const float near_z = ((ray->inv_direction.z < 0.0f ? hi.z : lo.z) - ray->origin.z) *
                         ray->inv_direction.z;
    const float far_z = ((ray->inv_direction.z < 0.0f ? lo.z : hi.z) - ray->origin.z) * inv_far.z;
    // wide_max and wide_min lane by lane: a > b ? a : b, a < b ? a : b.
    const float xy_near = near_x > near_y ? near_x : near_y;
    const float z_near = near_z > 0.0f ? near_z : 0.0f;
    const float t_near = xy_near > z_near ? xy_near : z_near;
    const float xy_far = far_x < far_y ? far_x : far_y;
    const float t_far = xy_far < far_z ? xy_far : far_z;
    *entered = t_near <= (t_far < t_max ? t_far : t_max);
    return t_near;
}

// traverse_bvh_sorted's walk, the same nodes and leaves in the same order,
// for a GPU (T0_LANE_TRAVERSAL 1), whose work-item is one lane, not eight:
// - a node's children are tested one at a time (child_entry), and the
//   nearest picked as they come, rather than eight at once into an array;
// - its children that wait are one stack entry, their node and their bits
//   (node_group), visited nearest first as the entry comes back to the top
//   (ties as there: of two the first, of three or more the last), each
//   skipped if a hit has come as close since. Their distances are not kept
//   but computed again from the node then (the same floats).
// So the stack holds a word per level, not seven words and distances. A
// CPU, for which the second node test costs 9.9 % more instructions a path,
// keeps the sorted stack (docs/gpu.md).
T0_INLINE Hit traverse_bvh_groups(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
    Hit hit = no_hit(t_max);
    t0_u32 stack[T0_BVH_GROUP_STACK_SIZE];
    int top = 0;
    const float3 inv_far = ray->inv_direction * (1.0f + 2.0f * T0_GAMMA4);
    t0_u32 child = 0u;  // what is visited: node 0, the root, or a leaf (T0_BVH_LEAF)
    for (;;) {
        if ((child & T0_BVH_LEAF) != 0u) {
            if (leaf_lane_hits(scene, child & ~T0_BVH_LEAF, ray, &hit) && any_hit) {
                return hit;
            }
        } else {
            T0_GLOBAL const BvhNode* n = &scene->nodes[child];
            int mask = 0;
            int first = 0;  // the first child entered
            float first_entry = 0.0f;
            int near = 0;  // the nearest, the last of equals
            float near_entry = 0.0f;
            for (int i = 0; i < T0_BVH_WIDTH; ++i) {
                int entered = 0;
                const float e = child_entry(n, ray, inv_far, i, hit.t, &entered);
                if (entered) {
                    if (mask == 0) {
                        first = i;
                        first_entry = e;
                    }
                    if (mask == 0 || e <= near_entry) {
                        near = i;
                        near_entry = e;
                    }
                    mask |= 1 << i;
                }
            }
            if (mask != 0) {
                const int rest = mask & ~(1 << first);
                // Of two at the same distance, the first.
                near = rest != 0 && (rest & (rest - 1)) == 0 && first_entry <= near_entry ? first
                                                                                       : near;
                if (rest != 0) {
                    stack[top++] = node_group(child, mask & ~(1 << near));
                }
                child = node_child(n, near);
                continue;
            }
        }
        // The next waiting child that can still hold a nearer hit: the top
        // entry's nearest, whose siblings go on waiting.
        for (;;) {
            if (top == 0) {
                return hit;
            }
            const t0_u32 group = stack[top - 1];
            T0_GLOBAL const BvhNode* n = &scene->nodes[group_node(group)];
            int waiting = 0;
            int near = 0;
            float near_entry = 0.0f;
            for (int m = group_waiting(group); m != 0; m &= m - 1) {
                const int i = lowest_set_bit(m);
                int entered = 0;
                const float e = child_entry(n, ray, inv_far, i, hit.t, &entered);
                if (e < hit.t) {
                    if (waiting == 0 || e <= near_entry) {
                        near = i;
                        near_entry = e;
                    }
                    waiting |= 1 << i;
                }
            }
            if (waiting == 0) {
                --top;
                continue;
            }
            keep_waiting(stack, &top, group, waiting & ~(1 << near));
            child = node_child(n, near);
            break;
        }
    }
}

T0_INLINE Hit traverse_bvh(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
#if T0_LANE_TRAVERSAL
    return traverse_bvh_groups(scene, ray, t_max, any_hit);
#else
    return traverse_bvh_sorted(scene, ray, t_max, any_hit);
#endif
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
