// The edge-preserving filter of the thesis' outlook, as today's real-time
// path tracers do it (SVGF, Schied et al. 2017, without its temporal
// part): the accumulated image divided by the first non-specular
// surface's albedo (what is left is the lighting, smoother than the
// texture), a few passes of an a-trous wavelet (a 5 x 5 B3 spline, its
// taps 2^pass pixels apart), whose weights stop at edges: of depth, of
// normal, and of luminance beyond what the pixel's own noise (its
// variance, filtered along) explains; then multiplied by the albedo again.
// The accumulation itself is never changed: the filter reads a copy.
//
// Each pass is one function of a pixel (atrous_pixel) over the previous
// pass's buffer, so both backends run the same code, pixel by pixel.
#ifndef TRAC0R_KERNEL_FILTER_H
#define TRAC0R_KERNEL_FILTER_H

#include "accumulate.h"
#include "compat.h"
#include "ray.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// How many a-trous passes (taps 1, 2, 4, 8, 16 pixels apart: a footprint
// 125 pixels across), and the edge-stopping strengths (SVGF's values).
#define T0_FILTER_PASSES 5
#define T0_FILTER_SIGMA_LUMINANCE 4.0f
#define T0_FILTER_SIGMA_DEPTH 1.0f

// A pixel as the passes carry it: xyz the lighting (the colour over the
// albedo, or the colour itself where there is none), w the variance of its
// luminance's estimate.
typedef struct T0_ALIGN16 FilterPixel {
    float4 value;
} FilterPixel;

// What the edge-stopping functions read of a pixel: the camera ray's first
// non-specular surface, and the lamps that part of the pixel sees.
typedef struct T0_ALIGN16 FilterGuide {
    float4 albedo;  // xyz: albedo (zero: nothing; no demodulation), w: depth (T0_NO_HIT: none)
    float4 normal;  // xyz: unit normal facing the camera (zero: none), w: 1: kept as it is (a
                    // pure emitter, or a pixel almost all lamp)
    // Where a lamp's edge runs through the pixel: xyz the lamps' radiance
    // averaged over the pixel, w the share of the pixel they cover (the
    // rest is the surface above); zero elsewhere.
    float4 emission;
} FilterGuide;

// c^128 (the normal's edge-stopping power), by squaring: the same on
// both backends.
T0_INLINE float pow128(float c) {
    for (int i = 0; i < 7; ++i) {
        c *= c;
    }
    return c;
}

#ifndef __OPENCL_VERSION__
T0_STATIC_ASSERT_SIZE(FilterPixel, 16);
T0_STATIC_ASSERT_SIZE(FilterGuide, 48);
#endif

// A channel's albedo as a divisor: tiny and zero ones are not divided by.
T0_INLINE float demodulation_divisor(float albedo) { return albedo > 1e-3f ? albedo : 1.0f; }

// The three channels' divisors of a guide's albedo.
T0_INLINE float3 demodulation(FilterGuide g) {
    return make_float3(demodulation_divisor(g.albedo.x), demodulation_divisor(g.albedo.y),
                       demodulation_divisor(g.albedo.z));
}

// The share of a pixel that the surface covers (the rest: lamps whose
// edge runs through it; their light is no noise, and is not filtered).
T0_INLINE float surface_share(FilterGuide g) {
    return g.normal.w > 0.0f ? 1.0f : 1.0f - g.emission.w;
}

T0_INLINE float3 lamp_part(FilterGuide g) {
    return g.normal.w > 0.0f ? float3_splat(0.0f) : xyz(g.emission);
}

// The first pass's input for one pixel: the lighting of its surface, i.e.
// its accumulated mean less the lamps' part over the albedo times the
// surface's share, and the variance of that lighting's luminance (the
// per-sample variance over the samples, likewise scaled).
T0_INLINE FilterPixel filter_input(AccumPixel px, FilterGuide g) {
    const float3 colour = accumulated_mean(px) - lamp_part(g);
    const float share = surface_share(g);
    const float3 d = demodulation(g) * share;
    const float n = px.moments.z;
    const float dl = demodulation_divisor(luminance(demodulation(g))) * share;
    const float variance = n > 1.0f ? px.moments.y / (n - 1.0f) / n / (dl * dl) : 1e30f;
    FilterPixel out;
    out.value = make_float4(colour.x / d.x, colour.y / d.y, colour.z / d.z, variance);
    return out;
}

// The filtered pixel's colour: its lighting times the albedo and the
// surface's share again, plus the lamps' part.
T0_INLINE float3 filter_output(FilterPixel p, FilterGuide g) {
    return xyz(p.value) * (demodulation(g) * surface_share(g)) + lamp_part(g);
}

