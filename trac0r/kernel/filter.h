// The edge-preserving filter of the thesis' outlook, as today's real-time
// path tracers do it (SVGF, Schied et al. 2017, without its temporal
// part): the accumulated image divided by the first non-specular
// surface's albedo (what is left is the lighting, smoother than the
// texture), a few passes of an a-trous wavelet (3 x 3 taps, 2^pass
// pixels apart), whose weights stop at edges: of depth, of normal, and of
// luminance beyond what the pixel's own noise (its variance, filtered
// along) explains; then multiplied by the albedo again. The accumulation
// itself is never changed: the filter reads a copy.
//
// Each pass is one function of a pixel (atrous_pixel) over the previous
// pass's buffer; its formula is tap_weight and atrous_result, which the
// CPU backend calls tap by tap along a row (trac0r/filter.cpp), so both
// backends run the same formula.
#ifndef TRAC0R_KERNEL_FILTER_H
#define TRAC0R_KERNEL_FILTER_H

#include "accumulate.h"
#include "compat.h"
#include "ray.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// How many a-trous passes (taps 1, 2, 4 and 8 pixels apart: a footprint
// 31 pixels across; more passes blur more than they smooth at 4 spp, see
// docs/filter.md), and the edge-stopping strengths (SVGF's values).
#define T0_FILTER_PASSES 4
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

// What the first pass's input and the filtered pixel take of a pixel's
// guides (filter_scale): the divisors of its surface's lighting (the
// albedo's, demodulation, times the surface's share), that of its
// luminance, and the lamps' part. They stay while the view does.
typedef struct FilterScale {
    float3 divisor;
    float luminance_divisor;
    float3 lamp;
} FilterScale;

T0_INLINE FilterScale filter_scale(FilterGuide g) {
    const float share = surface_share(g);
    FilterScale out;
    out.divisor = demodulation(g) * share;
    out.luminance_divisor = demodulation_divisor(luminance(demodulation(g))) * share;
    out.lamp = lamp_part(g);
    return out;
}

// The first pass's input for one pixel: the lighting of its surface, i.e.
// its accumulated mean less the lamps' part over the albedo times the
// surface's share, and the variance of that lighting's luminance (the
// per-sample variance over the samples, likewise scaled).
T0_INLINE FilterPixel filter_input_scaled(AccumPixel px, FilterScale s) {
    const float3 colour = accumulated_mean(px) - s.lamp;
    const float3 d = s.divisor;
    const float n = px.moments.z;
    const float dl = s.luminance_divisor;
    const float variance = n > 1.0f ? px.moments.y / (n - 1.0f) / n / (dl * dl) : 1e30f;
    FilterPixel out;
    out.value = make_float4(colour.x / d.x, colour.y / d.y, colour.z / d.z, variance);
    return out;
}

T0_INLINE FilterPixel filter_input(AccumPixel px, FilterGuide g) {
    return filter_input_scaled(px, filter_scale(g));
}

// The filtered pixel's colour: its lighting times the albedo and the
// surface's share again, plus the lamps' part.
T0_INLINE float3 filter_output_scaled(FilterPixel p, FilterScale s) {
    return xyz(p.value) * s.divisor + s.lamp;
}

