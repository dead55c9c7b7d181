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

struct Timing {
    double build_seconds;   // OpenCL program build (0 on the CPU)
    double frame_seconds;   // mean over the timed frames
};

// Renders one warm-up frame, then times `frames` more.
Timing measure(Backend& backend, const PackedScene& packed, const Scene& scene, int frames) {
    const Clock::time_point build_start = Clock::now();
    backend.set_scene(packed);
    const double build = std::chrono::duration<double>(Clock::now() - build_start).count();
    backend.reset(scene.render.width, scene.render.height);
    const kernel::CameraRecord camera =
        make_camera_record(scene.camera, scene.render.width, scene.render.height);
    backend.render_frame(camera, 1, 0, scene.render.max_depth);
    const Clock::time_point start = Clock::now();
    for (int i = 1; i <= frames; ++i) {
        backend.render_frame(camera, 1, static_cast<std::uint32_t>(i), scene.render.max_depth);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return {build, seconds / frames};
}

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
double median_build_seconds(const PackedScene& packed, std::uint32_t features) {
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
                const Timing t = measure(*row.backend, *row.packed, scene, config.frames);
                const double pixels = static_cast<double>(config.width) * config.height;
                std::printf("| %s | %s | %s (0x%02x) | %.2f | %.0f | %.2f | %.3f |\n",
                            path.c_str(), row.backend->name().c_str(), row.mask,
                            row.packed->features, t.build_seconds, 1e3 * t.frame_seconds,
                            1.0 / t.frame_seconds, pixels / t.frame_seconds * 1e-6);
                std::fflush(stdout);
            }
        }
        std::printf("\nOpenCL program build time (median of 3 real compiles):\n\n");
        std::printf("| scene | mask | build s |\n| --- | --- | --- |\n");
        for (const std::string& path : config.scenes) {
            const PackedScene packed = pack_scene(load_scene_file(path));
            const std::uint32_t masks[] = {packed.features, packed.features | all_materials};
            for (std::uint32_t mask : masks) {
                if (mask == packed.features && &mask != &masks[0]) {
                    continue;
                }
                std::printf("| %s | %s (0x%02x) | %.2f |\n", path.c_str(),
                            mask == packed.features ? "scene's" : "all materials", mask,
                            median_build_seconds(packed, mask));
                std::fflush(stdout);
            }
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_backends: %s\n", e.what());
        return 1;
    }
}