// The depth's change per pixel at (x, y): on each axis the smaller of the
// one-sided differences to the neighbours that hit something (so that at a
// silhouette the flat side counts, not the jump), the larger over the two
// axes; at least a thousandth of the depth, so a plane facing the camera
// still has some.
T0_INLINE float axis_slope(float z, float before, float after) {
    const float a = before < T0_NO_HIT ? fabs(z - before) : T0_NO_HIT;
    const float b = after < T0_NO_HIT ? fabs(after - z) : T0_NO_HIT;
    const float slope = fmin(a, b);
    return slope < T0_NO_HIT ? slope : 0.0f;
}

T0_INLINE float depth_slope(T0_GLOBAL const FilterGuide* guides, int width, int height, int x,
                            int y) {
    const float z = guides[y * width + x].albedo.w;
    const float left = x > 0 ? guides[y * width + x - 1].albedo.w : T0_NO_HIT;
    const float right = x + 1 < width ? guides[y * width + x + 1].albedo.w : T0_NO_HIT;
    const float up = y > 0 ? guides[(y - 1) * width + x].albedo.w : T0_NO_HIT;
    const float down = y + 1 < height ? guides[(y + 1) * width + x].albedo.w : T0_NO_HIT;
    return fmax(fmax(axis_slope(z, left, right), axis_slope(z, up, down)), 1e-3f * z);
}

// Pass `pass` (taps 2^pass apart) at pixel (x, y) of the previous pass's
// buffer `in`. A pixel whose camera ray meets nothing, or a lamp (whose
// light is not noise), is kept as it is and never mixed with the others.
T0_INLINE FilterPixel atrous_pixel(T0_GLOBAL const FilterPixel* in,
                                   T0_GLOBAL const FilterGuide* guides, int width, int height,
                                   int x, int y, int pass) {
    const int i = y * width + x;
    const FilterPixel centre = in[i];
    const FilterGuide g = guides[i];
    if (!(g.albedo.w < T0_NO_HIT) || g.normal.w > 0.0f) {
        return centre;
    }
    const float kernel_weights[3] = {0.375f, 0.25f, 0.0625f};
    const int step = 1 << pass;
    const float l = luminance(xyz(centre.value));
    const float sigma_z =
        fmax(T0_FILTER_SIGMA_DEPTH * depth_slope(guides, width, height, x, y), 1e-20f);
    const float3 n = xyz(g.normal);
    float3 sum = float3_splat(0.0f);
    float variance = 0.0f;
    float total = 0.0f;
    for (int dy = -2; dy <= 2; ++dy) {
        const int qy = y + dy * step;
        if (qy < 0 || qy >= height) {
            continue;
        }
        for (int dx = -2; dx <= 2; ++dx) {
            const int qx = x + dx * step;
            if (qx < 0 || qx >= width) {
                continue;
            }
            const int q = qy * width + qx;
            const FilterGuide gq = guides[q];
            if (!(gq.albedo.w < T0_NO_HIT) || gq.normal.w > 0.0f) {
                continue;
            }
            const FilterPixel p = in[q];
            const int adx = dx < 0 ? -dx : dx;
            const int ady = dy < 0 ? -dy : dy;
            const float h = kernel_weights[adx] * kernel_weights[ady];
            // A pixel without a normal (its ray went on through glass or a
            // mirror and met nothing) is mixed only with its like.
            const float3 nq = xyz(gq.normal);
            const int has_n = dot(n, n) > 0.0f;
            const int has_nq = dot(nq, nq) > 0.0f;
            const float w_n =
                has_n && has_nq ? pow128(fmax(dot(n, nq), 0.0f)) : (has_n == has_nq ? 1.0f : 0.0f);
            const float distance = (float)(adx + ady);
            const float w_z = exp(-fabs(g.albedo.w - gq.albedo.w) /
                                  (sigma_z * (float)step * fmax(distance, 1.0f)));
            // The luminance noise that the two pixels' variances (filtered
            // along) explain: the larger, so that the weight is the same
            // both ways and a noisy pixel gives as much as it takes (which
            // keeps the image's energy).
            const float sigma_l =
                T0_FILTER_SIGMA_LUMINANCE * sqrt(fmax(fmax(centre.value.w, p.value.w), 0.0f)) +
                1e-6f;
            const float w_l = exp(-fabs(l - luminance(xyz(p.value))) / sigma_l);
            // A pixel partly lamp saw its surface with that share of its
            // samples: its lighting counts as much.
            const float w = h * w_n * w_z * w_l * surface_share(gq);
            // A tap whose weight or value is not finite is left out, so one
            // bad pixel does not spoil its neighbours.
            if (!(w >= 0.0f) || !is_finite_f(p.value.x + p.value.y + p.value.z + p.value.w)) {
                continue;
            }
            sum += xyz(p.value) * w;
            variance += w * w * p.value.w;
            total += w;
        }
    }
    // The centre's weights are one but h, so total > 0 unless its own
    // values are not finite: then it is kept as it is.
    if (!(total > 0.0f)) {
        return centre;
    }
    FilterPixel out;
    const float3 mean = sum / total;
    out.value = make_float4(mean.x, mean.y, mean.z, variance / (total * total));
    return out;
}

T0_NAMESPACE_END

#endif
