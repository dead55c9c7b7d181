// Paths per second of the two backends with the flat list and the BVH,
// side by side in one run; rays per second of ray casting alone (primary
// rays and diffuse bounces, benchmarks/ray_cast.h); and what compiling the
// OpenCL program for the scene's feature mask saves against a program with
// every material compiled in.
//
//   build/benchmarks/bench_backends [--frames N] [--width W --height H]
//                                   [--accel flat,bvh] [SCENE.json ...]
//
// Prints Markdown tables (docs/performance.md, "Backends and ray
// casting"). PoCL's on-disk kernel cache is switched off, and each timed
// build gets a unique dummy define so the process-wide program cache
// cannot answer it either: build times are real compiles.
#include "cli.h"
#include "ray_cast.h"
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
using trac0r_bench::parse_long;
using trac0r_bench::UsageError;

struct Config {
    int frames = 5;
    int width = 800;
    int height = 600;
    std::vector<Accel> accels = {Accel::flat, Accel::bvh};
    std::vector<std::string> scenes;
    bool default_scenes = false;  // none given: scenes/*.json, from the working directory
    bool help = false;            // --help or --version: printed, nothing to run
};

const char* const description =
    "Paths per second of the CPU (OpenMP) and OpenCL backends with each acceleration "
    "structure, rays per second of ray casting alone, and OpenCL program build times, for each "
    "scene (default: scenes/cornell.json and scenes/cornell_diffuse.json, relative to the "
    "working directory: run from the repository root), as Markdown tables.";

std::vector<Accel> parse_accels(const std::string& list) {
    std::vector<Accel> out;
    for (const std::string& name : trac0r_bench::split_commas(list)) {
        try {
            out.push_back(parse_accel(name));
        } catch (const std::invalid_argument&) {
            throw UsageError("--accel: unknown structure '" + name +
                             "' (expected a list of flat, bvh, auto)");
        }
    }
    return out;
}

Config parse(int argc, char** argv) {
    Config c;
    trac0r_cli::CommandLine cl("bench_backends", "bench_backends [options] [SCENE.json ...]",
                               description, 24);
    cl.app().add_option("SCENE.json", c.scenes, "the scenes to time");
    cl.integer("--frames", &c.frames, 1, 100000,
               "timed frames (and ray casting passes) after one warm-up, in [1, 100000] "
               "(default 5)");
    cl.integer("--width", &c.width, 1, 16384, "resolution, in [1, 16384] (default 800)", "W");
    cl.integer("--height", &c.height, 1, 16384, "resolution, in [1, 16384] (default 600)", "H");
    cl.value("--accel", "LIST", "structures to compare, of flat, bvh, auto (default flat,bvh)",
             [&c](const std::string& v) { c.accels = parse_accels(v); });
    c.help = !cl.parse_or_print(argc, argv);
    if (c.help) {
        return c;
    }
    if (c.scenes.empty()) {
        c.scenes = {"scenes/cornell.json", "scenes/cornell_diffuse.json"};
        c.default_scenes = true;
    }
    return c;
}

// Every scene of the command line, loaded before anything is printed; a
// default scene that is not there says where it was looked for.
std::vector<Scene> load_scenes(const Config& config) {
    std::vector<Scene> scenes;
    for (const std::string& path : config.scenes) {
        try {
            scenes.push_back(load_scene_file(path));
        } catch (const SceneError& e) {
            if (!config.default_scenes) {
                throw;
            }
            throw SceneError(std::string(e.what()) +
                             " (the default scenes are relative to the working directory: run "
                             "from the repository root, or give scene paths)");
        }
    }
    return scenes;
}

