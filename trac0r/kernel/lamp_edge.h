// The share of a pixel that sees a lamp, and the lamp's light over it, as
// the render's samples see it (a box filter): what the display filter sets
// apart from the lighting it smooths (trac0r/guides.cpp, add_lamp_edges).
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

T0_NAMESPACE_END

#endif
