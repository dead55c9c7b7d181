#include "trac0r/cpu_backend.h"

#include "trac0r/kernel/tile.h"

#include <omp.h>

#include <algorithm>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace trac0r {

#if defined(__SSE__)
// MXCSR bit 15: flush to zero (denormal results); bit 6: denormals are
// zero (denormal inputs).
DenormalsAreZero::DenormalsAreZero() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }
DenormalsAreZero::~DenormalsAreZero() { _mm_setcsr(saved_); }
#else
DenormalsAreZero::DenormalsAreZero() : saved_(0) {}
DenormalsAreZero::~DenormalsAreZero() {}
#endif

namespace {

int thread_count(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

std::string openmp_device(int threads) {
    return "OpenMP, " + std::to_string(threads) + " thread" + (threads == 1 ? "" : "s");
}

}  // namespace

CpuBackend::CpuBackend(int threads)
    : Backend("cpu", openmp_device(thread_count(threads))), threads_(thread_count(threads)) {}

void CpuBackend::set_scene(const PackedScene& scene) { scene_ = scene; }

void CpuBackend::reset(int width, int height) {
    accum_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                  kernel::AccumPixel{});
}

void CpuBackend::render_frame(const kernel::CameraRecord& camera, std::uint64_t seed,
                              std::uint32_t frame, int max_depth) {
    const kernel::SceneView view = scene_.view();
    const kernel::CameraRecord scaled = scaled_camera(camera, scene_.scale);
    const long pixel_count = static_cast<long>(accum_.size());
    kernel::AccumPixel* accum = accum_.data();
    // Tiles of 8 x 8 pixels (T0_TILE), handed out dynamically: neighbouring
    // rays visit the same nodes and triangles (cache), and with the BVH share
    // the leaves their camera rays may enter (render_tile); and the image's
    // regions differ a lot in cost (background against glass).
    const long width = static_cast<long>(camera.size.x);
    const long height = pixel_count / width;
    const long tile = T0_TILE;
    const long tiles_x = (width + tile - 1) / tile;
    const long tile_count = tiles_x * ((height + tile - 1) / tile);
#pragma omp parallel num_threads(threads_)
    {
        const DenormalsAreZero denormals;  // in every thread of the team
#pragma omp for schedule(dynamic, 1)
        for (long t = 0; t < tile_count; ++t) {
            const long x0 = (t % tiles_x) * tile;
            const long y0 = (t / tiles_x) * tile;
            const long x1 = std::min(x0 + tile, width);
            const long y1 = std::min(y0 + tile, height);
            kernel::render_tile(&view, scaled, accum, seed, frame, max_depth, x0, y0, x1, y1,
                                width);
        }
    }
}

void CpuBackend::read_accumulator(std::vector<kernel::AccumPixel>& out) { out = accum_; }

}  // namespace trac0r