// Median of three real builds of the program for `features`.
double median_build_seconds(const Scene& scene, const PackedScene& packed, std::uint32_t features) {
    const kernel::CameraRecord camera_8x8 = make_camera_record(scene.camera, 8, 8);
    static int nonce = 0;
    PackedScene p = packed;
    p.features = features;
    std::vector<double> seconds;
    // A define of its own makes each build a real compile (PoCL caches
    // programs on disk by source and options); the user's options stay.
    const char* user = std::getenv("TRAC0R_OPENCL_OPTIONS");
    const std::string user_options = user ? user : "";
    for (int i = 0; i < 3; ++i) {
        const std::string option = user_options + " -DT0_BENCH_NONCE=" + std::to_string(++nonce);
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
    if (user) {
        setenv("TRAC0R_OPENCL_OPTIONS", user_options.c_str(), 1);
    } else {
        unsetenv("TRAC0R_OPENCL_OPTIONS");
    }
    return trac0r_bench::median(seconds);
}

// A table cell: millions of rays per second, or "no rays" for an empty set
// (a scene with no triangles, or one whose primary rays all miss or hit a
// lamp, has no bounces).
std::string mrays_per_second(const trac0r_bench::RaySet& rays, const trac0r_bench::CastResult& r) {
    if (rays.size() == 0) {
        return "no rays";
    }
    char cell[32];
    std::snprintf(cell, sizeof cell, "%.2f", rays.size() / r.seconds * 1e-6);
    return cell;
}

// Rays per second of ray casting alone: the same rays (made once from the
// BVH scene) through each structure on each backend.
void print_ray_table(const Config& config, const std::vector<Scene>& scenes) {
    std::printf(
        "\nRays per second of ray casting alone (nearest hit, no shading), %d x %d: "
        "one jittered primary ray per pixel, and one cosine-distributed diffuse "
        "bounce from each primary hit that does not emit; %d passes after "
        "one warm-up, on %d free cores from CPU time (benchmarks/ray_cast.h):\n\n",
        config.width, config.height, config.frames, trac0r_bench::machine_cores());
    std::printf("| scene | backend | accel | primary Mrays/s | diffuse bounce Mrays/s |\n");
    std::printf("| --- | --- | --- | --- | --- |\n");
    trac0r_bench::OpenClCaster opencl;
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const std::string& path = config.scenes[s];
        const Scene& scene = scenes[s];
        PackOptions bvh_options;
        bvh_options.accel = Accel::bvh;
        const kernel::CameraRecord camera =
            make_camera_record(scene.camera, config.width, config.height);
        const trac0r_bench::RaySets rays =
            trac0r_bench::make_ray_sets(pack_scene(scene, bvh_options), camera);
        std::size_t expected_hits[2] = {0, 0};
        bool first = true;
        for (int backend = 0; backend < 2; ++backend) {
            for (Accel accel : config.accels) {
                PackOptions options;
                options.accel = accel;
                const PackedScene packed = pack_scene(scene, options);
                trac0r_bench::CastResult r[2];
                const trac0r_bench::RaySet* sets[2] = {&rays.primary, &rays.bounce};
                for (int k = 0; k < 2; ++k) {
                    r[k] = backend == 0 ? trac0r_bench::cast_cpu(packed, *sets[k], config.frames)
                                        : opencl.cast(packed, *sets[k], config.frames);
                    if (first) {
                        expected_hits[k] = r[k].hits;
                    } else if (r[k].hits != expected_hits[k]) {
                        std::printf("(warning: %zu of %zu rays hit here, %zu in the first row)\n",
                                    r[k].hits, sets[k]->size(), expected_hits[k]);
                    }
                }
                first = false;
                std::printf("| %s | %s | %s | %s | %s |\n", path.c_str(),
                            backend == 0 ? "cpu" : "opencl", to_string(accel),
                            mrays_per_second(rays.primary, r[0]).c_str(),
                            mrays_per_second(rays.bounce, r[1]).c_str());
                std::fflush(stdout);
            }
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_backends", [&] {
        setenv("POCL_KERNEL_CACHE", "0", 1);
        const Config config = parse(argc, argv);
        if (config.help) {
            return 0;  // --help or --version, printed
        }
        const std::vector<Scene> scenes = load_scenes(config);
        const std::uint32_t all_materials = T0_FEATURE_EMISSIVE | T0_FEATURE_DIFFUSE |
                                            T0_FEATURE_GLASS | T0_FEATURE_GLOSSY |
                                            T0_FEATURE_EMITTANCE;
        CpuBackend cpu;
        OpenClBackend opencl(0);
        std::printf("%d x %d, %d timed frames after one warm-up; CPU: %s; OpenCL: %s\n\n",
                    config.width, config.height, config.frames, cpu.device().c_str(),
                    opencl.device().c_str());
        const int cores = trac0r_bench::machine_cores();
        std::printf(
            "Mask bits: 0x40 = BVH, 0x20 = flat list. A frame is one path per pixel. "
            "fps and Mpaths/s on %d free cores: %d / the frame's CPU time (all threads); "
            "wall ms/frame depends on the machine's load.\n\n",
            cores, cores);
        std::printf(
            "| scene | backend | accel | mask | build s | wall ms/frame | CPU ms/frame | "
            "fps | Mpaths/s |\n");
        std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
        const double pixels = static_cast<double>(config.width) * config.height;
        std::string ratios;
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const std::string& path = config.scenes[s];
            Scene scene = scenes[s];
            scene.render.width = config.width;
            scene.render.height = config.height;
            for (Accel accel : config.accels) {
                PackOptions options;
                options.accel = accel;
                // The thesis' paths, which docs/performance.md's figures time.
                options.integrator = Integrator::naive;
                options.sampler = SamplerKind::random;
                const PackedScene packed = pack_scene(scene, options);
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
                    if (row.packed == &full &&
                        (full.features == packed.features || accel != config.accels.back())) {
                        continue;  // the scene uses every material; or once per scene
                    }
                    const trac0r_bench::Timing t =
                        trac0r_bench::measure(*row.backend, *row.packed, scene, config.frames);
                    const double free = t.free_frame_seconds();
                    std::printf(
                        "| %s | %s | %s | %s (0x%02x) | %.2f | %.0f | %.0f | %.2f "
                        "| %.3f |\n",
                        path.c_str(), row.backend->name().c_str(), to_string(accel), row.mask,
                        row.packed->features, t.build_seconds, 1e3 * t.frame_seconds,
                        1e3 * t.cpu_frame_seconds, 1.0 / free, pixels / free * 1e-6);
                    std::fflush(stdout);
                }
            }
            const bool both = std::find(config.accels.begin(), config.accels.end(), Accel::flat) !=
                                  config.accels.end() &&
                              std::find(config.accels.begin(), config.accels.end(), Accel::bvh) !=
                                  config.accels.end();
            if (both) {
                // The ratio from frames alternated, flat then BVH, with
                // backends of their own: robust to the machine's load
                // changing between the rows above.
                const PackedScene flat_packed = trac0r_bench::pack_with(scene, Accel::flat);
                const PackedScene bvh_packed = trac0r_bench::pack_with(scene, Accel::bvh);
                std::string cells;
                for (int b = 0; b < 2; ++b) {
                    std::unique_ptr<Backend> flat_backend;
                    std::unique_ptr<Backend> bvh_backend;
                    if (b == 0) {
                        flat_backend.reset(new CpuBackend());
                        bvh_backend.reset(new CpuBackend());
                    } else {
                        flat_backend.reset(new OpenClBackend(0));
                        bvh_backend.reset(new OpenClBackend(0));
                    }
                    const trac0r_bench::Alternated t = trac0r_bench::measure_alternated(
                        *flat_backend, flat_packed, *bvh_backend, bvh_packed, scene, config.frames);
                    std::vector<double> ratios_per_round;
                    for (std::size_t i = 0; i < t.a.size(); ++i) {
                        ratios_per_round.push_back(t.a[i] / t.b[i]);
                    }
                    const auto range =
                        std::minmax_element(ratios_per_round.begin(), ratios_per_round.end());
                    char cell[160];
                    std::snprintf(cell, sizeof cell, "%s %.2f (%.2f to %.2f; %.0f and %.0f ms)",
                                  b == 0 ? "CPU" : "OpenCL", trac0r_bench::median(ratios_per_round),
                                  *range.first, *range.second, 1e3 * trac0r_bench::median(t.a),
                                  1e3 * trac0r_bench::median(t.b));
                    cells += (b == 0 ? "" : ", ") + std::string(cell);
                }
                ratios += "- " + path + ": " + cells + "\n";
            }
        }
        if (!ratios.empty()) {
            std::printf(
                "\nBVH / flat list, paths per second: the median over %d rounds of a "
                "flat-list frame then a BVH frame, each backend twice (one per "
                "structure), of the ratio of their CPU times (the range; the median "
                "CPU ms of a flat and of a BVH frame):\n\n%s",
                config.frames, ratios.c_str());
        }
        print_ray_table(config, scenes);
        std::printf(
            "\nOpenCL program build time, to the end of the first (8 x 8) launch, "
            "median of 3 real compiles:\n\n");
        std::printf("| scene | mask | build s |\n| --- | --- | --- |\n");
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const std::string& path = config.scenes[s];
            const Scene& scene = scenes[s];
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
    });
}
