// The CPU backend's loop over one tile of the image (C++ only: the OpenCL
// program renders one pixel per work item, render_pixel). Here, not in
// cpu_backend.cpp, so that a program can compile two versions of the
// kernel headers side by side and time exactly what the backend runs
// (benchmarks/ab_kernels.sh).
#ifndef TRAC0R_KERNEL_TILE_H
#define TRAC0R_KERNEL_TILE_H

#include "trace.h"

#ifndef __OPENCL_VERSION__

T0_NAMESPACE_BEGIN

// One sample of each pixel of the tile [x0, x1) x [y0, y1) of an image
// `width` pixels wide, in order, each pixel's random numbers and camera ray
// made before the path of the pixel before it is traced, so that their
// latency overlaps that path (README, "Each pixel's camera ray made
// ahead").
inline void render_tile(const SceneView* scene, CameraRecord cam, AccumPixel* accum, t0_u64 seed,
                        t0_u32 frame, int max_depth, long x0, long y0, long x1, long y1,
                        long width) {
    PixelSample samples[2];
    int current = 0;
    t0_u32 pixel = (t0_u32)(y0 * width + x0);
    begin_pixel(cam, pixel, seed, frame, &samples[current]);
    for (long y = y0; y < y1; ++y) {
        for (long x = x0; x < x1; ++x) {
            const t0_u32 this_pixel = pixel;
            const bool last = x + 1 == x1 && y + 1 == y1;
            if (!last) {
                pixel = (t0_u32)(x + 1 < x1 ? y * width + x + 1 : (y + 1) * width + x0);
                begin_pixel(cam, pixel, seed, frame, &samples[1 - current]);
            }
            finish_pixel(scene, accum, this_pixel, max_depth, &samples[current]);
            current = 1 - current;
        }
    }
}

T0_NAMESPACE_END

#endif

#endif
