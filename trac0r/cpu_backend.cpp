#include "trac0r/cpu_backend.h"

#include "trac0r/cpu_bdpt.h"

#include "trac0r/kernel/tile.h"
#include "trac0r/packed_scene.h"

#include <omp.h>

#include <atomic>
#include <cstdint>
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

struct CpuBackend::State {
    PackedScene scene;
    std::vector<kernel::AccumPixel> accum;
    // Bidirectional path tracing: each pixel's own light in a frame, and
    // the light subpaths' splats (kernel/splat.h), four sums a pixel.
    std::vector<glm::vec4> frame_radiance;
    std::vector<std::int64_t> splats;
};

CpuBackend::CpuBackend(int threads)
    : Backend("cpu", openmp_device(thread_count(threads))),
      threads_(thread_count(threads)),
      state_(new State) {}

CpuBackend::~CpuBackend() = default;

void CpuBackend::set_scene(const PackedScene& scene) { state_->scene = scene; }

void CpuBackend::reset(int width, int height) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    state_->accum.assign(pixels, kernel::AccumPixel{});
    // BDPT's buffers: sized by its first frame (render_bdpt_frame).
    state_->frame_radiance.clear();
    state_->splats.clear();
}

void CpuBackend::render_frame(const kernel::CameraRecord& camera, std::uint64_t seed,
                              std::uint32_t frame, int max_depth) {
    render_frame_cancellable(camera, seed, frame, max_depth, CancelCheck());
}

bool CpuBackend::render_frame_cancellable(const kernel::CameraRecord& camera, std::uint64_t seed,
                                          std::uint32_t frame, int max_depth,
                                          const CancelCheck& cancel) {
    const kernel::SceneView view = state_->scene.view();
    const kernel::CameraRecord scaled = scaled_camera(camera, state_->scene.scale);
    const long pixel_count = static_cast<long>(state_->accum.size());
    kernel::AccumPixel* accum = state_->accum.data();
    // Tiles of 8 x 8 pixels (T0_TILE), handed out dynamically: neighbouring
    // rays visit the same nodes and triangles (cache), and with the BVH share
    // the leaves their camera rays may enter (render_tile); and the image's
    // regions differ a lot in cost (background against glass).
    const std::uint32_t width = camera.size.x;
    const std::uint32_t height = static_cast<std::uint32_t>(pixel_count / width);
    const long tile_count = kernel::tile_count(width, height);
    // Asked before each tile; once it says stop, the remaining tiles are
    // skipped (an OpenMP loop cannot be left early), each at the cost of a
    // load.
    std::atomic<bool> cancelled(false);
    if ((state_->scene.features & T0_FEATURE_BDPT) != 0u) {
        return render_bdpt_frame(view, scaled, seed, frame, max_depth, threads_, state_->accum,
                                 state_->frame_radiance, state_->splats, cancel);
    }
#pragma omp parallel num_threads(threads_)
    {
        const DenormalsAreZero denormals;  // in every thread of the team
#pragma omp for schedule(dynamic, 1)
        for (long t = 0; t < tile_count; ++t) {
            if (cancel && (cancelled.load(std::memory_order_relaxed) || cancel())) {
                cancelled.store(true, std::memory_order_relaxed);
                continue;
            }
            const kernel::TileRect rect =
                kernel::tile_rect(static_cast<std::uint32_t>(t), width, height);
            kernel::render_tile(&view, scaled, accum, seed, frame, max_depth, rect, width);
        }
    }
    return !cancelled.load();
}

void CpuBackend::read_accumulator(std::vector<kernel::AccumPixel>& out) { out = state_->accum; }

}  // namespace trac0r
