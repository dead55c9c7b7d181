// Where the BVH starts to pay: paths per second of the flat list and the
// BVH, side by side, on scenes of growing triangle count (the Cornell box's
// walls and lamp plus a grid of small boxes), CPU backend.
//
//   build/benchmarks/bench_accel_crossover [--frames N] [--size W H]
//
// Prints a Markdown table of paths per second on the machine's cores, from
// CPU time (benchmarks/timing.h); PackedScene's auto_bvh_min_triangles comes
// from it.
#include "timing.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/scene_loader.h"

#include <cstdio>
#include <cstdlib>
#include <string>

using namespace trac0r;

namespace {

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
            scene.shapes.push_back(make_box(p, glm::vec3(0.0f, 0.3f * i, 0.0f),
                                            glm::vec3(0.5f * step), white));
        }
    }
    return scene;
}

}  // namespace

int main(int argc, char** argv) {
    int frames = 30;
    int width = 200;
    int height = 150;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--frames" && i + 1 < argc) {
            frames = std::atoi(argv[++i]);
        } else if (a == "--size" && i + 2 < argc) {
            width = std::atoi(argv[++i]);
            height = std::atoi(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: bench_accel_crossover [--frames N] [--size W H]\n");
            return 2;
        }
    }
    if (frames < 1 || width < 1 || height < 1) {
        std::fprintf(stderr, "bench_accel_crossover: --frames and --size must be positive\n");
        return 2;
    }
    CpuBackend cpu;
    std::printf("%d x %d, %d timed frames, %s; paths per second on %d free cores, from CPU "
                "time\n\n",
                width, height, frames, cpu.device().c_str(), trac0r_bench::machine_cores());
    std::printf("| triangles | flat Mpaths/s | BVH Mpaths/s | BVH / flat |\n");
    std::printf("| --- | --- | --- | --- |\n");
    for (int boxes : {0, 1, 2, 3, 4, 5, 6, 8, 12, 20}) {
        Scene scene = box_grid(boxes);
        scene.render.width = width;
        scene.render.height = height;
        PackOptions flat;
        flat.accel = Accel::flat;
        PackOptions bvh;
        bvh.accel = Accel::bvh;
        const PackedScene flat_packed = pack_scene(scene, flat);
        const PackedScene bvh_packed = pack_scene(scene, bvh);
        const double pixels = static_cast<double>(width) * height;
        const double f =
            pixels / trac0r_bench::measure(cpu, flat_packed, scene, frames).free_frame_seconds();
        const double b =
            pixels / trac0r_bench::measure(cpu, bvh_packed, scene, frames).free_frame_seconds();
        std::printf("| %zu | %.3f | %.3f | %.2f |\n", flat_packed.triangles.size(), f * 1e-6,
                    b * 1e-6, b / f);
        std::fflush(stdout);
    }
    return 0;
}
