// Paths per second of the two backends, side by side in one run, and what
// compiling the OpenCL program for the scene's feature mask saves against a
// program with every material compiled in.
//
//   build/benchmarks/bench_backends [--frames N] [--width W --height H] [SCENE.json ...]
//
// Prints Markdown tables (the README's). PoCL's on-disk kernel cache is
// switched off, and each timed build gets a unique dummy define so the
// process-wide program cache cannot answer it either: build times are real
// compiles.
#include "timing.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

using Clock = std::chrono::steady_clock;

struct Config {
    int frames = 5;
    int width = 800;
    int height = 600;
    std::vector<std::string> scenes;
};

Config parse(int argc, char** argv) {
    Config c;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() {
            if (i + 1 >= argc) {
                throw std::invalid_argument(a + ": expected a value");
            }
            return std::atoi(argv[++i]);
        };
        if (a == "--frames") {
            c.frames = value();
        } else if (a == "--width") {
            c.width = value();
        } else if (a == "--height") {
            c.height = value();
        } else if (!a.empty() && a[0] == '-') {
            throw std::invalid_argument(a + ": unknown option");
        } else {
            c.scenes.push_back(a);
        }
    }
    if (c.frames < 1 || c.width < 1 || c.height < 1) {
        throw std::invalid_argument("--frames, --width and --height must be positive");
    }
    if (c.scenes.empty()) {
        c.scenes = {"scenes/cornell.json", "scenes/cornell_diffuse.json"};
    }
    return c;
}

// Median of three real builds of the program for `features`.
double median_build_seconds(const Scene& scene, const PackedScene& packed,
                            std::uint32_t features) {
    const kernel::CameraRecord camera_8x8 = make_camera_record(scene.camera, 8, 8);
    static int nonce = 0;
    PackedScene p = packed;
    p.features = features;
    std::vector<double> seconds;
    for (int i = 0; i < 3; ++i) {
        const std::string option = "-DT0_BENCH_NONCE=" + std::to_string(++nonce);
        setenv("TRAC0R_OPENCL_OPTIONS", option.c_str(), 1);
        OpenClBackend backend(0);
        const Clock::time_point start = Clock::now();
        backend.set_scene(p);
        // PoCL finishes compiling at the first launch: include one of
        // 8 x 8 pixels, whose own cost is negligible.
        backend.reset(8, 8);
        backend.render_frame(camera_8x8, 1, 0, 1);
        seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    unsetenv("TRAC0R_OPENCL_OPTIONS");
    std::sort(seconds.begin(), seconds.end());
    return seconds[1];
}

}  // namespace

int main(int argc, char** argv) {
    try {
        setenv("POCL_KERNEL_CACHE", "0", 1);
        const Config config = parse(argc, argv);
        const std::uint32_t all_materials = T0_FEATURE_EMISSIVE | T0_FEATURE_DIFFUSE |
                                            T0_FEATURE_GLASS | T0_FEATURE_GLOSSY |
                                            T0_FEATURE_EMITTANCE;
        CpuBackend cpu;
        OpenClBackend opencl(0);
        std::printf("%d x %d, %d timed frames after one warm-up; CPU: %s; OpenCL: %s\n\n",
                    config.width, config.height, config.frames, cpu.device().c_str(),
                    opencl.device().c_str());
        std::printf("Acceleration: --accel auto (mask bit 0x40 = BVH, 0x20 = flat list)\n\n");
        std::printf("| scene | backend | mask | build s | ms/frame | fps | Mpaths/s |\n");
        std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
        for (const std::string& path : config.scenes) {
            Scene scene = load_scene_file(path);
            scene.render.width = config.width;
            scene.render.height = config.height;
            const PackedScene packed = pack_scene(scene);
            PackedScene full = packed;
            full.features |= all_materials;
            struct Row {
                Backend* backend;
                const PackedScene* packed;
                const char* mask;
            };
            const Row rows[] = {{&cpu, &packed, "scene's"},
                                {&opencl, &packed, "scene's"},
                                {&opencl, &full, "all materials"}};
            for (const Row& row : rows) {
                if (row.packed == &full && full.features == packed.features) {
                    continue;  // the scene already uses every material
                }
                const trac0r_bench::Timing t = trac0r_bench::measure(*row.backend, *row.packed, scene, config.frames);
                const double pixels = static_cast<double>(config.width) * config.height;
                std::printf("| %s | %s | %s (0x%02x) | %.2f | %.0f | %.2f | %.3f |\n",
                            path.c_str(), row.backend->name().c_str(), row.mask,
                            row.packed->features, t.build_seconds, 1e3 * t.frame_seconds,
                            1.0 / t.frame_seconds, pixels / t.frame_seconds * 1e-6);
                std::fflush(stdout);
            }
        }
        std::printf("\nOpenCL program build time, to the end of the first (8 x 8) launch, "
                    "median of 3 real compiles:\n\n");
        std::printf("| scene | mask | build s |\n| --- | --- | --- |\n");
        for (const std::string& path : config.scenes) {
            const Scene scene = load_scene_file(path);
            const PackedScene packed = pack_scene(scene);
            const std::uint32_t masks[] = {packed.features, packed.features | all_materials};
            for (int i = 0; i < 2; ++i) {
                const std::uint32_t mask = masks[i];
                if (i == 1 && mask == masks[0]) {
                    continue;  // the scene already uses every material
                }
                std::printf("| %s | %s (0x%02x) | %.2f |\n", path.c_str(),
                            mask == packed.features ? "scene's" : "all materials", mask,
                            median_build_seconds(scene, packed, mask));
                std::fflush(stdout);
            }
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_backends: %s\n", e.what());
        return 1;
    }
}
