// Temporal reuse while the camera moves, as today's real-time path tracers
// do it (SVGF's temporal part, Schied et al. 2017): each pixel of the new
// view finds where its first hit was in the previous displayed frame
// (through the previous camera) and takes that frame's colour as history,
// where the previous frame saw the same surface there (depth and normal
// agree); where it did not (a disocclusion, the edge of the view) the
// pixel starts again from the new samples alone. The history is blended
// with the new samples as a running mean whose history part is capped, so
// that stale light (a glossy highlight that moved) fades.
//
// A display aid only: the accumulation is never touched.
#ifndef TRAC0R_KERNEL_TEMPORAL_H
#define TRAC0R_KERNEL_TEMPORAL_H

#include "compat.h"
#include "filter.h"
#include "ray.h"
#include "trace.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// A history tap counts where its depth is within this fraction of the
// reprojected point's, plus what the depth changes over the two pixels'
// distance at the tap; and its normal within acos(this) of the pixel's.
#define T0_TEMPORAL_DEPTH_TOLERANCE 0.02f
#define T0_TEMPORAL_NORMAL_COS 0.9f

// A displayed pixel: xyz its linear radiance, w how many samples stand
// behind it (0: none, nothing to reuse).
typedef struct T0_ALIGN16 TemporalPixel {
    float4 value;
} TemporalPixel;

// What reprojection reads of a pixel: xyz the unit normal of the first
// non-specular surface, facing the camera (zero: none), w the first hit's
// depth along the camera's forward axis (T0_NO_HIT: the ray met nothing).
typedef struct T0_ALIGN16 TemporalGuide {
    float4 normal_depth;
} TemporalGuide;

#ifndef __OPENCL_VERSION__
T0_STATIC_ASSERT_SIZE(TemporalPixel, 16);
T0_STATIC_ASSERT_SIZE(TemporalGuide, 16);
#endif

// How much the depth of history pixel (x, y) changes to a neighbour: on
// each axis the smaller of the one-sided changes (the filter's axis_slope:
// at a silhouette the flat side counts, not the jump), the larger over the
// two axes.
T0_INLINE float temporal_depth_slope(T0_GLOBAL const TemporalGuide* guides, int width, int height,
                                     int x, int y) {
    const int i = y * width + x;
    const float z = guides[i].normal_depth.w;
    const float left = x > 0 ? guides[i - 1].normal_depth.w : T0_NO_HIT;
    const float right = x + 1 < width ? guides[i + 1].normal_depth.w : T0_NO_HIT;
    const float up = y > 0 ? guides[i - width].normal_depth.w : T0_NO_HIT;
    const float down = y + 1 < height ? guides[i + width].normal_depth.w : T0_NO_HIT;
    return fmax(axis_slope(z, left, right), axis_slope(z, up, down));
}

// Whether history pixel q saw the surface that pixel `here` sees at depth
// `depth` along the previous camera's axis: a hit there too, within the
// tolerance and within what the depth changes over the at most two pixels
// between the tap and the point (`slopes`: each history pixel's
// temporal_depth_slope, made once with its frame), with a normal that
// agrees.
T0_INLINE int temporal_tap_matches(TemporalGuide here, T0_GLOBAL const TemporalGuide* guides,
                                   T0_GLOBAL const float* slopes, int q, float depth) {
    const TemporalGuide tap = guides[q];
    if (!(tap.normal_depth.w < T0_NO_HIT)) {
        return 0;
    }
    const float tolerance = T0_TEMPORAL_DEPTH_TOLERANCE * depth + 2.0f * slopes[q];
    if (!(fabs(tap.normal_depth.w - depth) <= tolerance)) {
        return 0;
    }
    const float3 n = xyz(here.normal_depth);
    const float3 m = xyz(tap.normal_depth);
    const int has_n = dot(n, n) > 0.0f;
    const int has_m = dot(m, m) > 0.0f;
    return has_n && has_m ? dot(n, m) >= T0_TEMPORAL_NORMAL_COS : has_n == has_m;
}

