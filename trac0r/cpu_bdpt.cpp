// The CPU backend's bidirectional path tracing frame (kernel/bdpt.h), in a
// file of its own: the kernel headers it includes stay out of the
// translation unit of the path tracer's tile loop (cpu_backend.cpp), whose
// code the compiler then lays out as before.
#include "trac0r/cpu_bdpt.h"

#include "trac0r/kernel/bdpt.h"

#include <omp.h>

#include <algorithm>
#include <atomic>

namespace trac0r {

// Every pixel's sample first (its light subpath's splats land anywhere),
// in chunks of 64 pixels handed out dynamically; then every pixel's merge.
bool render_bdpt_frame(const kernel::SceneView& view, const kernel::CameraRecord& camera,
                       std::uint64_t seed, std::uint32_t frame, int max_depth, int threads,
                       std::vector<kernel::AccumPixel>& accumulator,
                       std::vector<glm::vec4>& frame_radiance,
                       std::vector<std::int64_t>& splat_sums, const Backend::CancelCheck& cancel) {
    const long pixels = static_cast<long>(accumulator.size());
    if (splat_sums.size() != 4 * accumulator.size()) {
        frame_radiance.assign(accumulator.size(), glm::vec4(0.0f));
        splat_sums.assign(4 * accumulator.size(), 0);
    }
    glm::vec4* radiance = frame_radiance.data();
    kernel::t0_i64* splats = splat_sums.data();
    kernel::AccumPixel* accum = accumulator.data();
    const long chunk = 64;
    const long chunks = (pixels + chunk - 1) / chunk;
    std::atomic<bool> cancelled(false);
#pragma omp parallel num_threads(threads)
    {
        const DenormalsAreZero denormals;
#pragma omp for schedule(dynamic, 1)
        for (long c = 0; c < chunks; ++c) {
            if (cancel && (cancelled.load(std::memory_order_relaxed) || cancel())) {
                cancelled.store(true, std::memory_order_relaxed);
                continue;
            }
            const long end = std::min(pixels, (c + 1) * chunk);
            for (long p = c * chunk; p < end; ++p) {
                kernel::bdpt_sample(&view, camera, static_cast<std::uint32_t>(p), seed, frame,
                                    max_depth, kernel::bdpt_all_strategies(), radiance, splats);
            }
        }
        if (!cancelled.load()) {
#pragma omp for schedule(static)
            for (long p = 0; p < pixels; ++p) {
                kernel::bdpt_merge(accum, radiance, splats, static_cast<std::uint32_t>(p));
            }
        }
    }
    if (cancelled.load()) {
        splat_sums.clear();
        return false;
    }
    return true;
}

}  // namespace trac0r
