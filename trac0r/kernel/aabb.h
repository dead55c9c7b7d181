// The ray/box slab test: where a ray enters an axis-aligned box.
#ifndef TRAC0R_KERNEL_AABB_H
#define TRAC0R_KERNEL_AABB_H

#include "ray.h"

T0_NAMESPACE_BEGIN

// One slab of the slab test: narrows [*t_enter, *t_exit] to where the ray
// is between lo and hi. A ray parallel to the slab (a zero direction
// component, whose inv is the nudged +-1e30) is inside it for every t when
// its origin is in [lo, hi], boundary planes included (bounds are
// conservative), and nowhere otherwise. The general formula cannot say
// this: on the plane hi it gives (hi - origin) * inv = 0, an exit at t = 0.
T0_INLINE void clip_slab(float lo, float hi, float origin, float direction, float inv,
                         float* t_enter, float* t_exit) {
    if (is_parallel_component(direction)) {
        if (origin < lo || origin > hi) {
            *t_exit = -1.0f;
        }
        return;
    }
    // Plain comparisons, not fmin/fmax: nothing here is NaN (inv is finite),
    // and on the CPU fminf is a library call that dominated the profile.
    const float t_lo = (lo - origin) * inv;
    const float t_hi = (hi - origin) * inv;
    const float t_near = t_lo < t_hi ? t_lo : t_hi;
    // Widened by 2 gamma(3) (pbrt-v4, Bounds3::IntersectP): rounding in the
    // two products must not make a ray that grazes a box (or a triangle on
    // its boundary) miss it.
    const float t_far = (t_lo < t_hi ? t_hi : t_lo) * (1.0f + 2.0f * T0_GAMMA3);
    *t_enter = t_near > *t_enter ? t_near : *t_enter;
    *t_exit = t_far < *t_exit ? t_far : *t_exit;
}

// Slab test over the ray's [0, t_max]: the distance at which the ray enters
// the box (0 when it starts inside), or T0_NO_HIT. inv_direction is finite,
// so no inf * 0 NaN arises.
T0_INLINE float aabb_entry(float3 box_min, float3 box_max, Ray ray, float t_max) {
    if (!ray.any_parallel) {
        // clip_slab on three slabs without its per-axis branch, the same
        // floats (widening each exit or their minimum is one rounding: both
        // monotonic), for the BVH's inner loop (kernel/tuning.h).
        const float3 t_lo = (box_min - ray.origin) * ray.inv_direction;
        const float3 t_hi = (box_max - ray.origin) * ray.inv_direction;
        const float t_near = max_f(max_f(min_f(t_lo.x, t_hi.x), min_f(t_lo.y, t_hi.y)),
                                   max_f(min_f(t_lo.z, t_hi.z), 0.0f));
        const float t_far =
            min_f(min_f(max_f(t_lo.x, t_hi.x), max_f(t_lo.y, t_hi.y)), max_f(t_lo.z, t_hi.z)) *
            (1.0f + 2.0f * T0_GAMMA3);
        return t_near <= min_f(t_far, t_max) ? t_near : T0_NO_HIT;
    }
    float t_enter = 0.0f;
    float t_exit = t_max;
    clip_slab(box_min.x, box_max.x, ray.origin.x, ray.direction.x, ray.inv_direction.x, &t_enter,
              &t_exit);
    clip_slab(box_min.y, box_max.y, ray.origin.y, ray.direction.y, ray.inv_direction.y, &t_enter,
              &t_exit);
    clip_slab(box_min.z, box_max.z, ray.origin.z, ray.direction.z, ray.inv_direction.z, &t_enter,
              &t_exit);
    return t_enter <= t_exit ? t_enter : T0_NO_HIT;
}

T0_INLINE int intersect_aabb(float3 box_min, float3 box_max, Ray ray, float t_max) {
    return aabb_entry(box_min, box_max, ray, t_max) < T0_NO_HIT;
}

T0_NAMESPACE_END

#endif