T0_INLINE float3 filter_output(FilterPixel p, FilterGuide g) {
    return filter_output_scaled(p, filter_scale(g));
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

// What a pass reads of a pixel's guides, made once before the passes
// (filter_tap): the formula's per-pixel parts, in two vectors.
typedef struct T0_ALIGN16 FilterTap {
    // xyz: the unit normal (zero: none), w: 1 where there is none; so the
    // dot product of two pixels' is their normals' cosine, 1 for two
    // without one, and 0 for one with and one without.
    float4 normal;
    // x: depth; y: 1 / (T0_FILTER_SIGMA_DEPTH x the depth slope); z: the
    // pixel's weight as a tap, its surface share (0: never a tap: kept as
    // it is, or sees nothing); w: 1 where the pixel is kept as it is.
    float4 params;
} FilterTap;

#ifndef __OPENCL_VERSION__
T0_STATIC_ASSERT_SIZE(FilterTap, 32);
#endif

T0_INLINE FilterTap filter_tap(T0_GLOBAL const FilterGuide* guides, int width, int height, int x,
                               int y) {
    const FilterGuide g = guides[y * width + x];
    FilterTap t;
    const float3 n = xyz(g.normal);
    t.normal = make_float4(n.x, n.y, n.z, dot(n, n) > 0.0f ? 0.0f : 1.0f);
    const int kept = !(g.albedo.w < T0_NO_HIT) || g.normal.w > 0.0f;
    const float slope = kept ? 1.0f : depth_slope(guides, width, height, x, y);
    t.params =
        make_float4(kept ? 0.0f : g.albedo.w, 1.0f / fmax(T0_FILTER_SIGMA_DEPTH * slope, 1e-20f),
                    kept ? 0.0f : surface_share(g), kept ? 1.0f : 0.0f);
    return t;
}

// v clamped into [lo, hi] (an index: image borders).
T0_INLINE int clamp_index(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

// The edge-stopping weight of a distance x >= 0 (in units of what the
// noise or the depth slope explains): (1 + x/8)^-8, which falls as
// exp(-x) does near 0 (within 3 % up to x = 1) with a heavier tail, and
// costs one division where exp costs many operations.
T0_INLINE float edge_weight(float x) {
    float r = 1.0f / (1.0f + 0.125f * x);
    r *= r;
    r *= r;
    return r * r;
}

// What the luminance weights of a pass read of a pixel, made before the
// pass (filter_noise): x its luminance, y 1 / (T0_FILTER_SIGMA_LUMINANCE
// standard deviations of its noise); zw: zero.
typedef struct T0_ALIGN16 FilterNoise {
    float4 value;
} FilterNoise;

#ifndef __OPENCL_VERSION__
T0_STATIC_ASSERT_SIZE(FilterNoise, 16);
#endif

// 1 / (T0_FILTER_SIGMA_LUMINANCE standard deviations) for a variance:
// FilterNoise's y, as a scalar (its x is luminance_rgb).
T0_INLINE float by_noise_of(float variance) {
    return 1.0f / (T0_FILTER_SIGMA_LUMINANCE * sqrt(fmax(variance, 0.0f)) + 1e-6f);
}

T0_INLINE FilterNoise filter_noise(FilterPixel p) {
    FilterNoise out;
    out.value = make_float4(luminance_rgb(p.value.x, p.value.y, p.value.z), by_noise_of(p.value.w),
                            0.0f, 0.0f);
    return out;
}

// The wavelet's weight of the tap (dx, dy), each -1, 0 or 1: 1/4, 1/2,
// 1/4 on each axis.
T0_INLINE float wavelet_weight(int dx, int dy) {
    return (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
}

// How far the tap (dx, dy) reaches in depth slopes, inverted: diagonal
// taps are twice as far, so the depth slope counts twice.
T0_INLINE float tap_reach(int dx, int dy) { return dx != 0 && dy != 0 ? 0.5f : 1.0f; }

// The weight of a tap of a centre pixel c: the wavelet's weight h times
// the edge-stopping ones (normal, depth over reach, luminance) and the
// tap's surface share; zero for a tap whose weight or value (the sum of
// its components, p_sum) is not finite, so one bad pixel does not spoil
// its neighbours. The centre's by_depth is its FilterTap's params.y over
// the pass's tap distance; l and by_noise, and the tap's t_l and
// t_by_noise, are their FilterNoise's x and y; the normals (FilterTap's)
// come as their components. Scalars, not structs: the CPU backend reads
// them from planes.
T0_INLINE float tap_weight(float cnx, float cny, float cnz, float cnw, float c_depth, float l,
                           float by_noise, float by_depth, float tnx, float tny, float tnz,
                           float tnw, float t_depth, float t_share, float t_l, float t_by_noise,
                           float p_sum, float h, float reach) {
    const float cosine = cnx * tnx + cny * tny + cnz * tnz + cnw * tnw;
    const float w_n = pow128(cosine > 0.0f ? cosine : 0.0f);
    const float distance = fabs(c_depth - t_depth) * by_depth * reach +
                           fabs(l - t_l) * (by_noise < t_by_noise ? by_noise : t_by_noise);
    const float w = h * w_n * edge_weight(distance) * t_share;
    const int ok = (w >= 0.0f) & is_finite_f(p_sum);
    return ok ? w : 0.0f;
}

// A pass's pixel from its taps' weighted sums: their mean, and the
// variance of that mean. A pixel kept as it is stays so; so does one whose
// taps' weights sum to zero (the centre weighs its surface share, > 0,
// unless its own values are not finite).
T0_INLINE int atrous_keeps(float kept, float total) { return (kept > 0.0f) | !(total > 0.0f); }

T0_INLINE FilterPixel atrous_result(FilterPixel centre, FilterTap c, float3 sum, float variance,
                                    float total) {
    if (atrous_keeps(c.params.w, total)) {
        return centre;
    }
    FilterPixel out;
    out.value =
        make_float4(sum.x / total, sum.y / total, sum.z / total, variance / (total * total));
    return out;
}

// Pass `pass` (taps 2^pass apart) at pixel (x, y) of the previous pass's
// buffer `in`: a 3 x 3 a-trous wavelet (1/4, 1/2, 1/4 on each axis) whose
// taps are weighted by normal (cos^128), depth (against the local depth
// slope) and luminance (against the noise of the noisier of the two
// pixels, `noise`: so the weight is the same both ways and a noisy pixel
// gives as much as it takes, which keeps the image's energy). A pixel
// whose camera ray meets nothing, or a lamp (whose light is not noise), is
// kept as it is and never mixed with the others. Taps outside the image
// weigh zero.
T0_INLINE FilterPixel atrous_pixel(T0_GLOBAL const FilterPixel* in, T0_GLOBAL const FilterTap* taps,
                                   T0_GLOBAL const FilterNoise* noise, int width, int height, int x,
                                   int y, int pass) {
    const int i = y * width + x;
    const FilterPixel centre = in[i];
    const FilterTap c = taps[i];
    if (c.params.w > 0.0f) {
        return centre;
    }
    const int step = 1 << pass;
    const float l = noise[i].value.x;
    const float by_noise = noise[i].value.y;
    const float by_depth = c.params.y / (float)step;
    float3 sum = float3_splat(0.0f);
    float variance = 0.0f;
    float total = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        const int qy = y + dy * step;
        const int inside_y = qy >= 0 && qy < height;
        const int cy = clamp_index(qy, 0, height - 1);
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx * step;
            const int q = cy * width + clamp_index(qx, 0, width - 1);
            const float inside = inside_y && qx >= 0 && qx < width ? 1.0f : 0.0f;
            const FilterPixel p = in[q];
            const FilterTap t = taps[q];
            const FilterNoise n = noise[q];
            const float w =
                inside * tap_weight(c.normal.x, c.normal.y, c.normal.z, c.normal.w, c.params.x, l,
                                    by_noise, by_depth, t.normal.x, t.normal.y, t.normal.z,
                                    t.normal.w, t.params.x, t.params.z, n.value.x, n.value.y,
                                    p.value.x + p.value.y + p.value.z + p.value.w,
                                    wavelet_weight(dx, dy), tap_reach(dx, dy));
            if (w > 0.0f) {
                const float4 v = p.value;
                sum += xyz(v) * w;
                variance += w * w * v.w;
                total += w;
            }
        }
    }
    return atrous_result(centre, c, sum, variance, total);
}

T0_NAMESPACE_END

#endif
