// A render split by frames (rank r of N renders frames r, r + N, ...:
// trac0r_mpi) and merged is the render of every frame: the same samples,
// summed in another order. test_mpi.cpp runs the same across processes.
#include "trac0r/accumulator_merge.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

using namespace trac0r;

namespace {

std::vector<kernel::AccumPixel> render_frames(const Scene& scene, std::uint32_t first,
                                              std::uint32_t stride, int frames) {
    Renderer r(scene, std::make_unique<CpuBackend>(2), 7);
    r.set_frame_sequence(first, stride);
    for (int f = 0; f < frames; ++f) {
        r.render_frame();
    }
    return r.accumulator();
}

}  // namespace

TEST_CASE("frames split across renderers and merged are the render of every frame", "[split]") {
    const Scene scene = load_test_scene("cornell.json", 24, 18);
    const int total = 11;
    const std::vector<kernel::AccumPixel> whole = render_frames(scene, 0, 1, total);
    for (std::uint32_t ranks : {1u, 2u, 3u}) {
        INFO(ranks << " parts");
        std::vector<std::vector<kernel::AccumPixel>> parts;
        for (std::uint32_t r = 0; r < ranks; ++r) {
            // Rank r's share of 11 frames: those of r, r + N, ... below 11.
            const int frames = static_cast<int>((total - r + ranks - 1) / ranks);
            parts.push_back(render_frames(scene, r, ranks, frames));
        }
        std::vector<const kernel::AccumPixel*> views;
        for (const auto& p : parts) {
            views.push_back(p.data());
        }
        std::vector<kernel::AccumPixel> merged(whole.size());
        merge_accumulators(views, whole.size(), merged.data());
        double worst = 0.0;
        for (std::size_t i = 0; i < whole.size(); ++i) {
            REQUIRE(merged[i].moments.z == whole[i].moments.z);  // samples
            REQUIRE(merged[i].moments.w == whole[i].moments.w);  // dropped
            const kernel::float3 a = kernel::accumulated_mean(merged[i]);
            const kernel::float3 b = kernel::accumulated_mean(whole[i]);
            for (int c = 0; c < 3; ++c) {
                const double x = c == 0 ? a.x : (c == 1 ? a.y : a.z);
                const double y = c == 0 ? b.x : (c == 1 ? b.y : b.z);
                if (y > 0.0) {
                    worst = std::max(worst, std::abs(x - y) / y);
                } else {
                    REQUIRE(x == 0.0);
                }
            }
        }
        CHECK(worst <= split_render_tolerance());
        // The luminance moments merge too: the noise estimate agrees (float
        // Welford on one side, a double merge on the other: 1e-4).
        const double e_whole = estimate_relative_mse(whole, 24, 18);
        const double e_merged = estimate_relative_mse(merged, 24, 18);
        CHECK(std::abs(e_merged - e_whole) <= 1e-4 * e_whole);
    }
}
