// Picking a light by a tree over the lights with a position (pbrt-v4's
// BVHLightSampler, after Conty Estevez and Kulla 2018): from the shading
// point down, each child's importance (its power, over its squared
// distance, times bounds on the cosines at the light and at the point)
// decides the way, so that near lights that face the point are picked
// often and far or turned-away ones seldom. The probability of a given
// light is the product of the choices on its path (light_tree_pmf), which
// its light record keeps as bits, for MIS.
#ifndef TRAC0R_KERNEL_LIGHT_TREE_H
#define TRAC0R_KERNEL_LIGHT_TREE_H

#include "sampler.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// cos(a - b) and sin(a - b) for angles a, b in [0, pi], clamped to a
// difference of zero where a < b (the cosine's bound cannot exceed one).
T0_INLINE float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}

T0_INLINE float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

T0_INLINE float safe_sqrt(float x) { return sqrt(fmax(x, 0.0f)); }

// The largest importance: the sum of two stays finite, so that a choice
// between them is never inf / inf (a lamp of intensity 1e30 right at p).
#define T0_LIGHT_IMPORTANCE_MAX 1e30f

// An upper bound, up to a common factor, on what the lights under `node`
// can bring to a surface at p with normal n (either side): zero only
// where they bring nothing. node->lo.w is their peak intensity (W/sr
// along the normal for a surface, L x area), not their power: the cones
// bound the directions.
T0_INLINE float light_importance(T0_GLOBAL const LightTreeNode* node, float3 p, float3 n) {
    const float3 lo = xyz(node->lo);
    const float3 hi = xyz(node->hi);
    const float3 to_p = p - (lo + hi) * 0.5f;
    const float3 diagonal = hi - lo;
    const float radius2 = 0.25f * dot(diagonal, diagonal);
    const float distance2 = dot(to_p, to_p);
    // Inside the bounds' sphere, every direction: no bound on the angles.
    if (!(distance2 > radius2)) {
        return fmin(node->lo.w / fmax(radius2, 1e-30f), T0_LIGHT_IMPORTANCE_MAX);
    }
    const float3 wi = to_p / sqrt(distance2);
    float cos_w = dot(xyz(node->axis), wi);
    if (node->info.z != 0u) {
        cos_w = fabs(cos_w);
    }
    const float sin_w = safe_sqrt(1.0f - cos_w * cos_w);
    // The cone the bounds' sphere subtends from p.
    const float cos_b = safe_sqrt(1.0f - radius2 / distance2);
    const float sin_b = safe_sqrt(1.0f - cos_b * cos_b);
    // The smallest angle between the lights' cone and the way to p.
    const float cos_o = node->hi.w;
    const float sin_o = safe_sqrt(1.0f - cos_o * cos_o);
    const float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o);
    const float sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
    const float cos_light = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if (!(cos_light > node->axis.w)) {
        return 0.0f;
    }
    // The largest cosine at the surface over the bounds' cone.
    const float cos_i = fabs(dot(wi, n));
    const float sin_i = safe_sqrt(1.0f - cos_i * cos_i);
    const float cos_surface = cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
    return fmin(fmax(node->lo.w * cos_light * cos_surface / distance2, 0.0f),
                T0_LIGHT_IMPORTANCE_MAX);
}

typedef struct LightPick {
    t0_u32 light;  // an index into the light list
    float pmf;     // its probability; 0: nothing to pick
} LightPick;

// Down the tree from the root: the first level chooses by u in [0, 1),
// each level below by a number of its own, hashed from u's bits and the
// level, so that every choice has a float's 24 bits (u stretched from
// level to level would run out of them after a dozen levels, and picks
// would stray from the probabilities MIS computes).
T0_INLINE LightPick light_tree_pick(const SceneView* scene, float3 p, float3 n, float u) {
    const t0_u32 bits = (t0_u32)(u * 16777216.0f);
    LightPick pick;
    pick.light = 0u;
    pick.pmf = 1.0f;
    t0_u32 node = 0u;
    for (int depth = 0; depth <= 32; ++depth) {
        T0_GLOBAL const LightTreeNode* nd = &scene->light_nodes[node];
        if (nd->info.y != 0u) {
            pick.light = nd->info.x;
            return pick;
        }
        const t0_u32 first = nd->info.x;
        const float i0 = light_importance(&scene->light_nodes[first], p, n);
        const float i1 = light_importance(&scene->light_nodes[first + 1u], p, n);
        const float total = i0 + i1;
        if (!(total > 0.0f)) {
            break;
        }
        const float p0 = i0 / total;
        if (depth > 0) {
            u = unit_float(hash32(bits + (t0_u32)depth * 0x9E3779B9u));
        }
        if (u < p0) {
            node = first;
            pick.pmf *= p0;
        } else {
            node = first + 1u;
            pick.pmf *= i1 / total;
        }
    }
    pick.pmf = 0.0f;
    return pick;
}

// The probability that light_tree_pick at p, n gives the light whose path
// is `trail` (bit k: the child at depth k).
T0_INLINE float light_tree_pmf(const SceneView* scene, float3 p, float3 n, t0_u32 trail) {
    float pmf = 1.0f;
    t0_u32 node = 0u;
    for (int depth = 0; depth <= 32; ++depth) {
        T0_GLOBAL const LightTreeNode* nd = &scene->light_nodes[node];
        if (nd->info.y != 0u) {
            return pmf;
        }
        const t0_u32 first = nd->info.x;
        const float i0 = light_importance(&scene->light_nodes[first], p, n);
        const float i1 = light_importance(&scene->light_nodes[first + 1u], p, n);
        const float total = i0 + i1;
        if (!(total > 0.0f)) {
            return 0.0f;
        }
        const t0_u32 bit = trail & 1u;
        trail >>= 1;
        pmf *= (bit != 0u ? i1 : i0) / total;
        node = first + bit;
    }
    return 0.0f;
}

T0_NAMESPACE_END

#endif
