// The per-pixel accumulator: a running mean that stays exact over very many
// frames (compensated summation) plus luminance moments for the noise
// estimate. Non-finite samples are counted and dropped, never summed.
#ifndef TRAC0R_KERNEL_ACCUMULATE_H
#define TRAC0R_KERNEL_ACCUMULATE_H

#include "types.h"

T0_NAMESPACE_BEGIN

// Rec. 709 luminance; luminance_rgb takes the channels one by one (the
// filter's vectorized CPU loop).
T0_INLINE float luminance_rgb(float r, float g, float b) {
    return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

T0_INLINE float luminance(float3 c) { return luminance_rgb(c.x, c.y, c.z); }

T0_INLINE int is_finite3(float3 c) {
    return is_finite_f(c.x) && is_finite_f(c.y) && is_finite_f(c.z);
}

T0_INLINE void accumulate_sample(T0_GLOBAL AccumPixel* px, float3 sample) {
    // Kahan: compensation carries the low-order bits each addition loses.
    const float3 y = sample - xyz(px->compensation);
    const float3 sum = xyz(px->sum);
    const float3 t = sum + y;
    // A non-finite sample makes t non-finite, and so does a finite one
    // whose sum a float cannot hold (an emission near FLT_MAX: the scene
    // loader refuses more than 1e30): either is counted and dropped, never
    // summed (inf - inf would make the compensation NaN). One test for both.
    if (!is_finite3(t)) {
        px->moments.w += 1.0f;
        return;
    }
    const float3 c = (t - sum) - y;
    px->sum = make_float4(t.x, t.y, t.z, 0.0f);
    px->compensation = make_float4(c.x, c.y, c.z, 0.0f);
    // Welford's update of the luminance mean and squared deviations.
    const float l = luminance(sample);
    const float n = px->moments.z + 1.0f;
    const float delta = l - px->moments.x;
    const float mean = px->moments.x + delta / n;
    px->moments.x = mean;
    px->moments.y += delta * (l - mean);
    px->moments.z = n;
}

T0_INLINE float3 accumulated_mean(AccumPixel px) {
    if (!(px.moments.z > 0.0f)) {
        return float3_splat(0.0f);
    }
    return (xyz(px.sum) - xyz(px.compensation)) / px.moments.z;
}

T0_NAMESPACE_END

#endif
