// Frames per second against triangle count (the thesis' figure 3.5): the
// Cornell box's walls and lamp plus a 4 x 4 wall of icospheres, subdivided
// 0, 1, 2, ... times (332 to 1,310,732 triangles), rendered with the flat
// list and the BVH on the CPU (OpenMP) and OpenCL backends, side by side in
// one run. The spheres keep their place and size at every level, so the
// image (and the paths) stay the same and only the triangle count grows.
//
//   build/benchmarks/bench_complexity [options]      (see --help)
//
// Prints a Markdown table and writes a CSV; plot it with
// benchmarks/plot_complexity.py.
#include "cli.h"
#include "timing.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/scene_loader.h"
#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_backend.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

using Clock = std::chrono::steady_clock;
using trac0r_bench::parse_long;
using trac0r_bench::UsageError;

const char* const description =
    "Renders the Cornell box's walls and lamp plus a 4 x 4 wall of icospheres of 0, 1, ... "
    "--max-subdivisions subdivisions (332 to 1,310,732 triangles at the default 6) with each "
    "backend and acceleration structure, and prints frames per second against the triangle "
    "count as a Markdown table and a CSV.";

struct Options {
    int frames = 5;
    int width = 160;
    int height = 120;
    int max_subdivisions = 6;
    bool cpu = true;
    bool opencl = true;
    double flat_limit = 5.0;
    int repeats = 1;
    std::string csv_path = "benchmarks/results/complexity.csv";
};

void parse_backends(const std::string& list, Options& o) {
    o.cpu = false;
    o.opencl = false;
    for (const std::string& part : trac0r_bench::split_commas(list)) {
        bool* chosen = part == "cpu" ? &o.cpu : part == "opencl" ? &o.opencl : nullptr;
        if (chosen == nullptr) {
            throw UsageError("--backends " + trac0r::printable(list, 40) + ": unknown backend '" +
                             trac0r::printable(part, 40) +
                             "' (expected cpu, opencl or cpu,opencl)");
        }
        if (*chosen) {
            throw UsageError("--backends " + trac0r::printable(list, 40) + ": '" + part +
                             "' given twice");
        }
        *chosen = true;
    }
}

// false for --help and --version (printed).
bool parse(int argc, char** argv, Options& o) {
    trac0r_cli::CommandLine cl("bench_complexity", "bench_complexity [options]", description, 24);
    cl.integer("--frames", &o.frames, 1, 100000,
               "timed frames per measurement, after one warm-up (default 5)");
    cl.integer("--repeats", &o.repeats, 1, 1000,
               "measure each cell R times, in turn, and keep the median (default 1)", "R");
    cl.integer("--width", &o.width, 1, 16384, "resolution (default 160)", "W");
    cl.integer("--height", &o.height, 1, 16384, "resolution (default 120)", "H");
    cl.integer("--max-subdivisions", &o.max_subdivisions, 0, 7,
               "the spheres' last subdivision level, 0-7 (default 6)");
    cl.value("--backends", "LIST", "cpu, opencl or cpu,opencl (default cpu,opencl)",
             [&o](const std::string& v) { parse_backends(v, o); });
    cl.number("--flat-limit", &o.flat_limit, 0.0, 1e6,
              "skip the flat list at a level where its frame time, predicted linearly in "
              "triangles from the level before, exceeds S seconds (default 5; 0: never skip)",
              "S");
    cl.text("--csv", &o.csv_path,
            "where to write the CSV (default benchmarks/results/complexity.csv)");
    return cl.parse_or_print(argc, argv);
}

