// Shared by the benchmark programs: time frames of a packed scene on a
// backend, after one warm-up frame.
#ifndef TRAC0R_BENCHMARKS_TIMING_H
#define TRAC0R_BENCHMARKS_TIMING_H

#include "trac0r/backend.h"
#include "trac0r/camera.h"
#include "trac0r/packed_scene.h"
#include "trac0r/scene.h"

#include <chrono>

namespace trac0r_bench {

struct Timing {
    double build_seconds;  // set_scene: upload, and the OpenCL program build
    double frame_seconds;  // mean over the timed frames
};

inline Timing measure(trac0r::Backend& backend, const trac0r::PackedScene& packed,
                      const trac0r::Scene& scene, int frames) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point build_start = Clock::now();
    backend.set_scene(packed);
    const double build = std::chrono::duration<double>(Clock::now() - build_start).count();
    backend.reset(scene.render.width, scene.render.height);
    const trac0r::kernel::CameraRecord camera =
        trac0r::make_camera_record(scene.camera, scene.render.width, scene.render.height);
    backend.render_frame(camera, 1, 0, scene.render.max_depth);
    const Clock::time_point start = Clock::now();
    for (int i = 1; i <= frames; ++i) {
        backend.render_frame(camera, 1, static_cast<std::uint32_t>(i), scene.render.max_depth);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return {build, seconds / frames};
}

}  // namespace trac0r_bench

#endif
