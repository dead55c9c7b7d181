// Whole renders on the CPU backend: the furnace (light transport and
// Russian roulette are unbiased), determinism, and no non-finite pixels.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <cmath>
#include <memory>

using namespace trac0r;

namespace {

// The camera inside a closed box whose walls are diffuse with albedo rho and
// emit radiance le (colour x emittance, so emittance = le / rho): every path
// hits a wall at every vertex, so a path of at most max_depth vertices
// carries le * (1 + rho + ... + rho^(D-1)).
Scene furnace_scene(float rho, float le, int max_depth) {
    Scene scene;
    Material wall;
    wall.name = "wall";
    wall.type = MaterialType::diffuse;
    wall.color = glm::vec3(rho);
    wall.emittance = le / rho;
    scene.materials.push_back(wall);
    scene.shapes.push_back(
        make_box(glm::vec3(0.0f), glm::vec3(0.3f, 0.2f, 0.1f), glm::vec3(2.0f), 0));
    scene.camera.position = glm::vec3(0.1f, -0.2f, 0.05f);
    scene.camera.direction = glm::vec3(0.2f, 0.1f, 1.0f);
    scene.camera.vertical_fov = 90.0f;
    scene.render.width = 32;
    scene.render.height = 24;
    scene.render.max_depth = max_depth;
    return scene;
}

struct ImageEstimate {
    double mean;            // over pixels and channels' luminance
    double standard_error;  // of that mean
};

// Mean luminance over all samples of all pixels, and its standard error from
// the per-pixel Welford moments (every sample is independent).
ImageEstimate estimate(Renderer& renderer) {
    double sum = 0.0;
    double squared_deviations = 0.0;
    double n = 0.0;
    for (const kernel::AccumPixel& p : renderer.accumulator()) {
        sum += static_cast<double>(p.moments.x) * p.moments.z;
        n += p.moments.z;
    }
    const double mean = sum / n;
    for (const kernel::AccumPixel& p : renderer.accumulator()) {
        const double d = p.moments.x - mean;
        squared_deviations += p.moments.y + p.moments.z * d * d;
    }
    const double variance = squared_deviations / (n - 1.0);
    return {mean, std::sqrt(variance / n)};
}

ImageEstimate render_furnace(float rho, float le, int max_depth, int frames) {
    Renderer renderer(furnace_scene(rho, le, max_depth), std::make_unique<CpuBackend>(), 7);
    for (int i = 0; i < frames; ++i) {
        renderer.render_frame();
    }
    REQUIRE(renderer.stats().samples_dropped == 0);
    return estimate(renderer);
}

double furnace_expected(double rho, double le, int max_depth) {
    return le * (1.0 - std::pow(rho, max_depth)) / (1.0 - rho);
}

}  // namespace

TEST_CASE("furnace: the image mean is Le (1 - rho^D) / (1 - rho)", "[render][furnace]") {
    struct Case {
        float rho;
        int max_depth;
    };
    const Case cases[] = {{0.5f, 5}, {0.5f, 64}, {0.9f, 5}, {0.9f, 20}, {0.9f, 1000}};
    for (const Case& c : cases) {
        CAPTURE(c.rho, c.max_depth);
        const ImageEstimate e = render_furnace(c.rho, 1.0f, c.max_depth, 24);
        const double expected = furnace_expected(c.rho, 1.0, c.max_depth);
        CAPTURE(e.mean, e.standard_error, expected);
        // The estimate must be precise enough to mean something: a biased
        // roulette (dividing only at the emitter, or not at all) is off by
        // far more than 1 % here.
        REQUIRE(e.standard_error < 0.01 * expected);
        // Unbiased: within 5 standard errors (a false alarm once in ~1.7
        // million runs; the seeds are fixed, so it is deterministic anyway).
        REQUIRE(std::fabs(e.mean - expected) < 5.0 * e.standard_error);
    }
}

