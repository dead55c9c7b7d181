// The noise estimate: the relative MSE the renderer reports from its own
// per-pixel variance must match the true error against a reference.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "test_support.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

Scene small(const std::string& name) { return load_test_scene(name, 32, 24); }

void render_frames(Renderer& r, std::uint32_t until) {
    while (r.frames() < until) {
        r.render_frame();
    }
}

// Estimated against true relative MSE at the checkpoints of a convergence
// run (doubling samples per pixel), within the factor 1.5 the issue asks.
// Both are averaged over four renders of independent seeds: the estimate
// predicts the expected error, and one render's error at 8 spp scatters
// about it by more than that factor where a rare path (a naive sample
// finding the lamp after many bounces) lands in a pixel or not.
void check_estimate(const std::string& name, std::uint32_t first_checkpoint,
                    Integrator integrator = Integrator::naive) {
    const Scene scene = small(name);
    PackOptions pack;
    pack.integrator = integrator;
    pack.sampler = SamplerKind::random;  // independent samples: what the figures above measured
    // The reference: 32 times the samples of the last checkpoint, another
    // seed. Its own noise adds to the measured error (independent renders:
    // E[(L - L_ref)^2] = var L + var L_ref), so subtract its estimate (at
    // most a 32nd of the error measured).
    const std::uint32_t last_checkpoint = 64;
    Renderer reference(scene, std::make_unique<CpuBackend>(), 1000, pack);
    render_frames(reference, 32 * last_checkpoint);
    const Image reference_image = reference.image();
    const double reference_noise = estimate_relative_mse(reference.accumulator(), 32, 24);

    const int runs = 4;
    std::vector<std::unique_ptr<Renderer>> renders;
    for (int i = 0; i < runs; ++i) {
        renders.push_back(std::make_unique<Renderer>(scene, std::make_unique<CpuBackend>(),
                                                     static_cast<std::uint64_t>(7 + i), pack));
    }
    for (std::uint32_t spp = first_checkpoint; spp <= last_checkpoint; spp *= 2) {
        double estimated = 0.0, measured = 0.0;
        for (const auto& r : renders) {
            render_frames(*r, spp);
            estimated += estimate_relative_mse(r->accumulator(), 32, 24) / runs;
            measured += image_error(r->image(), reference_image).relative_mse / runs;
        }
        const double truth = measured - reference_noise;
        CAPTURE(name, spp, estimated, measured, reference_noise, truth);
        WARN(name << " spp " << spp << " estimated " << estimated << " truth " << truth);
        CHECK(truth > 0.0);
        CHECK(estimated / truth < 1.5);
        CHECK(truth / estimated < 1.5);
    }
}

}  // namespace

TEST_CASE("image_error: RMSE, relative MSE and PSNR of known images", "[noise]") {
    Image a;
    a.width = 2;
    a.height = 1;
    a.pixels = {glm::vec3(0.5f), glm::vec3(1.0f)};
    Image b = a;
    REQUIRE(image_error(a, b).rmse == 0.0);
    b.pixels[0] = glm::vec3(0.6f);
    const ImageError e = image_error(a, b);
    // One pixel off by 0.1 in all three channels out of six values.
    REQUIRE(e.rmse == Approx(std::sqrt(3 * 0.01 / 6)).epsilon(1e-5));
    REQUIRE(e.psnr == Approx(-20.0 * std::log10(e.rmse)));
    // Luminance of grey g is g: (0.1)^2 / (0.6^2 + 0.01), averaged over 2.
    REQUIRE(e.relative_mse == Approx(0.01 / (0.36 + 0.01) / 2).epsilon(1e-4));
    b.width = 1;
    REQUIRE_THROWS(image_error(a, b));
}

TEST_CASE("the noise estimate needs two samples per pixel", "[noise]") {
    Renderer r(small("cornell_diffuse.json"), std::make_unique<CpuBackend>(), 1);
    r.render_frame();
    REQUIRE(std::isinf(estimate_relative_mse(r.accumulator(), 32, 24)));
    r.render_frame();
    REQUIRE(std::isfinite(estimate_relative_mse(r.accumulator(), 32, 24)));
}

