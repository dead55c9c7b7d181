// Error against run time: renders a scene with one or more configurations,
// takes checkpoints at doubling samples per pixel, and at each reports the
// wall time, RMSE, relative MSE and PSNR against a reference image, beside
// the renderer's own estimate of the relative MSE (no reference needed),
// how long each configuration takes to the first one's final error, and
// with --target-rmse or --target-relmse, the samples and time each takes to
// a given error.
//
//   build/benchmarks/bench_convergence [SCENE.json] [options]
//
// See --help. Writes a table on stdout and a CSV; plot the CSV with
// benchmarks/plot_convergence.py. Every configuration is measured in the
// same run, one after the other, so their times compare.
#include "trac0r/cpu_backend.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include "cli.h"
#include "reference_cache.h"
#include "timing.h"
#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_backend.h"
#endif

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

using Clock = std::chrono::steady_clock;
using trac0r_bench::cached_reference;
using trac0r_bench::parse_long;
using trac0r_bench::Reference;
using trac0r_bench::reference_cache_base;
using trac0r_bench::reference_is_cached;
using trac0r_bench::UsageError;

const char* const description =
    "Renders SCENE.json (default: the built-in Cornell box) with each --config, with "
    "checkpoints at 1, 2, 4, ... samples per pixel (the configurations take turns frame by "
    "frame, so they share the machine's load alike), and prints at each the render time, RMSE, "
    "relative MSE and PSNR against a reference, and the renderer's own relative MSE estimate; "
    "then the fitted slopes and, with two or more configurations, the time each of the others "
    "takes to the first one's error at its last checkpoint, and the samples and time each "
    "takes to --target-rmse and --target-relmse.";

struct Config {
    std::string backend = "cpu";
    std::string accel = "auto";
    std::string integrator = "naive";
    std::string sampler = "random";
    std::string light_sampler = "auto";
    int max_depth = 0;  // 0: the scene's
    std::string label;
};

struct Options {
    std::string scene_path;
    std::vector<Config> configs;
    long max_spp = 1024;
    double seconds = 0.0;
    double target_rmse = 0.0;    // 0: none
    double target_relmse = 0.0;  // 0: none
    std::vector<int> region;     // --region: x0, y0, x1, y1; empty: the whole image
    int width = 200;
    int height = 150;
    std::string reference_path;
    long reference_spp = 0;  // 0: not given
    std::string cache_dir = "convergence_cache";
    std::string csv_path = "convergence.csv";
};

Config parse_config(const std::string& spec) {
    if (spec.empty()) {
        throw UsageError("--config: expected comma-separated key=value (e.g. backend=cpu), got ''");
    }
    Config c;
    std::set<std::string> seen;
    for (const std::string& part : trac0r_bench::split_commas(spec)) {
        const std::size_t eq = part.find('=');
        const std::string key = part.substr(0, eq);
        const std::string value = eq == std::string::npos ? "" : part.substr(eq + 1);
        const std::string where = "--config " + spec + ": " + key;
        if (part.empty()) {
            throw UsageError("--config " + spec +
                             ": an empty key=value (two commas, or one at an end)");
        }
        if (!seen.insert(key).second) {
            throw UsageError("--config " + spec + ": key '" + key + "' given twice");
        }
        if (key == "backend" && (value == "cpu" || value == "opencl")) {
            c.backend = value;
        } else if (key == "accel" && (value == "flat" || value == "bvh" || value == "auto")) {
            c.accel = value;
        } else if (key == "max_depth") {
            c.max_depth = static_cast<int>(parse_long(where, value, 1, 100000));
        } else if (key == "integrator" && (value == "naive" || value == "nee" || value == "bdpt")) {
            c.integrator = value;
        } else if (key == "sampler" && (value == "random" || value == "sobol")) {
            c.sampler = value;
        } else if (key == "light_sampler" &&
                   (value == "power" || value == "tree" || value == "auto")) {
            c.light_sampler = value;
        } else if (key == "backend" || key == "accel" || key == "integrator" || key == "sampler" ||
                   key == "light_sampler") {
            throw UsageError(where + ": unknown value '" + value + "'");
        } else {
            throw UsageError("--config " + spec + ": unknown key '" + key +
                             "' (expected backend, accel, max_depth, integrator, sampler, "
                             "light_sampler)");
        }
    }
    c.label = c.backend + (c.accel == "auto" ? "" : " " + c.accel) +
              (c.max_depth > 0 ? " depth " + std::to_string(c.max_depth) : "") +
              (c.integrator == "naive" ? "" : " " + c.integrator) +
              (c.sampler == "random" ? "" : " " + c.sampler) +
              (c.light_sampler == "auto" ? "" : " lights by " + c.light_sampler);
#ifndef TRAC0R_HAVE_OPENCL
    if (c.backend == "opencl") {
        throw UsageError("--config " + spec + ": this build has no OpenCL backend");
    }
#endif
    return c;
}