// The history at pixel (x, y) of the view `camera` (whose guide is `here`):
// the previous frame (`previous`, its pixels, guides and depth slopes)
// bilinearly at the place where this pixel's first hit was, over the taps
// that saw the same surface. `offset` is camera.position - previous.position (taken by the
// caller once: every point is then relative to the previous camera). w is
// 0 where there is no history: a disocclusion, a point outside or behind
// the previous view.
T0_INLINE float4 reproject_history(CameraRecord camera, CameraRecord previous, float3 offset,
                                   T0_GLOBAL const TemporalPixel* history,
                                   T0_GLOBAL const TemporalGuide* history_guides,
                                   T0_GLOBAL const float* history_slopes, TemporalGuide here, int x,
                                   int y) {
    const float4 none = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    // A ray that met nothing sees the black background: nothing to carry
    // over (its only light is a sample that caught a silhouette's edge, and
    // carried over, such samples would trail behind a moving edge).
    if (!(here.normal_depth.w < T0_NO_HIT)) {
        return none;
    }
    const Ray ray = camera_ray(camera, (float)x, (float)y, 0.5f, 0.5f);
    // The first hit, relative to the previous camera (an orthographic
    // camera's rays start away from its position).
    const float t = here.normal_depth.w / dot(ray.direction, xyz(camera.forward));
    const float3 p = offset + (ray.origin - xyz(camera.position)) + ray.direction * t;
    const float depth = dot(p, xyz(previous.forward));
    if (!(depth > 0.0f)) {
        return none;
    }
    const float width = (float)previous.size.x;
    const float height = (float)previous.size.y;
    // Where the previous view saw p: on its image plane at distance one,
    // or, orthographic, on the plane through its position.
    const float scale = camera_is_orthographic(previous) ? 1.0f : depth;
    const float sx = dot(p, xyz(previous.right)) / (scale * previous.extent.x);
    const float sy = dot(p, xyz(previous.up)) / (scale * previous.extent.y);
    // Continuous pixel coordinates of the previous image, less half a pixel:
    // the taps are the four pixel centres around it.
    const float u = (sx + 1.0f) * 0.5f * width - 0.5f;
    const float v = (1.0f - sy) * 0.5f * height - 0.5f;
    if (!(u > -1.0f && v > -1.0f && u < width && v < height)) {
        return none;
    }
    const int x0 = (int)floor(u);
    const int y0 = (int)floor(v);
    const float fx = u - (float)x0;
    const float fy = v - (float)y0;
    float3 sum = float3_splat(0.0f);
    float samples = 0.0f;
    float total = 0.0f;
    for (int j = 0; j <= 1; ++j) {
        const int ty = y0 + j;
        if (ty < 0 || ty >= (int)previous.size.y) {
            continue;
        }
        for (int i = 0; i <= 1; ++i) {
            const int tx = x0 + i;
            if (tx < 0 || tx >= (int)previous.size.x) {
                continue;
            }
            const int q = ty * (int)previous.size.x + tx;
            const TemporalPixel h = history[q];
            // A tap that is not finite is left out: it would spread to its
            // neighbours every frame.
            if (!(h.value.w > 0.0f) || !is_finite_f(h.value.x + h.value.y + h.value.z) ||
                !temporal_tap_matches(here, history_guides, history_slopes, q, depth)) {
                continue;
            }
            const float w = (i ? fx : 1.0f - fx) * (j ? fy : 1.0f - fy);
            sum += xyz(h.value) * w;
            samples += h.value.w * w;
            total += w;
        }
    }
    // Too little of the history saw this point (the last sliver of a tap
    // across an edge): none rather than an amplified corner.
    if (!(total > 0.05f)) {
        return none;
    }
    const float3 colour = sum / total;
    return make_float4(colour.x, colour.y, colour.z, samples / total);
}

// The new displayed pixel: the history (as reproject_history gives it,
// counting at most `max_history` samples) and `current`, the mean of
// `samples` new samples, as one running mean.
T0_INLINE TemporalPixel temporal_blend_pixel(float4 history, float3 current, float samples,
                                             float max_history) {
    const float n = fmin(history.w, max_history);
    TemporalPixel out;
    const float total = n + samples;
    const float3 mean = total > 0.0f ? (xyz(history) * n + current * samples) / total : current;
    out.value = make_float4(mean.x, mean.y, mean.z, total);
    return out;
}

T0_NAMESPACE_END

#endif