// The built-in scene's five walls and lamp, plus 16 diffuse white
// icospheres of radius 0.09 in a 4 x 4 grid facing the camera.
Scene sphere_wall(int subdivisions) {
    Scene scene = builtin_scene();
    scene.shapes.resize(6);
    int white = -1;
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        if (scene.materials[m].name == "white") {
            white = static_cast<int>(m);
        }
    }
    if (white < 0) {
        throw std::runtime_error("the built-in scene has no material 'white'");
    }
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) {
            const glm::vec3 centre(-0.33f + 0.22f * column, 0.07f + 0.22f * row, 0.2f);
            scene.shapes.push_back(
                make_icosphere(centre, glm::vec3(0.0f), 0.09f, subdivisions, white));
        }
    }
    return scene;
}

struct Measurement {
    bool measured = false;
    std::string why_skipped;
    double frame_seconds = 0.0;       // on free cores, from CPU time
    double wall_frame_seconds = 0.0;  // as measured, on a machine maybe shared
};

struct Level {
    int subdivisions = 0;
    std::size_t triangles = 0;
    double pack_bvh_seconds = 0.0;
    // [backend][accel]: backend 0 cpu, 1 opencl; accel 0 flat, 1 bvh.
    Measurement m[2][2];
};

const char* backend_names[2] = {"cpu", "opencl"};
const char* accel_names[2] = {"flat", "bvh"};

std::string fps_cell(const Measurement& m) {
    if (!m.measured) {
        return m.why_skipped.empty() ? "-" : "skipped";
    }
    char s[32];
    std::snprintf(s, sizeof s, "%.2f", 1.0 / m.frame_seconds);
    return s;
}

void write_csv(std::ofstream& csv, const Options& o, const std::vector<Level>& levels) {
    // ms_per_frame, fps, mpaths_per_s: on free cores, from CPU time;
    // wall_ms_per_frame: the wall clock on the (maybe shared) machine.
    csv << "triangles,subdivisions,backend,accel,status,ms_per_frame,fps,mpaths_per_s,"
           "wall_ms_per_frame,cores,width,height\n";
    const double pixels = static_cast<double>(o.width) * o.height;
    for (const Level& l : levels) {
        for (int b = 0; b < 2; ++b) {
            for (int a = 0; a < 2; ++a) {
                const Measurement& m = l.m[b][a];
                if (!m.measured && m.why_skipped.empty()) {
                    continue;  // backend not asked for
                }
                csv << l.triangles << ',' << l.subdivisions << ',' << backend_names[b] << ','
                    << accel_names[a] << ',' << (m.measured ? "measured" : "skipped") << ',';
                if (m.measured) {
                    csv << 1e3 * m.frame_seconds << ',' << 1.0 / m.frame_seconds << ','
                        << pixels / m.frame_seconds * 1e-6 << ',' << 1e3 * m.wall_frame_seconds;
                } else {
                    csv << ",,,";
                }
                csv << ',' << trac0r_bench::machine_cores() << ',' << o.width << ',' << o.height
                    << '\n';
            }
        }
    }
    if (!csv) {
        throw std::runtime_error(o.csv_path + ": write failed");
    }
}

// The level whose triangle count is nearest to `target` on a log scale.
const Level& nearest(const std::vector<Level>& levels, double target) {
    const Level* best = &levels.front();
    for (const Level& l : levels) {
        const double distance = std::abs(std::log(l.triangles / target));
        if (distance < std::abs(std::log(best->triangles / target))) {
            best = &l;
        }
    }
    return *best;
}

void print_growth(const std::vector<Level>& levels) {
    const Level& small = nearest(levels, 1e3);
    const Level& large = nearest(levels, 1e6);
    if (&small == &large) {
        std::printf("\n(too few levels for the 1,000 to 1,000,000 triangle growth)\n");
        return;
    }
    // The target is stated for three decades of triangles; say it only
    // where the run spans them.
    const bool spans_target = large.triangles >= 1000 * small.triangles;
    std::printf("\nBVH frame time growth from %zu to %zu triangles%s:\n", small.triangles,
                large.triangles, spans_target ? " (target: at most 3x)" : "");
    for (int b = 0; b < 2; ++b) {
        const Measurement& s = small.m[b][1];
        const Measurement& l = large.m[b][1];
        if (s.measured && l.measured) {
            std::printf("  %s: %.1f ms -> %.1f ms, %.2fx\n", backend_names[b],
                        1e3 * s.frame_seconds, 1e3 * l.frame_seconds,
                        l.frame_seconds / s.frame_seconds);
        }
    }
}

