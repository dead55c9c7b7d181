// The share of a pixel that sees a lamp, and the lamp's light over it, as
// the render's samples see it (a box filter): what the display filter sets
// apart from the lighting it smooths (trac0r/guides.cpp, add_lamp_edges):
// by T0_GUIDE_EMISSION_RAYS rays over the pixel (pixel_emission), or, where
// one straight edge of a lamp crosses it, from where that edge crosses the
// pixel's sides (straight_edge_emission).
// Each ray is a guide ray (guides.h): it goes on through mirrors and glass
// to the first surface that is neither.
#ifndef TRAC0R_KERNEL_LAMP_EDGE_H
#define TRAC0R_KERNEL_LAMP_EDGE_H

#include "guides.h"

T0_NAMESPACE_BEGIN

// Rays per pixel of pixel_emission: enough that a lamp's edge across a
// pixel is placed to about 1 % of it (the raw render's box filter sees the
// exact share).
#define T0_GUIDE_EMISSION_RAYS 256

// Rays per pixel that first test whether a lamp's edge crosses it at all
// (trac0r/guides.cpp, add_lamp_edges).
#define T0_GUIDE_PROBE_RAYS 16

// Ray i's point in a pixel: the R2 sequence (Roberts 2018), whose points
// place an edge of any slope evenly.
T0_INLINE float2 r2_point(int i) {
    const float fi = (float)i;
    const float jx = 0.5f + fi * 0.7548776662f;
    const float jy = 0.5f + fi * 0.5698402910f;
    return make_float2(jx - floor(jx), jy - floor(jy));
}

// Ray i of pixel (x, y)'s r2_point sequence: the camera ray through that
// point of the pixel.
T0_INLINE Ray pixel_emission_ray(CameraRecord camera, t0_u32 x, t0_u32 y, int i) {
    const float2 j = r2_point(i);
    return camera_ray(camera, (float)x, (float)y, j.x, j.y);
}

// One ray's part of pixel_emission_rays' sums, from its guides and the
// radiance it met (guide_ray_from).
T0_INLINE void add_emission_ray(GuidePixel g, float3 emitted, float3* sum, int* hits) {
    if (g.normal.w > 0.0f) {
        *sum += emitted;
        ++*hits;
    }
}

// Rays first to last - 1 of pixel (x, y)'s r2_point sequence, each traced
// alone: adds to *sum the radiance of the pure emitters they meet first
// (through mirrors and glass) and to *hits how many meet one. (The CPU's
// lamp-edge split finds a pixel's first hits together instead:
// trac0r/guides.cpp.)
T0_INLINE void pixel_emission_rays(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y,
                                   int first, int last, float3* sum, int* hits) {
    for (int i = first; i < last; ++i) {
        const Ray ray = pixel_emission_ray(camera, x, y, i);
        float3 emitted;
        const GuidePixel g =
            guide_ray_from(scene, camera, ray, intersect_scene(scene, &ray), &emitted);
        add_emission_ray(g, emitted, sum, hits);
    }
}

// pixel_emission's result from pixel_emission_rays' sum and hits over
// `rays` rays.
T0_INLINE float4 pixel_emission_of(float3 sum, int hits, int rays) {
    const float3 mean = sum / (float)rays;
    return make_float4(mean.x, mean.y, mean.z, (float)hits / (float)rays);
}

// Over pixel (x, y), as its samples see it (a box filter): xyz the mean
// radiance of the pure emitters that its rays meet first, w the share of
// the pixel that meets one; from its first `rays` rays.
T0_INLINE float4 pixel_emission(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y,
                                int rays) {
    float3 sum = float3_splat(0.0f);
    int hits = 0;
    pixel_emission_rays(scene, camera, x, y, 0, rays, &sum, &hits);
    return pixel_emission_of(sum, hits, rays);
}

// ---- A straight lamp edge across a pixel --------------------------------
//
// Where one straight edge of a lamp crosses a pixel (two of the pixel's
// sides, a lamp's outline seen directly), its share of the pixel is the
// area on the lamp's side of the line through the two points where it
// crosses them, each found by bisection along its side: 2 x
// T0_GUIDE_EDGE_STEPS rays, and the T0_GUIDE_PROBE_RAYS and 6 rays beside
// the line that check it, where pixel_emission takes
// T0_GUIDE_EMISSION_RAYS and places the edge to about 1 % of the pixel.

