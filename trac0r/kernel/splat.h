// The splat image of bidirectional path tracing (bdpt.h): light subpaths
// connected to the camera add their light to whatever pixel they land in,
// from any work-item or thread. The sums are 64-bit fixed point with
// 2^-24 as their unit, added by integer atomics: integer addition is
// associative, so the sum is the same whatever order the adds come in,
// and a frame stays a pure function of the scene, settings, seed and frame
// on both backends. A splat's value is rounded to the unit (6e-8, below a
// float's precision for any value above 1) and held at most 2^31 (2.1e9,
// 2^55 units), so that 256 of them in one pixel cannot overflow.
#ifndef TRAC0R_KERNEL_SPLAT_H
#define TRAC0R_KERNEL_SPLAT_H

#include "types.h"

T0_NAMESPACE_BEGIN

#ifdef __OPENCL_VERSION__
typedef long t0_i64;
// A 64-bit add from OpenCL 1.2's 32-bit atomics (64-bit ones are an
// extension not every device has): the low word's add returns the word
// before it, which says whether it carried into the high word. The sum of
// every add is then exact, whatever their order.
T0_INLINE void splat_atomic_add(__global long* sum, long value) {
    volatile __global uint* words = (volatile __global uint*)sum;  // little-endian
    const uint low = (uint)value;
    const uint high = (uint)((ulong)value >> 32);
    const uint before = atomic_add(&words[0], low);
    const uint carry = before + low < before ? 1u : 0u;
    if (high + carry != 0u) {
        atomic_add(&words[1], high + carry);
    }
}
#else
typedef int64_t t0_i64;
inline void splat_atomic_add(t0_i64* sum, t0_i64 value) {
    __atomic_fetch_add(sum, value, __ATOMIC_RELAXED);
}
#endif

#define T0_SPLAT_UNITS 16777216.0f  // units per 1: 2^24
#define T0_SPLAT_MAX 2147483648.0f  // 2^31

// One channel's value in units: rounded to the nearest, held to
// [0, T0_SPLAT_MAX].
T0_INLINE t0_i64 splat_units(float v) {
    const float held = fmin(fmax(v, 0.0f), T0_SPLAT_MAX);
    return (t0_i64)(held * T0_SPLAT_UNITS + 0.5f);
}

// Adds a non-negative, finite colour to pixel `pixel` of the splat image
// (three sums a pixel, and a fourth left zero: 32 bytes); any other colour
// is dropped (the accumulator would drop its sample too).
T0_INLINE void splat_add(T0_GLOBAL t0_i64* splats, t0_u32 pixel, float3 c) {
    if (!(is_finite_f(c.x) && is_finite_f(c.y) && is_finite_f(c.z))) {
        return;
    }
    T0_GLOBAL t0_i64* p = splats + 4u * pixel;
    if (c.x > 0.0f) {
        splat_atomic_add(p, splat_units(c.x));
    }
    if (c.y > 0.0f) {
        splat_atomic_add(p + 1, splat_units(c.y));
    }
    if (c.z > 0.0f) {
        splat_atomic_add(p + 2, splat_units(c.z));
    }
}

// Pixel `pixel`'s sum, as a colour.
T0_INLINE float3 splat_value(T0_GLOBAL const t0_i64* splats, t0_u32 pixel) {
    T0_GLOBAL const t0_i64* p = splats + 4u * pixel;
    return make_float3((float)p[0], (float)p[1], (float)p[2]) * (1.0f / T0_SPLAT_UNITS);
}

T0_NAMESPACE_END

#endif