typedef std::unique_ptr<Backend> Backends[2];

// The last measured flat frame time per backend and its triangle count, to
// predict the next level's.
struct FlatHistory {
    double seconds[2] = {0.0, 0.0};
    std::size_t triangles[2] = {0, 0};
};

// Which cells of a level to measure: every backend asked for, the flat list
// only while its predicted frame time is within the limit (else why not).
void choose_cells(const Options& o, const Backends& backends, const FlatHistory& history,
                  Level& level, bool measure_cell[2][2]) {
    for (int b = 0; b < 2; ++b) {
        measure_cell[b][0] = measure_cell[b][1] = false;
        if (!backends[b]) {
            continue;
        }
        measure_cell[b][1] = true;
        const std::size_t last_triangles = std::max<std::size_t>(1, history.triangles[b]);
        const double predicted = history.seconds[b] * static_cast<double>(level.triangles) /
                                 static_cast<double>(last_triangles);
        if (history.triangles[b] > 0 && o.flat_limit > 0.0 && predicted > o.flat_limit) {
            char why[200];
            std::snprintf(why, sizeof why,
                          "predicted %.1f s/frame on free cores (%.2f s at %zu triangles, "
                          "linear in triangles) > --flat-limit %g s",
                          predicted, history.seconds[b], history.triangles[b], o.flat_limit);
            level.m[b][0].why_skipped = why;
            std::fprintf(stderr, "  %s flat skipped: %s\n", backend_names[b], why);
        } else {
            measure_cell[b][0] = true;
        }
    }
}

// One level: pack both structures, time every chosen cell once per round,
// in turn, and keep the median of the rounds.
Level measure_level(const Options& o, const Backends& backends, int subdivisions,
                    FlatHistory& history) {
    Scene scene = sphere_wall(subdivisions);
    scene.render.width = o.width;
    scene.render.height = o.height;
    Level level;
    level.subdivisions = subdivisions;
    // The thesis' paths (naive, xorshift), which docs/performance.md's
    // figures time.
    PackOptions flat_options;
    flat_options.accel = Accel::flat;
    flat_options.integrator = Integrator::naive;
    flat_options.sampler = SamplerKind::random;
    PackOptions bvh_options = flat_options;
    bvh_options.accel = Accel::bvh;
    const Clock::time_point pack_start = Clock::now();
    const PackedScene bvh = pack_scene(scene, bvh_options);
    level.pack_bvh_seconds = std::chrono::duration<double>(Clock::now() - pack_start).count();
    const PackedScene flat = pack_scene(scene, flat_options);
    level.triangles = bvh.triangles.size();
    std::fprintf(stderr, "%zu triangles (BVH packed in %.2f s, depth %d)\n", level.triangles,
                 level.pack_bvh_seconds, bvh.bvh_depth);
    bool measure_cell[2][2];
    choose_cells(o, backends, history, level, measure_cell);
    std::vector<double> seconds[2][2];
    std::vector<double> wall_seconds[2][2];
    for (int r = 0; r < o.repeats; ++r) {
        for (int b = 0; b < 2; ++b) {
            for (int a = 0; a < 2; ++a) {
                if (!measure_cell[b][a]) {
                    continue;
                }
                const trac0r_bench::Timing t =
                    trac0r_bench::measure(*backends[b], a == 0 ? flat : bvh, scene, o.frames);
                seconds[b][a].push_back(t.free_frame_seconds());
                wall_seconds[b][a].push_back(t.frame_seconds);
                std::fprintf(stderr, "  %s %s: %.1f ms/frame on free cores (wall %.1f ms)\n",
                             backend_names[b], accel_names[a], 1e3 * t.free_frame_seconds(),
                             1e3 * t.frame_seconds);
            }
        }
    }
    for (int b = 0; b < 2; ++b) {
        for (int a = 0; a < 2; ++a) {
            if (!measure_cell[b][a]) {
                continue;
            }
            std::vector<double>& v = seconds[b][a];
            std::vector<double>& w = wall_seconds[b][a];
            std::sort(v.begin(), v.end());
            std::sort(w.begin(), w.end());
            level.m[b][a].measured = true;
            level.m[b][a].frame_seconds = v[v.size() / 2];
            level.m[b][a].wall_frame_seconds = w[w.size() / 2];
        }
        if (measure_cell[b][0]) {
            history.seconds[b] = level.m[b][0].frame_seconds;
            history.triangles[b] = level.triangles;
        }
    }
    return level;
}