// Bisection steps along a side: the crossing to 2^-11 of the side, its
// share to about 5e-4 of the pixel.
#define T0_GUIDE_EDGE_STEPS 10

// How far from the line through the crossings (in pixels) the rays that
// check it is straight lie: an outline that strays less from it errs by at
// most this times the line's length in the share (about 0.011).
#define T0_GUIDE_EDGE_OFFSET (1.0f / 128.0f)

// Corner k of a pixel, going round it: (0, 0), (1, 0), (1, 1), (0, 1), in
// the pixel's own coordinates (x right, y down, as a jitter).
T0_INLINE float2 pixel_corner(int k) {
    return make_float2(k == 1 || k == 2 ? 1.0f : 0.0f, k >= 2 ? 1.0f : 0.0f);
}

// Which of pixel (x, y)'s corners (pixel_corner) see a pure emitter first:
// bit k for corner k.
T0_INLINE int pixel_corner_lamps(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y) {
    int mask = 0;
    for (int k = 0; k < 4; ++k) {
        const float2 c = pixel_corner(k);
        float3 emitted;
        const GuidePixel g =
            guide_ray(scene, camera, x + (t0_u32)c.x, y + (t0_u32)c.y, 0.0f, 0.0f, &emitted);
        mask |= g.normal.w > 0.0f ? 1 << k : 0;
    }
    return mask;
}

// What the rays of straight_edge_emission met: the lamps' radiance, the
// same on every ray that met one (else the pixel is not one lamp's edge).
typedef struct EdgeRadiance {
    float3 radiance;
    int seen;  // a ray met a lamp, and radiance is its
    int same;  // every ray that met one met this radiance
} EdgeRadiance;

// Whether the ray through point p of pixel (x, y) meets a pure emitter
// first; its radiance into *r.
T0_INLINE int edge_ray_lamp(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y,
                            float2 p, EdgeRadiance* r) {
    float3 emitted;
    const GuidePixel g = guide_ray(scene, camera, x, y, p.x, p.y, &emitted);
    if (!(g.normal.w > 0.0f)) {
        return 0;
    }
    if (!r->seen) {
        r->radiance = emitted;
        r->seen = 1;
    } else if (emitted.x != r->radiance.x || emitted.y != r->radiance.y ||
               emitted.z != r->radiance.z) {
        r->same = 0;
    }
    return 1;
}