TEST_CASE("a luminance's squared deviations beyond float's range are reported as overflowed",
          "[noise]") {
    std::vector<kernel::AccumPixel> accum(4, kernel::AccumPixel{});
    for (kernel::AccumPixel& p : accum) {
        kernel::accumulate_sample(&p, kernel::make_float3(1.0f, 1.0f, 1.0f));
        kernel::accumulate_sample(&p, kernel::make_float3(3.0f, 3.0f, 3.0f));
    }
    CHECK(std::isfinite(estimate_relative_mse(accum, 2, 2)));
    CHECK_FALSE(noise_estimate_overflowed(accum));
    // Finite samples of 1e25 and 0: squared deviations of 1e50.
    kernel::accumulate_sample(&accum[3], kernel::make_float3(1e25f, 1e25f, 1e25f));
    kernel::accumulate_sample(&accum[3], kernel::make_float3(0.0f, 0.0f, 0.0f));
    CHECK(noise_estimate_overflowed(accum));
    CHECK(std::isinf(estimate_relative_mse(accum, 2, 2)));
}

TEST_CASE("the noise estimate: variance of the mean over the neighbourhood's mean", "[noise]") {
    const int w = 8;
    const int h = 6;
    // n = 5 samples per pixel, sample variance 0.2 (squared deviations 0.8).
    kernel::AccumPixel uniform = {};
    uniform.moments = glm::vec4(0.5f, 0.8f, 5.0f, 0.0f);
    std::vector<kernel::AccumPixel> accum(w * h, uniform);
    const double per_pixel = 0.2 / 5.0 / (0.25 + relative_mse_epsilon);
    REQUIRE(estimate_relative_mse(accum, w, h) == Approx(per_pixel));
    // One bright noisy pixel in a black corner: its 5 x 5 window is cut to
    // 3 x 3 by the border, so the mean it is judged against is 1 / 9.
    kernel::AccumPixel black = {};
    black.moments = glm::vec4(0.0f, 0.0f, 5.0f, 0.0f);
    accum.assign(w * h, black);
    accum[0].moments = glm::vec4(1.0f, 0.8f, 5.0f, 0.0f);
    REQUIRE(estimate_relative_mse(accum, w, h) ==
            Approx(0.2 / 5.0 / (1.0 / 81.0 + relative_mse_epsilon) / (w * h)));
    // The same pixel in the interior: 1 / 25.
    accum[0] = black;
    accum[3 * w + 4].moments = glm::vec4(1.0f, 0.8f, 5.0f, 0.0f);
    REQUIRE(estimate_relative_mse(accum, w, h) ==
            Approx(0.2 / 5.0 / (1.0 / 625.0 + relative_mse_epsilon) / (w * h)));
    REQUIRE_THROWS(estimate_relative_mse(accum, w + 1, h));
}

TEST_CASE("the noise estimate tracks the true error: diffuse Cornell box", "[noise]") {
    check_estimate("cornell_diffuse.json", 8);
}

TEST_CASE("the noise estimate tracks the true error: thesis Cornell box", "[noise]") {
    check_estimate("cornell.json", 8);
}

// Next-event estimation finds the light at every diffuse hit, so its
// samples are less heavy-tailed; but the glass and mirror paths that carry
// the caustics still find it by chance, and at 8 spp their rare bright
// samples are mostly not yet drawn, so the sample variance is low: over
// the four renders, estimate / truth is 0.53 at 8 spp and 0.71, 0.78 and
// 0.78 at 16, 32 and 64 (docs/noise.md, "How good the estimate is"). From
// 16 spp on, it is within the factor 1.5.
TEST_CASE("the noise estimate tracks the true error: thesis Cornell box with NEE", "[noise]") {
    check_estimate("cornell.json", 16, Integrator::nee);
}
