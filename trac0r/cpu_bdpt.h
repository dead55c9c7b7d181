// The CPU backend's bidirectional path tracing frame (cpu_bdpt.cpp).
#ifndef TRAC0R_CPU_BDPT_H
#define TRAC0R_CPU_BDPT_H

#include "trac0r/backend.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/types.h"

#include <cstdint>
#include <vector>

namespace trac0r {

// One frame of kernel::bdpt_sample over every pixel of `accumulator` on
// `threads` OpenMP threads, then each pixel's merge (its splats added to
// its sample, accumulated); frame_radiance and splat_sums (four a pixel)
// are the frame's buffers, sized (zeroed) here where they do not fit: the
// backend's reset empties them. Asks `cancel` before each chunk of 64
// pixels; false when it stopped: the accumulator is as it was, and the
// part of the frame's splats is dropped with splat_sums.
bool render_bdpt_frame(const kernel::SceneView& view, const kernel::CameraRecord& camera,
                       std::uint64_t seed, std::uint32_t frame, int max_depth, int threads,
                       std::vector<kernel::AccumPixel>& accumulator,
                       std::vector<glm::vec4>& frame_radiance,
                       std::vector<std::int64_t>& splat_sums, const Backend::CancelCheck& cancel);

}  // namespace trac0r

#endif