// Where the edge crosses the side from corner a to corner b, a on the
// side whose lamp flag is a_lamp and b on the other: by bisection.
T0_INLINE float2 edge_crossing(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y,
                               float2 a, float2 b, int a_lamp, EdgeRadiance* r) {
    float lo = 0.0f;
    float hi = 1.0f;
    for (int i = 0; i < T0_GUIDE_EDGE_STEPS; ++i) {
        const float mid = 0.5f * (lo + hi);
        if (edge_ray_lamp(scene, camera, x, y, a + (b - a) * mid, r) == a_lamp) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return a + (b - a) * (0.5f * (lo + hi));
}

// The z of the cross product (q - p) x (r - p): which side of the line
// from p through q the point r lies on, times the line's length.
T0_INLINE float line_side(float2 p, float2 q, float2 r) {
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
}

// Over pixel (x, y), whose corners see a lamp where `corners` says
// (pixel_corner_lamps) and whose centre ray does where centre_lamp:
// pixel_emission's value (xyz the lamps' mean radiance over the pixel, w
// the share that sees one) where one straight lamp edge crosses it, from
// the line through the two crossings. Returns 0, *out untouched, where
// that is not what the pixel holds: the corners do not form two runs (a
// lamp's corner or a thin lamp inside), the centre, one of the
// T0_GUIDE_PROBE_RAYS rays over the pixel (pixel_emission's first) or one
// of six rays beside the line lies on the other side of it from what it
// sees (a bent or a second edge), or the rays that meet a lamp do not all
// meet the same radiance.
T0_INLINE int straight_edge_emission(const SceneView* scene, CameraRecord camera, t0_u32 x,
                                     t0_u32 y, int corners, int centre_lamp, float4* out) {
    // The sides where the corners change: exactly two.
    int changes = 0;
    int first_side = -1;
    int second_side = -1;
    for (int k = 0; k < 4; ++k) {
        const int a = (corners >> k) & 1;
        const int b = (corners >> ((k + 1) & 3)) & 1;
        if (a != b) {
            if (changes == 0) {
                first_side = k;
            } else {
                second_side = k;
            }
            ++changes;
        }
    }
    if (changes != 2) {
        return 0;
    }
    EdgeRadiance r;
    r.radiance = float3_splat(0.0f);
    r.seen = 0;
    r.same = 1;
    const float2 p =
        edge_crossing(scene, camera, x, y, pixel_corner(first_side),
                      pixel_corner((first_side + 1) & 3), (corners >> first_side) & 1, &r);
    const float2 q =
        edge_crossing(scene, camera, x, y, pixel_corner(second_side),
                      pixel_corner((second_side + 1) & 3), (corners >> second_side) & 1, &r);
    // The lamp's side of the line: that of a corner that sees it.
    int lamp_corner = 0;
    while (!((corners >> lamp_corner) & 1)) {
        ++lamp_corner;
    }
    const float lamp_side = line_side(p, q, pixel_corner(lamp_corner));
    // A ray within 1/256 of a pixel of the line may fall either way: its
    // disagreement is no evidence (line_side is the distance times the
    // line's length).
    const float band = (1.0f / 256.0f) * length(q - p);
    // The centre and the probes must agree with the line.
    const float centre_side = line_side(p, q, make_float2(0.5f, 0.5f));
    if (fabs(centre_side) > band && (centre_side * lamp_side > 0.0f) != (centre_lamp != 0)) {
        return 0;
    }
    for (int i = 0; i < T0_GUIDE_PROBE_RAYS; ++i) {
        const float2 point = r2_point(i);
        const int lamp = edge_ray_lamp(scene, camera, x, y, point, &r);
        const float side = line_side(p, q, point);
        if (fabs(side) > band && (side * lamp_side > 0.0f) != (lamp != 0)) {
            return 0;
        }
    }
    // Along the line, rays just either side of it at a quarter, half and
    // three quarters: a lamp's corner inside the pixel bends the outline
    // away from the line through the crossings, and the rays of the side it
    // bends to see the other side's.
    const float2 along = q - p;
    const float chord = length(along);
    const float2 normal = make_float2(-along.y, along.x) * (T0_GUIDE_EDGE_OFFSET / chord);
    for (int i = 1; i <= 3; ++i) {
        const float2 on = p + along * (0.25f * (float)i);
        for (int sign = -1; sign <= 1; sign += 2) {
            const float2 point = on + normal * (float)sign;
            const int lamp = edge_ray_lamp(scene, camera, x, y, point, &r);
            if ((line_side(p, q, point) * lamp_side > 0.0f) != (lamp != 0)) {
                return 0;
            }
        }
    }
    // (A ray beside the line on the lamp's side met the lamp: r.seen.)
    if (!r.seen || !r.same) {
        return 0;
    }
    // The lamp's part of the square: its corners on the lamp's side and the
    // two crossings, in order round the pixel (the shoelace formula).
    float2 polygon[6];
    int n = 0;
    for (int k = 0; k < 4; ++k) {
        if ((corners >> k) & 1) {
            polygon[n++] = pixel_corner(k);
        }
        if (k == first_side) {
            polygon[n++] = p;
        } else if (k == second_side) {
            polygon[n++] = q;
        }
    }
    float twice_area = 0.0f;
    for (int k = 0; k < n; ++k) {
        const float2 a = polygon[k];
        const float2 b = polygon[(k + 1) % n];
        twice_area += a.x * b.y - b.x * a.y;
    }
    const float share = fmin(fmax(0.5f * fabs(twice_area), 0.0f), 1.0f);
    const float3 mean = r.radiance * share;
    *out = make_float4(mean.x, mean.y, mean.z, share);
    return 1;
}

T0_NAMESPACE_END

#endif