// "x0,y0,x1,y1": four integers, x0 < x1 and y0 < y1, none negative.
std::vector<int> parse_region(const std::string& v) {
    std::vector<int> r;
    std::stringstream in(v);
    std::string part;
    while (std::getline(in, part, ',')) {
        r.push_back(static_cast<int>(parse_long("--region", part, 0, 16384)));
    }
    if (r.size() != 4 || r[0] < 0 || r[1] < 0 || r[0] >= r[2] || r[1] >= r[3]) {
        throw UsageError("--region " + v +
                         ": expected X0,Y0,X1,Y1 with 0 <= X0 < X1, 0 <= Y0 < Y1");
    }
    return r;
}

// The pixels of `region` (x0, y0, x1, y1) of an image; the image itself
// for no region.
Image region_of(const Image& image, const std::vector<int>& region) {
    if (region.size() != 4) {
        return image;
    }
    Image out;
    out.width = region[2] - region[0];
    out.height = region[3] - region[1];
    for (int y = region[1]; y < region[3]; ++y) {
        for (int x = region[0]; x < region[2]; ++x) {
            out.pixels.push_back(image.at(x, y));
        }
    }
    return out;
}

// --help and --version are printed, and end the program.
Options parse_options(int argc, char** argv) {
    Options o;
    trac0r_cli::CommandLine cl("bench_convergence", "bench_convergence [SCENE.json] [options]",
                               description, 22);
    cl.positional("SCENE.json", &o.scene_path, "the scene (default: the built-in Cornell box)");
    cl.on_extra([](const std::string& a) { throw UsageError(a + ": only one scene file"); });
    cl.repeated(
        "--config", "SPEC",
        "a configuration, repeatable (default: backend=cpu): comma-separated key=value "
        "of backend=cpu|opencl, accel=flat|bvh|auto, max_depth=N, integrator=naive|nee|bdpt, "
        "sampler=random|sobol, light_sampler=power|tree|auto (default: the library's, "
        "cpu, auto, the scene's depth, naive, random, auto), each key at most once\ne.g. "
        "--config backend=opencl --config "
        "backend=cpu,max_depth=2",
        [&o](const std::string& v) { o.configs.push_back(parse_config(v)); });
    cl.integer("--max-spp", &o.max_spp, 1, 1L << 24, "last checkpoint (default 1024)");
    cl.number("--target-rmse", &o.target_rmse, 1e-9, 1e9,
              "report the samples and time each configuration takes to an RMSE of E "
              "(interpolated between checkpoints); once it has reached every target, a "
              "configuration stops",
              "E");
    cl.number("--target-relmse", &o.target_relmse, 1e-9, 1e9, "the same for a relative MSE of E",
              "E");
    cl.number("--seconds", &o.seconds, 1e-6, 1e9,
              "no new checkpoint once a configuration has rendered S s (on free cores, as in "
              "the table), S in [1e-06, 1e+09]",
              "S");
    cl.integer("--width", &o.width, 1, 16384, "resolution (default 200)", "W");
    cl.integer("--height", &o.height, 1, 16384, "resolution (default 150)", "H");
    cl.text("--reference", &o.reference_path,
            "reference image (.pfm, the same resolution); default: rendered on the CPU with "
            "another seed at --reference-spp and cached in --cache");
    cl.integer("--reference-spp", &o.reference_spp, 1, 1L << 24,
               "samples per pixel of a rendered reference (default 16 x --max-spp); not with "
               "--reference");
    cl.text("--cache", &o.cache_dir,
            "where rendered references are kept (default convergence_cache; created if "
            "missing, its parent must exist; checked before anything renders)",
            "DIR");
    cl.text("--csv", &o.csv_path, "write the checkpoints as CSV (default convergence.csv)");
    cl.value("--region", "X0,Y0,X1,Y1",
             "measure the errors in the pixels x0 <= x < x1, y0 <= y < y1 alone (row 0 at the "
             "top), e.g. a caustic",
             [&o](const std::string& v) { o.region = parse_region(v); });
    if (!cl.parse_or_print(argc, argv)) {
        std::exit(0);
    }
    if (o.configs.empty()) {
        o.configs.push_back(parse_config("backend=cpu"));
    }
    if (o.region.size() == 4 && (o.region[2] > o.width || o.region[3] > o.height)) {
        throw UsageError("--region: reaches past the " + std::to_string(o.width) + " x " +
                         std::to_string(o.height) + " image");
    }
    if (!o.scene_path.empty() && trac0r::same_file(o.scene_path, o.csv_path)) {
        throw UsageError("--csv " + o.csv_path + ": is the scene file; it would be overwritten");
    }
    if (!o.reference_path.empty() && trac0r::same_file(o.reference_path, o.csv_path)) {
        throw UsageError("--csv " + o.csv_path +
                         ": is the --reference image; it would be "
                         "overwritten");
    }
    if (o.reference_spp != 0 && !o.reference_path.empty()) {
        throw UsageError("--reference-spp: only for a rendered reference; --reference " +
                         o.reference_path + " gives the reference image");
    }
    if (o.reference_spp == 0) {
        o.reference_spp = 16 * o.max_spp;
    }
    return o;
}

