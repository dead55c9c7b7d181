#include "trac0r/cpu_backend.h"

#include "trac0r/kernel/trace.h"

#include <omp.h>

namespace trac0r {

CpuBackend::CpuBackend(int threads) : threads_(threads > 0 ? threads : omp_get_max_threads()) {}

std::string CpuBackend::device() const {
    return "OpenMP, " + std::to_string(threads_) + " thread" + (threads_ == 1 ? "" : "s");
}

void CpuBackend::set_scene(const PackedScene& scene) { scene_ = scene; }

void CpuBackend::reset(int width, int height) {
    accum_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                  kernel::AccumPixel{});
}

void CpuBackend::render_frame(const kernel::CameraRecord& camera, std::uint64_t seed,
                              std::uint32_t frame, int max_depth) {
    const kernel::SceneView view = scene_.view();
    const long pixel_count = static_cast<long>(accum_.size());
    kernel::AccumPixel* accum = accum_.data();
    // Rows of the image differ a lot in cost (sky against glass), so hand
    // out small chunks dynamically.
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads_)
    for (long pixel = 0; pixel < pixel_count; ++pixel) {
        kernel::render_pixel(&view, camera, accum, static_cast<std::uint32_t>(pixel), seed, frame,
                             max_depth);
    }
}

void CpuBackend::read_accumulator(std::vector<kernel::AccumPixel>& out) { out = accum_; }

}  // namespace trac0r
