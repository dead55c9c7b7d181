// Where the BVH starts to pay: paths per second of the flat list and the
// BVH, side by side, on scenes of growing triangle count (the Cornell box's
// walls and lamp plus a grid of small boxes), on the CPU backend and, in a
// build with OpenCL, on OpenCL device 0.
//
//   build/benchmarks/bench_accel_crossover [--frames N] [--size W H]
//
// Prints a Markdown table of paths per second on the machine's cores, from
// CPU time (benchmarks/timing.h); PackedScene's auto_bvh_min_triangles comes
// from it.
#include "cli.h"
#include "timing.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/scene_loader.h"
#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_backend.h"
#endif

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

const char* const description =
    "Paths per second of the flat list and the BVH, side by side, on scenes of growing "
    "triangle count (the built-in Cornell box's walls and lamp plus a grid of 0 to 20 x 20 "
    "small boxes), on the CPU backend and, in a build with OpenCL, on OpenCL device 0; prints "
    "a Markdown table.";

struct Options {
    int frames = 30;
    int width = 200;
    int height = 150;
};

// The built-in scene's six walls and lamp, plus boxes x boxes small boxes.
Scene box_grid(int boxes) {
    Scene scene = builtin_scene();
    scene.shapes.resize(6);
    int white = 0;
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        if (scene.materials[m].name == "white") {
            white = static_cast<int>(m);
        }
    }
    for (int i = 0; i < boxes; ++i) {
        for (int j = 0; j < boxes; ++j) {
            const float step = 0.8f / boxes;
            const glm::vec3 p(-0.4f + (i + 0.5f) * step, -0.05f, -0.4f + (j + 0.5f) * step);
            scene.shapes.push_back(
                make_box(p, glm::vec3(0.0f, 0.3f * i, 0.0f), glm::vec3(0.5f * step), white));
        }
    }
    return scene;
}

int run(const Options& o) {
    const int frames = o.frames;
    const int width = o.width;
    const int height = o.height;
    std::vector<std::unique_ptr<Backend>> backends;
    backends.emplace_back(new CpuBackend());
#ifdef TRAC0R_HAVE_OPENCL
    backends.emplace_back(new OpenClBackend(0));  // throws when there is no device
#endif
    std::printf(
        "%d x %d, %d timed frames after one warm-up; paths per second on %d free cores, "
        "from CPU time",
        width, height, frames, trac0r_bench::machine_cores());
    for (const auto& b : backends) {
        std::printf("; %s: %s", b->name().c_str(), b->device().c_str());
    }
    std::printf("\n\n| triangles |");
    for (const auto& b : backends) {
        std::printf(" %s flat Mpaths/s | %s BVH Mpaths/s | %s BVH / flat |", b->name().c_str(),
                    b->name().c_str(), b->name().c_str());
    }
    std::printf("\n| ---: |");
    for (std::size_t i = 0; i < backends.size(); ++i) {
        std::printf(" ---: | ---: | ---: |");
    }
    std::printf("\n");
    for (int boxes : {0, 1, 2, 3, 4, 5, 6, 8, 12, 20}) {
        Scene scene = box_grid(boxes);
        scene.render.width = width;
        scene.render.height = height;
        const PackedScene flat_packed = trac0r_bench::pack_with(scene, Accel::flat);
        const PackedScene bvh_packed = trac0r_bench::pack_with(scene, Accel::bvh);
        const double pixels = static_cast<double>(width) * height;
        std::printf("| %zu |", flat_packed.triangles.size());
        for (const auto& backend : backends) {
            const double f =
                pixels /
                trac0r_bench::measure(*backend, flat_packed, scene, frames).free_frame_seconds();
            const double b =
                pixels /
                trac0r_bench::measure(*backend, bvh_packed, scene, frames).free_frame_seconds();
            std::printf(" %.3f | %.3f | %.2f |", f * 1e-6, b * 1e-6, b / f);
        }
        std::printf("\n");
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_accel_crossover", [&] {
        Options o;
        trac0r_cli::CommandLine cl("bench_accel_crossover",
                                   "bench_accel_crossover [--frames N] [--size W H]", description,
                                   16);
        cl.integer("--frames", &o.frames, 1, 100000,
                   "timed frames after one warm-up, in [1, 100000] (default 30)");
        cl.size("--size", &o.width, &o.height, 16384,
                "resolution, each in [1, 16384] (default 200 x 150)");
        return cl.parse_or_print(argc, argv) ? run(o) : 0;
    });
}
