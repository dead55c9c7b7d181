// Non-finite and extreme samples on the CPU (issue 5, docs/stability.md):
// a lamp of infinite emittance, whose non-finite samples are counted and
// dropped, and a firefly of 1e6 that the accumulator's compensated sum keeps
// exact.
#include <catch2/catch.hpp>

#include "stability_support.h"

#include <cstdint>
#include <limits>
#include <memory>

using namespace trac0r;
using namespace trac0r::stability;

TEST_CASE("a lamp of infinite emittance: every non-finite sample is counted and dropped",
          "[stability][numerics]") {
    // Colour (1, 0, 0.5) times infinity is (inf, NaN, inf). With max depth 1
    // a sample is non-finite exactly when its camera ray hits the lamp; the
    // count is replayed here from the kernel's own seeding and camera rays.
    Scene scene = room(1.0f, glm::vec3(0.0f), std::numeric_limits<float>::infinity());
    scene.materials[1].color = glm::vec3(1.0f, 0.0f, 0.5f);
    scene.render.max_depth = 1;
    // Looking up at 45 degrees: the lamp (60 to 35 degrees up) is in view.
    scene.camera.direction = glm::vec3(0.0f, 1.0f, 1.0f);
    const int frames = 4;
    const std::uint64_t seed = 8;
    std::unique_ptr<Renderer> r = render(scene, frames, seed);
    const PackedScene packed = pack_scene(scene);
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord cam = make_camera_record(scene.camera, r->width(), r->height());
    double lamp_hits = 0;
    for (std::uint32_t frame = 0; frame < static_cast<std::uint32_t>(frames); ++frame) {
        for (std::uint32_t pixel = 0; pixel < 16u * 16u; ++pixel) {
            kernel::Rng rng;
            kernel::rng_seed_pixel(&rng, seed, pixel, frame);
            const float jx = kernel::rng_float(&rng);
            const float jy = kernel::rng_float(&rng);
            const kernel::Hit hit =
                nearest_hit(&view, kernel::camera_ray(cam, static_cast<float>(pixel % 16),
                                                      static_cast<float>(pixel / 16), jx, jy));
            lamp_hits += hit.triangle >= 0 &&
                         packed.triangles[static_cast<std::size_t>(hit.triangle)].ids.x == 1u;
        }
    }
    REQUIRE(lamp_hits > 0);
    CHECK(r->stats().samples_dropped == lamp_hits);
    CHECK(non_finite_pixels(r->image()) == 0);
    for (const kernel::AccumPixel& p : r->accumulator()) {
        REQUIRE(p.moments.z + p.moments.w == static_cast<float>(frames));  // each sample once
    }
    SECTION("and at full depth, where the lamp is also seen through reflections") {
        scene.render.max_depth = 5;
        std::unique_ptr<Renderer> deep = render(scene, frames, seed);
        CHECK(deep->stats().samples_dropped > lamp_hits);
        CHECK(non_finite_pixels(deep->image()) == 0);
    }
}

TEST_CASE("a firefly of 1e6 among 100,000 samples keeps the mean exact", "[stability][numerics]") {
    // test_accumulate.cpp proves 100,000 samples spread over six decades;
    // here one sample of 1e6 (an emittance-1e6 lamp seen once) comes first
    // and 100,000 samples of 0.1 follow, each far below the sum's last
    // place (0.0625). The compensation must carry every one of them.
    kernel::AccumPixel px = {};
    kernel::accumulate_sample(&px, glm::vec3(1e6f));
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        kernel::accumulate_sample(&px, glm::vec3(0.1f));
    }
    const double expected = (1e6 + n * static_cast<double>(0.1f)) / (n + 1);
    const glm::vec3 mean = kernel::accumulated_mean(px);
    // Two roundings of the compensated sum and one of the division: 1e-6.
    for (int k = 0; k < 3; ++k) {
        CHECK(std::fabs(mean[k] - expected) <= 1e-6 * expected);
    }
    // A plain float sum would have lost every 0.1: 1e6 / 100001 = 9.9999.
    CHECK(std::fabs(mean.x - 1e6 / (n + 1.0)) > 0.09);
}
