// The OpenCL backend on PoCL (CI) or any device: the same kernel headers
// build as OpenCL C for every feature mask the scenes use, and the images
// agree with the CPU backend's. A missing device fails these tests.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "test_support.h"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

using namespace trac0r;

TEST_CASE("an OpenCL device is present", "[opencl]") {
    // No skip: CI installs PoCL, so no device means a broken installation.
    REQUIRE_FALSE(list_opencl_devices().empty());
    OpenClBackend backend(0);
    INFO(backend.device());
    REQUIRE_FALSE(backend.device().empty());
}

TEST_CASE("the kernel builds as OpenCL C for every scene's feature mask, warning-free",
          "[opencl]") {
    const char* scenes[] = {"cornell.json", "cornell_diffuse.json", "furnace.json",
                            "mesh_demo.json"};
    for (const char* name : scenes) {
        CAPTURE(name);
        const Scene scene = load_test_scene(name, 8, 8);
        const PackedScene packed = pack_scene(scene);
        require_warning_free_build(packed);
    }
}

TEST_CASE("--accel auto on OpenCL builds a BVH from PoCL's crossover", "[opencl]") {
    // README, "Performance": on PoCL the BVH is faster from the smallest
    // scene measured, the Cornell box's walls and lamp (12 triangles).
    Scene scene = builtin_scene();
    scene.shapes.resize(6);  // walls and lamp
    scene.render.width = 8;
    scene.render.height = 6;
    const Renderer gpu(scene, std::make_unique<OpenClBackend>(0), 1, PackOptions());
    REQUIRE(gpu.packed().triangles.size() == auto_bvh_min_triangles);
    REQUIRE(gpu.packed().features & T0_FEATURE_BVH);
    scene.shapes.resize(5);  // the walls without the lamp: 10 triangles
    const Renderer fewer(scene, std::make_unique<OpenClBackend>(0), 1, PackOptions());
    REQUIRE(fewer.packed().features & T0_FEATURE_FLAT);
}

TEST_CASE("a program is built once per feature mask and then reused", "[opencl]") {
    const PackedScene packed = pack_scene(load_test_scene("cornell_diffuse.json", 8, 8));
    OpenClBackend first(0);
    first.set_scene(packed);
    OpenClBackend second(0);
    second.set_scene(packed);
    REQUIRE(second.last_build_seconds() == 0.0);
}

// Both backends run the same code on the same random numbers, so most pixels
// agree to float rounding; a path that takes another branch because of a
// last-bit difference (e.g. fused multiply-add on one side) diverges, so the
// comparison is statistical: the mean over 8x8 blocks must agree within 5
// standard errors of the difference (from the per-pixel spread in the CPU
// image), and most individual pixels must agree closely.
// Both backends on the same structure (--accel auto may choose by backend).
static void compare_backends(const std::string& name, Accel accel) {
    const Scene scene = load_test_scene(name, 64, 48);
    const int frames = 16;
    PackOptions options;
    options.accel = accel;
    Renderer cpu(scene, std::make_unique<CpuBackend>(), 11, options);
    Renderer gpu(scene, std::make_unique<OpenClBackend>(0), 11, options);
    for (int i = 0; i < frames; ++i) {
        cpu.render_frame();
        gpu.render_frame();
    }
    const Image a = cpu.image();
    const Image b = gpu.image();
    const auto& moments = cpu.accumulator();
    int close_pixels = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
        if (d.x + d.y + d.z <= 1e-3f * (1.0f + a.pixels[i].x + a.pixels[i].y + a.pixels[i].z)) {
            ++close_pixels;
        }
    }
    CAPTURE(name, close_pixels, a.pixels.size());
    REQUIRE(close_pixels >= static_cast<int>(0.9 * a.pixels.size()));
    const int block = 8;
    for (int by = 0; by < a.height; by += block) {
        for (int bx = 0; bx < a.width; bx += block) {
            double la = 0.0, lb = 0.0, variance = 0.0;
            int n = 0;
            for (int y = by; y < by + block; ++y) {
                for (int x = bx; x < bx + block; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * a.width + x;
                    la += kernel::luminance(a.pixels[i]);
                    lb += kernel::luminance(b.pixels[i]);
                    // Variance of one pixel's mean: M2 / (n - 1) / n.
                    variance += moments[i].moments.y / (frames - 1) / frames;
                    ++n;
                }
            }
            // The difference of two independent block means has twice the
            // variance of one (an upper bound: the shared seeds correlate them).
            const double se = std::sqrt(2.0 * variance) / n;
            CAPTURE(bx, by, la / n, lb / n, se);
            REQUIRE(std::fabs(la - lb) / n <= 5.0 * se + 1e-6);
        }
    }
}

TEST_CASE("OpenCL and CPU images of cornell.json agree", "[opencl]") {
    compare_backends("cornell.json", Accel::bvh);
}

TEST_CASE("OpenCL and CPU images of cornell_diffuse.json agree", "[opencl]") {
    compare_backends("cornell_diffuse.json", Accel::bvh);
    compare_backends("cornell_diffuse.json", Accel::flat);
}

TEST_CASE("furnace on the OpenCL backend", "[opencl][furnace]") {
    // scenes/furnace.json: diffuse walls of albedo rho = 0.5 that emit
    // Le = colour x emittance = 0.5.
    Scene scene = load_test_scene("furnace.json", 32, 24);
    const double rho = scene.materials.at(0).color.x;
    const double le = rho * scene.materials.at(0).emittance;
    const int depth = scene.render.max_depth;
    const double expected = le * (1.0 - std::pow(rho, depth)) / (1.0 - rho);
    Renderer r(scene, std::make_unique<OpenClBackend>(0), 3);
    for (int i = 0; i < 24; ++i) {
        r.render_frame();
    }
    require_furnace_mean(r.accumulator(), expected);
}

TEST_CASE("an unknown device index is an error", "[opencl]") {
    REQUIRE_THROWS_WITH(OpenClBackend(999), Catch::Contains("--device 999: no such OpenCL device"));
}

TEST_CASE("a kernel that fails to build reports the build log", "[opencl]") {
    // A define that breaks the kernel source.
    setenv("TRAC0R_OPENCL_OPTIONS", "-Dmake_ray=syntax_error(", 1);
    OpenClBackend backend(0);
    const PackedScene packed = pack_scene(load_test_scene("furnace.json", 8, 8));
    REQUIRE_THROWS_WITH(backend.set_scene(packed),
                        Catch::Contains("build log") && Catch::Contains("syntax_error"));
    unsetenv("TRAC0R_OPENCL_OPTIONS");
}

TEST_CASE("the viewer exits non-zero with the build log on a broken kernel", "[opencl][cli]") {
    const std::string command = "TRAC0R_OPENCL_OPTIONS='-Dmake_ray=syntax_error(' " +
                                std::string(TRAC0R_VIEWER) +
                                " --headless --backend opencl --width 8 --height 8 --spp 1 "
                                "--output broken.pfm 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string output;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) {
        output += buffer;
    }
    const int status = pclose(pipe);
    INFO(output);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) != 0);
    REQUIRE(output.find("build log") != std::string::npos);
}