std::unique_ptr<Backend> make_backend(const std::string& name) {
#ifdef TRAC0R_HAVE_OPENCL
    if (name == "opencl") {
        if (list_opencl_devices().empty()) {
            throw std::runtime_error("backend=opencl: no OpenCL device found");
        }
        return std::make_unique<OpenClBackend>(0);
    }
#endif
    return std::make_unique<CpuBackend>();
}

// The cache's file name of the rendered reference, without its extension.
std::string cached_reference_base(const Options& o) {
    return reference_cache_base(o.cache_dir, o.scene_path, o.width, o.height, o.reference_spp);
}

// The cache directory, made if missing, and writable: checked before the
// reference renders, which can take longer than the run itself.
void prepare_cache_dir(const std::string& dir) {
    if (mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST) {
        throw UsageError("--cache " + dir + ": cannot create the directory (" +
                         std::strerror(errno) + ")");
    }
    if (!trac0r::is_directory(dir)) {
        throw UsageError("--cache " + dir + ": not a directory");
    }
    if (access(dir.c_str(), W_OK | X_OK) != 0) {
        throw UsageError("--cache " + dir + ": cannot write in the directory (" +
                         std::strerror(errno) + ")");
    }
}

// The --reference image, or the rendered one: from the cache, under
// cache_base, or rendered and put there.
Reference reference_image(const Options& o, const Scene& scene, const std::string& cache_base) {
    if (!o.reference_path.empty()) {
        Reference ref{read_pfm(o.reference_path), 0.0};
        if (ref.image.width != o.width || ref.image.height != o.height) {
            throw UsageError("--reference " + o.reference_path + ": the image is " +
                             std::to_string(ref.image.width) + "x" +
                             std::to_string(ref.image.height) + ", the run is " +
                             std::to_string(o.width) + "x" + std::to_string(o.height));
        }
        std::fprintf(stderr, "reference: %s (its own noise unknown, taken as 0)\n",
                     o.reference_path.c_str());
        return ref;
    }
    return cached_reference(cache_base, scene, o.reference_spp);
}

struct Checkpoint {
    long spp;
    double seconds;  // on machine_cores() free cores: CPU seconds / cores
    double wall_seconds;
    ImageError error;
    double estimated_rel_mse;
};

// Least-squares slope of log(y) against log(x).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double lx = std::log(x[i]);
        const double ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The two errors a target can be given in.
double rmse_of(const Checkpoint& p) { return p.error.rmse; }
double relative_mse_of(const Checkpoint& p) { return p.error.relative_mse; }

// Where a configuration's error (`metric`, relative MSE unless told) first
// falls to `target`: the checkpoint before it and the one at or below it,
// interpolated on the log-log curve (error, spp and time each taken as a
// power law between the two). False if it never gets there, or is there at
// its first checkpoint already (nothing to interpolate from).
bool reaches(const std::vector<Checkpoint>& points, double target, double* spp, double* seconds,
             double (*metric)(const Checkpoint&) = relative_mse_of) {
    for (std::size_t i = 1; i < points.size(); ++i) {
        const Checkpoint& a = points[i - 1];
        const Checkpoint& b = points[i];
        if (metric(a) > target && metric(b) <= target) {
            const double f = std::log(target / metric(a)) / std::log(metric(b) / metric(a));
            *spp = a.spp * std::pow(static_cast<double>(b.spp) / a.spp, f);
            *seconds = a.seconds * std::pow(b.seconds / a.seconds, f);
            return true;
        }
    }
    return false;
}

