// The CPU backend's loop over one tile of the image (C++ only: the OpenCL
// program renders one pixel per work item, render_pixel). Here, not in
// cpu_backend.cpp, so that a program can compile two versions of the
// kernel headers side by side and time exactly what the backend runs
// (benchmarks/ab_kernels.sh).
#ifndef TRAC0R_KERNEL_TILE_H
#define TRAC0R_KERNEL_TILE_H

#include "tile_grid.h"
#include "trace.h"

#ifndef __OPENCL_VERSION__

T0_NAMESPACE_BEGIN

// With the BVH, a tile of at most T0_TILE x T0_TILE pixels: every pixel's
// generator and camera ray first, then the leaves that the camera rays may
// enter, found once for all of them (bundle_leaves), then each path from
// its camera ray's hit among those leaves (camera_hit): the same hits as
// traversal, in less time (kernel/tuning.h; docs/performance.md, "Camera
// rays per tile"). Whether it rendered the tile: not through a thin lens,
// whose rays start all over the aperture, not at one point.
inline bool render_tile_bundled(const SceneView* scene, CameraRecord cam, AccumPixel* accum,
                                t0_u64 seed, t0_u32 frame, int max_depth, long x0, long y0, long x1,
                                long y1, long width) {
    if (!T0_HAS_FEATURE(scene, T0_FEATURE_BVH) || (x1 - x0) * (y1 - y0) > T0_TILE * T0_TILE ||
        cam.extent.z > 0.0f) {
        return false;
    }
    PixelSample samples[T0_TILE * T0_TILE];
    RayBundle bundle;
    bundle_start(&bundle, xyz(cam.position));
    int n = 0;
    for (long y = y0; y < y1; ++y) {
        for (long x = x0; x < x1; ++x, ++n) {
            begin_pixel(scene, cam, (t0_u32)(y * width + x), seed, frame, &samples[n]);
            if (!samples[n].ray.any_parallel) {
                bundle_add(&bundle, samples[n].ray.inv_direction);
            }
        }
    }
    LeafCandidate leaves[T0_BUNDLE_LEAVES];
    const int count = bundle_finish_leaves(scene, &bundle, leaves);
    n = 0;
    for (long y = y0; y < y1; ++y) {
        for (long x = x0; x < x1; ++x, ++n) {
            PixelSample* s = &samples[n];
            const Hit first = camera_hit(scene, &s->ray, leaves, count);
            accumulate_sample(&accum[y * width + x],
                              trace_path_from(scene, s->ray, first, max_depth, &s->sampler));
        }
    }
    return true;
}

// One sample of each pixel of `tile` (tile_rect) of an image `width`
// pixels wide, in order, each pixel's random numbers and camera ray
// made before the path of the pixel before it is traced, so that their
// latency overlaps that path (docs/performance.md, "Camera rays per
// tile"); with the BVH, as render_tile_bundled.
inline void render_tile(const SceneView* scene, CameraRecord cam, AccumPixel* accum, t0_u64 seed,
                        t0_u32 frame, int max_depth, TileRect tile, long width) {
    const long x0 = tile.x0;
    const long y0 = tile.y0;
    const long x1 = tile.x1;
    const long y1 = tile.y1;
    // An orthographic camera's rays start all over the image plane, not at
    // one point: no bundle (tested here, not in render_tile_bundled, where
    // the test cost 1 % of a frame on cornell_diffuse.json by changing how
    // the compiler laid the function out; benchmarks/ab_kernels.sh).
    if (!camera_is_orthographic(cam) &&
        render_tile_bundled(scene, cam, accum, seed, frame, max_depth, x0, y0, x1, y1, width)) {
        return;
    }
    PixelSample samples[2];
    int current = 0;
    t0_u32 pixel = (t0_u32)(y0 * width + x0);
    begin_pixel(scene, cam, pixel, seed, frame, &samples[current]);
    for (long y = y0; y < y1; ++y) {
        for (long x = x0; x < x1; ++x) {
            const t0_u32 this_pixel = pixel;
            const bool last = x + 1 == x1 && y + 1 == y1;
            if (!last) {
                pixel = (t0_u32)(x + 1 < x1 ? y * width + x + 1 : (y + 1) * width + x0);
                begin_pixel(scene, cam, pixel, seed, frame, &samples[1 - current]);
            }
            finish_pixel(scene, accum, this_pixel, max_depth, &samples[current]);
            current = 1 - current;
        }
    }
}

T0_NAMESPACE_END

#endif

#endif
