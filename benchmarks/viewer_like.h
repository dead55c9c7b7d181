// What the benchmarks that measure the window's display (bench_temporal,
// bench_frame_budget) share with trac0r_viewer: the scene size its camera
// speed follows. (Its integrator and sampler are the library's defaults,
// trac0r::PackOptions.)
#ifndef TRAC0R_BENCHMARKS_VIEWER_LIKE_H
#define TRAC0R_BENCHMARKS_VIEWER_LIKE_H

#include "trac0r/packed_scene.h"
#include "trac0r/scene.h"

#include <glm/glm.hpp>

namespace trac0r_bench {

// The diagonal of the box around every shape (1 for an empty scene).
inline float scene_diagonal(const trac0r::Scene& scene) {
    trac0r::AABB all;
    for (const trac0r::Shape& s : scene.shapes) {
        all.extend(s.aabb);
    }
    return all.empty() ? 1.0f : glm::length(all.max - all.min);
}

}  // namespace trac0r_bench

#endif