int run(const Options& o) {
    Scene scene = o.scene_path.empty() ? builtin_scene() : load_scene_file(o.scene_path);
    scene.render.width = o.width;
    scene.render.height = o.height;
    // Where the results go, checked before the reference renders.
    // The cache's name reads and hashes the scene file: made once.
    const std::string cache_base = o.reference_path.empty() ? cached_reference_base(o) : "";
    if (o.reference_path.empty() && !reference_is_cached(cache_base)) {
        prepare_cache_dir(o.cache_dir);
    }
    // Checked now, but opened (and so emptied) only once the reference is
    // there: a reference that fails or is stopped leaves the last CSV as it was.
    const std::string csv_problem = trac0r::unwritable_reason(o.csv_path);
    if (!csv_problem.empty()) {
        throw UsageError("--csv " + o.csv_path + ": cannot be written (" + csv_problem + ")");
    }
    const Reference ref = reference_image(o, scene, cache_base);
    std::ofstream csv(o.csv_path);
    if (!csv) {
        throw std::runtime_error("--csv " + o.csv_path + ": cannot write");
    }

    csv << "config,spp,seconds,rmse,rel_mse,psnr,estimated_rel_mse,reference_rel_mse,"
           "wall_seconds\n";
    std::printf("scene %s, %dx%d, reference %s (its own rel. MSE %.2g)\n\n",
                o.scene_path.empty() ? "built-in Cornell box" : o.scene_path.c_str(), o.width,
                o.height, o.reference_path.empty() ? "rendered" : o.reference_path.c_str(),
                ref.own_rel_mse);
    std::printf(
        "seconds: render time on %d free cores (the process's CPU time over all its\n"
        "threads / %d; the wall clock measures a shared machine's load as well),\n"
        "frames of all configurations interleaved, after one warm-up frame each\n"
        "(no OpenCL build); wall s: the wall clock\n\n",
        trac0r_bench::machine_cores(), trac0r_bench::machine_cores());
    std::printf(
        "| config | spp | seconds | wall s | RMSE | rel. MSE | PSNR dB | estimated rel. MSE |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    // Every configuration renders in turn, one frame each, so all of them
    // see the same load on a shared machine: their times compare side by
    // side. Each frame is timed on its own.
    struct Run {
        const Config* config;
        std::unique_ptr<Renderer> renderer;
        double seconds;  // on free cores, from CPU time
        double wall_seconds;
        bool stopped;
        std::vector<Checkpoint> points;
    };
    std::vector<Run> runs;
    for (const Config& c : o.configs) {
        Scene s = scene;
        if (c.max_depth > 0) {
            s.render.max_depth = c.max_depth;
        }
        PackOptions pack;
        pack.accel = parse_accel(c.accel);
        pack.integrator = parse_integrator(c.integrator);
        pack.sampler = parse_sampler(c.sampler);
        pack.light_sampler = parse_light_sampler(c.light_sampler);
        std::unique_ptr<Renderer> r(new Renderer(s, make_backend(c.backend), 1, pack));
        // One frame first, then thrown away: the OpenCL program build and
        // first-touch allocations are not render time. Frames are seeded by
        // (seed, frame), so the image after restart() is the same as without.
        r->render_frame();
        r->restart();
        runs.push_back(Run{&c, std::move(r), 0.0, 0.0, false, {}});
    }
    const struct Target {
        const char* name;
        double value;  // 0: not asked for
        double (*metric)(const Checkpoint&);
    } targets[] = {{"an RMSE", o.target_rmse, rmse_of},
                   {"a relative MSE", o.target_relmse, relative_mse_of}};
    const bool any_target = o.target_rmse > 0.0 || o.target_relmse > 0.0;
    // Whether a checkpoint is at or below every target asked for.
    const auto at_targets = [&](const Checkpoint& p) {
        for (const Target& t : targets) {
            if (t.value > 0.0 && t.metric(p) > t.value) {
                return false;
            }
        }
        return true;
    };
    for (long spp = 1; spp <= o.max_spp; spp *= 2) {
        if (std::all_of(runs.begin(), runs.end(), [](const Run& r) { return r.stopped; })) {
            break;
        }
        for (Run& run : runs) {
            run.stopped = run.stopped || (o.seconds > 0.0 && run.seconds >= o.seconds);
        }
        bool pending = true;
        while (pending) {
            pending = false;
            for (Run& run : runs) {
                if (!run.stopped && static_cast<long>(run.renderer->frames()) < spp) {
                    const Clock::time_point start = Clock::now();
                    const double cpu_start = trac0r_bench::process_cpu_seconds();
                    run.renderer->render_frame();  // returns when the frame is done
                    run.seconds += (trac0r_bench::process_cpu_seconds() - cpu_start) /
                                   trac0r_bench::machine_cores();
                    run.wall_seconds += std::chrono::duration<double>(Clock::now() - start).count();
                    pending = true;
                }
            }
        }
        for (Run& run : runs) {
            if (run.stopped) {
                continue;
            }
            Renderer& r = *run.renderer;
            run.points.push_back(Checkpoint{
                spp, run.seconds, run.wall_seconds,
                image_error(region_of(r.image(), o.region), region_of(ref.image, o.region)),
                spp >= 2 ? estimate_relative_mse(r.accumulator(), o.width, o.height)
                         : std::nan("")});
            // There: the next checkpoints would only cost time.
            run.stopped = any_target && at_targets(run.points.back());
        }
        std::fprintf(stderr, "  checkpoint %ld spp\n", spp);
    }
    std::vector<std::string> slopes;
    for (const Run& run : runs) {
        const Config& c = *run.config;
        const std::vector<Checkpoint>& points = run.points;
        for (const Checkpoint& p : points) {
            std::printf("| %s | %ld | %.3f | %.3f | %.4g | %.4g | %.2f | %.4g |\n", c.label.c_str(),
                        p.spp, p.seconds, p.wall_seconds, p.error.rmse, p.error.relative_mse,
                        p.error.psnr, p.estimated_rel_mse);
            csv << '"' << c.label << "\"," << p.spp << ',' << p.seconds << ',' << p.error.rmse
                << ',' << p.error.relative_mse << ',' << p.error.psnr << ',' << p.estimated_rel_mse
                << ',' << ref.own_rel_mse << ',' << p.wall_seconds << '\n';
        }
        // The slope where the reference's own noise is under a tenth of the
        // error and the per-pixel estimates have settled (8 spp on).
        std::vector<double> t, rel, rmse;
        std::vector<long> used;
        for (const Checkpoint& p : points) {
            if (p.spp >= 8 && p.error.relative_mse > 10.0 * ref.own_rel_mse) {
                used.push_back(p.spp);
                t.push_back(p.seconds);
                rel.push_back(p.error.relative_mse);
                rmse.push_back(p.error.rmse);
            }
        }
        char line[200];
        if (t.size() >= 2) {
            std::snprintf(line, sizeof line,
                          "%s: rel. MSE ~ time^%.2f, RMSE ~ time^%.2f (%zu checkpoints, %ld..%ld "
                          "spp)",
                          c.label.c_str(), log_log_slope(t, rel), log_log_slope(t, rmse), t.size(),
                          used.front(), used.back());
        } else {
            std::snprintf(line, sizeof line, "%s: too few checkpoints for a slope",
                          c.label.c_str());
        }
        slopes.push_back(line);
    }
    std::printf("\nFitted slopes (Monte Carlo: rel. MSE ~ time^-1, RMSE ~ time^-0.5):\n");
    for (const std::string& s : slopes) {
        std::printf("  %s\n", s.c_str());
    }
    // A configuration's mean cost per sample over the whole run: seconds on
    // the free cores per frame.
    const auto cost = [](const Run& run) {
        return run.seconds / static_cast<double>(run.renderer->frames());
    };
    // How long each other configuration takes to the first one's final
    // error: the figure that says which is worth its cost per sample. The
    // samples it needs come from the error curve, which the fixed seeds
    // make the same on every run; the time, from its mean cost per sample
    // over all its frames, which took turns with the first one's over the
    // whole run, so that a slow spell of a shared machine falls on both
    // alike (the time its checkpoints give covers only the run's start).
    if (runs.size() > 1 && !runs[0].points.empty()) {
        // "2.00 x fewer", "2.00 x more" or `same`: another configuration
        // against the first.
        const auto compared = [](double first_over_this, const char* fewer, const char* more,
                                 const char* same) {
            if (std::fabs(first_over_this - 1.0) < 0.005) {
                return std::string(same);
            }
            const bool fewer_here = first_over_this >= 1.0;
            char text[48];
            std::snprintf(text, sizeof text, "%.2f x %s",
                          fewer_here ? first_over_this : 1.0 / first_over_this,
                          fewer_here ? fewer : more);
            return std::string(text);
        };
        const Checkpoint& last = runs[0].points.back();
        const double target = last.error.relative_mse;
        std::printf(
            "\nTime to %s's relative MSE at its last checkpoint (%.4g at %ld spp): the samples "
            "needed, interpolated on the log-log curve between the checkpoints either side, at "
            "each configuration's mean cost per sample over the run:\n",
            runs[0].config->label.c_str(), target, last.spp);
        for (std::size_t k = 1; k < runs.size(); ++k) {
            const Run& run = runs[k];
            double spp = 0.0;
            double seconds = 0.0;
            const char* label = run.config->label.c_str();
            if (run.points.empty()) {
                std::printf("  %s: no checkpoint\n", label);
            } else if (run.points.front().error.relative_mse <= target) {
                std::printf("  %s: there by its first checkpoint (%ld spp)\n", label,
                            run.points.front().spp);
            } else if (reaches(run.points, target, &spp, &seconds)) {
                const double samples = last.spp / spp;
                const double cost_ratio = cost(run) / cost(runs[0]);
                std::printf(
                    "  %s: %.0f spp (%s samples) at %.2f x the cost per sample: %s time "
                    "(%.3f s against %.3f s; by its checkpoints' own times %.3f s, %s)\n",
                    label, spp, compared(samples, "fewer", "more", "as many").c_str(), cost_ratio,
                    compared(samples / cost_ratio, "less", "more", "the same").c_str(),
                    spp * cost(run), last.spp * cost(runs[0]), seconds,
                    compared(last.seconds / seconds, "less", "more", "the same").c_str());
            } else {
                std::printf("  %s: not reached by %ld spp (%.4g)\n", label, run.points.back().spp,
                            run.points.back().error.relative_mse);
            }
        }
    }
    std::printf("\nMean cost per sample over the run (seconds on free cores / frames):\n");
    for (const Run& run : runs) {
        std::printf("  %s: %.4f s (%.3f x %s's)\n", run.config->label.c_str(), cost(run),
                    cost(run) / cost(runs[0]), runs[0].config->label.c_str());
    }
    // The samples and time to each target: spp interpolated on the log-log
    // error curve, time from the mean cost per sample (as above) and from
    // the checkpoints' own times.
    for (const Target& t : targets) {
        if (t.value <= 0.0) {
            continue;
        }
        std::printf(
            "\nTo %s of %.4g: the samples needed, interpolated on the log-log curve between "
            "the checkpoints either side; the time at the mean cost per sample over the run (by "
            "the checkpoints' own times):\n",
            t.name, t.value);
        double first_seconds = 0.0;
        for (std::size_t k = 0; k < runs.size(); ++k) {
            const Run& run = runs[k];
            const char* label = run.config->label.c_str();
            double spp = 0.0;
            double seconds = 0.0;
            if (run.points.empty()) {
                std::printf("  %s: no checkpoint\n", label);
            } else if (t.metric(run.points.front()) <= t.value) {
                std::printf("  %s: there by its first checkpoint (%ld spp)\n", label,
                            run.points.front().spp);
            } else if (reaches(run.points, t.value, &spp, &seconds, t.metric)) {
                std::printf("  %s: %.0f spp, %.2f s (%.2f s)", label, spp, spp * cost(run),
                            seconds);
                if (k == 0) {
                    first_seconds = spp * cost(run);
                } else if (first_seconds > 0.0) {
                    std::printf(", %.2f x %s's time", spp * cost(run) / first_seconds,
                                runs[0].config->label.c_str());
                }
                std::printf("\n");
            } else {
                std::printf("  %s: not reached by %ld spp (%.4g)\n", label, run.points.back().spp,
                            t.metric(run.points.back()));
            }
        }
    }
    std::fprintf(stderr, "wrote %s\n", o.csv_path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_convergence",
                                  [&] { return run(parse_options(argc, argv)); });
}