TEST_CASE("furnace: as D grows the mean approaches Le / (1 - rho)", "[render][furnace]") {
    const ImageEstimate e = render_furnace(0.5f, 2.0f, 100000, 24);
    const double limit = 2.0 / (1.0 - 0.5);
    REQUIRE(std::fabs(e.mean - limit) < 5.0 * e.standard_error);
}

TEST_CASE("furnace: max depth 1 sees only the emission, with no noise", "[render][furnace]") {
    const ImageEstimate e = render_furnace(0.9f, 3.0f, 1, 2);
    REQUIRE(e.mean == Approx(3.0).epsilon(1e-6));
    REQUIRE(e.standard_error < 1e-6);
}

TEST_CASE("renders are a pure function of scene, seed and frame", "[render][determinism]") {
    Scene scene = builtin_scene();
    scene.render.width = 64;
    scene.render.height = 48;
    auto render = [&](std::uint64_t seed, int threads) {
        Renderer r(scene, std::make_unique<CpuBackend>(threads), seed);
        for (int i = 0; i < 3; ++i) {
            r.render_frame();
        }
        return r.image();
    };
    const Image a = render(42, 1);
    const Image b = render(42, 2);
    const Image c = render(43, 2);
    REQUIRE(a.pixels == b.pixels);  // bit-identical, whatever the thread count
    REQUIRE(a.pixels != c.pixels);
    for (const glm::vec3& p : a.pixels) {
        REQUIRE(std::isfinite(p.x));
        REQUIRE(std::isfinite(p.y));
        REQUIRE(std::isfinite(p.z));
    }
}

TEST_CASE("restart clears the accumulator", "[render]") {
    Scene scene = builtin_scene();
    scene.render.width = 16;
    scene.render.height = 12;
    Renderer r(scene, std::make_unique<CpuBackend>(), 1);
    r.render_frame();
    const Image first = r.image();
    r.render_frame();
    r.restart();
    REQUIRE(r.frames() == 0);
    r.render_frame();
    REQUIRE(r.image().pixels == first.pixels);
}

namespace {

// A denormal times one, computed at run time (volatile: not folded).
float denormal_times_one() {
    volatile float denormal = 1e-40f;
    volatile float one = 1.0f;
    return denormal * one;
}

}  // namespace

TEST_CASE("the CPU backend's denormals-as-zero mode holds in its scope and is restored after",
          "[render]") {
#if !defined(__SSE__)
    FAIL("DenormalsAreZero is implemented for x86 (SSE) only");
#endif
    REQUIRE(denormal_times_one() != 0.0f);
    {
        const DenormalsAreZero denormals;
        CHECK(denormal_times_one() == 0.0f);
    }
    CHECK(denormal_times_one() != 0.0f);
    // A render leaves the calling thread's mode as it found it.
    Renderer r(furnace_scene(0.5f, 1.0f, 3), std::make_unique<CpuBackend>(2), 1);
    r.render_frame();
    CHECK(denormal_times_one() != 0.0f);
}

TEST_CASE("set_size renders what a renderer made at that size renders", "[render]") {
    Scene scene = builtin_scene();
    scene.render.width = 40;
    scene.render.height = 30;
    Renderer resized(scene, std::make_unique<CpuBackend>(2), 3);
    resized.render_frame();
    resized.set_size(56, 24);
    CHECK(resized.frames() == 0);
    resized.render_frame();
    resized.render_frame();
    scene.render.width = 56;
    scene.render.height = 24;
    Renderer fresh(scene, std::make_unique<CpuBackend>(2), 3);
    fresh.render_frame();
    fresh.render_frame();
    CHECK(resized.width() == 56);
    CHECK(resized.height() == 24);
    const Image a = resized.image();
    const Image b = fresh.image();
    CHECK(a.width == 56);
    CHECK(a.height == 24);
    CHECK(a.pixels == b.pixels);
}