void print_table(const std::vector<Level>& levels) {
    std::printf(
        "| triangles | subdivisions | CPU flat fps | CPU BVH fps | OpenCL flat fps | "
        "OpenCL BVH fps | BVH pack s |\n");
    std::printf("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Level& l : levels) {
        std::printf("| %zu | %d | %s | %s | %s | %s | %.2f |\n", l.triangles, l.subdivisions,
                    fps_cell(l.m[0][0]).c_str(), fps_cell(l.m[0][1]).c_str(),
                    fps_cell(l.m[1][0]).c_str(), fps_cell(l.m[1][1]).c_str(), l.pack_bvh_seconds);
    }
    bool any_skipped = false;
    for (const Level& l : levels) {
        for (int b = 0; b < 2; ++b) {
            if (!l.m[b][0].why_skipped.empty()) {
                if (!any_skipped) {
                    std::printf("\nSkipped (brute force would take too long):\n");
                    any_skipped = true;
                }
                std::printf("- %zu triangles, %s flat: %s\n", l.triangles, backend_names[b],
                            l.m[b][0].why_skipped.c_str());
            }
        }
    }
}

int run(const Options& o) {
    // Checked and opened first: a bad path should fail now, not after
    // minutes of timing.
    const std::string problem = trac0r::unwritable_reason(o.csv_path);
    if (!problem.empty()) {
        throw UsageError("--csv " + o.csv_path + ": cannot be written (" + problem + ")");
    }
    std::ofstream csv(o.csv_path);
    if (!csv) {
        throw std::runtime_error("--csv " + o.csv_path + ": cannot write");
    }
    Backends backends;
    if (o.cpu) {
        backends[0].reset(new CpuBackend());
    }
    if (o.opencl) {
#ifdef TRAC0R_HAVE_OPENCL
        backends[1].reset(new OpenClBackend(0));  // throws when there is no device
#else
        throw UsageError(
            "--backends opencl: this build has no OpenCL backend "
            "(configured with TRAC0R_OPENCL=OFF); use --backends cpu");
#endif
    }
    std::printf(
        "%d x %d, %d timed frames after one warm-up (median of %d rounds), max depth "
        "from the scene, fps on %d free cores from CPU time (benchmarks/timing.h);",
        o.width, o.height, o.frames, o.repeats, trac0r_bench::machine_cores());
    for (int b = 0; b < 2; ++b) {
        if (backends[b]) {
            std::printf(" %s: %s;", backend_names[b], backends[b]->device().c_str());
        }
    }
    std::printf(" flat list skipped where predicted over %g s/frame\n\n", o.flat_limit);
    std::fflush(stdout);

    std::vector<Level> levels;
    FlatHistory history;
    for (int s = 0; s <= o.max_subdivisions; ++s) {
        levels.push_back(measure_level(o, backends, s, history));
    }
    print_table(levels);
    print_growth(levels);
    write_csv(csv, o, levels);
    std::printf("\nCSV: %s\n", o.csv_path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_complexity", [&] {
        Options o;
        return parse(argc, argv, o) ? run(o) : 0;
    });
}
