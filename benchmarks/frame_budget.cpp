// How much noise is too much for a frame budget (issue 31; the thesis asks
// for a sufficiently converged frame in 16.67 ms): for each budget, the
// error against a converged reference of what fits in it
//
//   raw       floor(B / t_spp) samples a pixel, the accumulated mean;
//   filtered  floor((B - t_filter) / t_spp), then the edge-preserving filter
//             (render_surface_guides, add_lamp_edges,
//             FilterWorkspace::set_guides, filter_image), the guides and
//             the workspace kept from frame to frame as the window keeps them;
//   temporal  while the camera moves, each frame floor((B - t_temporal) /
//             t_spp) samples blended with the previous frame reprojected
//             (render_surface_guides, temporal_blend), as trac0r_viewer's window
//             does.
//
// t_spp, t_filter and t_temporal are medians measured side by side in the
// same run, on the CPU backend with the viewer's defaults (NEE, Sobol).
// Times are CPU seconds over the machine's cores: a frame's time on that
// many free cores (benchmarks/timing.h), beside the wall clock.
#include "cli.h"
#include "reference_cache.h"
#include "timing.h"
#include "viewer_like.h"

#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/filter.h"
#include "trac0r/fly_camera.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/input_checks.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "trac0r/temporal.h"

#include <glm/glm.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace trac0r;
using trac0r_bench::cached_reference;
using trac0r_bench::Reference;
using trac0r_bench::reference_cache_base;
using trac0r_bench::reference_is_cached;
using trac0r_bench::scene_stem;
using trac0r_bench::UsageError;
using Clock = std::chrono::steady_clock;

const char* const description =
    "For each frame budget, the error against a converged reference of a frame that fits in "
    "it: raw (as many samples a pixel as fit), filtered (fewer samples, then the "
    "edge-preserving filter) and temporal (the camera moving, each frame's samples blended with "
    "the previous frame reprojected). The time of one sample a pixel, of the filter and of the "
    "temporal blend are measured side by side first, on the CPU backend with the viewer's "
    "defaults (NEE, Sobol). A mode whose overhead and one sample a pixel take longer than a "
    "budget is reported as \"does not fit\". Progress on stderr; the table on stdout; --csv and "
    "--images for benchmarks/plot_frame_budget.py.";

struct Options {
    std::string scene_path;
    long width = 400;
    long height = 300;
    std::string budgets_text = "16.7,33,100,1000";
    std::vector<double> budgets_ms;
    long repeats = 15;
    long reference_spp = 1024;
    long bias_spp = 256;
    double move_seconds = 1.0;
    double speed = 0.25;
    double max_history = TemporalSettings().max_history;
    std::string cache_dir = "frame_budget_cache";
    std::string images_dir;
    std::string csv_path;
};

std::vector<double> parse_budgets(const std::string& text) {
    std::vector<double> out;
    for (const std::string& part : trac0r_bench::split_commas(text)) {
        out.push_back(trac0r_bench::parse_number("--budgets", part, 0.001, 1e6));
    }
    std::sort(out.begin(), out.end());
    if (std::adjacent_find(out.begin(), out.end()) != out.end()) {
        throw UsageError("--budgets " + text + ": a budget is given twice");
    }
    return out;
}

void check_directory(const std::string& flag, const std::string& dir) {
    if (mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST) {
        throw UsageError(flag + " " + dir + ": cannot create the directory (" +
                         std::strerror(errno) + ")");
    }
    if (!is_directory(dir)) {
        throw UsageError(flag + " " + dir + ": not a directory");
    }
    if (access(dir.c_str(), W_OK | X_OK) != 0) {
        throw UsageError(flag + " " + dir + ": cannot write in the directory (" +
                         std::strerror(errno) + ")");
    }
}

Options parse_options(int argc, char** argv) {
    Options o;
    trac0r_cli::CommandLine cl("bench_frame_budget", "bench_frame_budget [SCENE.json] [options]",
                               description, 26);
    cl.positional("SCENE.json", &o.scene_path, "the scene (default: the built-in Cornell box)");
    cl.on_extra([](const std::string& a) { throw UsageError(a + ": only one scene file"); });
    cl.integer("--width", &o.width, 8, 16384, "resolution (default 400)", "W");
    cl.integer("--height", &o.height, 8, 16384, "resolution (default 300)", "H");
    cl.text("--budgets", &o.budgets_text,
            "frame budgets in milliseconds, comma-separated (default 16.7,33,100,1000)", "LIST");
    cl.integer("--repeats", &o.repeats, 1, 10000,
               "timed rounds of frame, filter and temporal blend; the medians count (default "
               "15)",
               "N");
    cl.integer("--reference-spp", &o.reference_spp, 1, 1L << 24,
               "samples a pixel of the converged reference, another seed, cached in --cache "
               "(default 1024)",
               "N");
    cl.integer("--bias-spp", &o.bias_spp, 0, 1L << 24,
               "also raw and filtered at N samples a pixel, whatever the budget: the filter's "
               "bias where the noise is low (default 256; 0: none)",
               "N");
    cl.number("--move-seconds", &o.move_seconds, 1e-3, 1e4,
              "temporal: the camera moves this long, at least two frames, ending at the "
              "scene's view (default 1)",
              "S");
    cl.number("--speed", &o.speed, 0.0, 1e3,
              "temporal: to the right, in scene diagonals a second (default 0.25, the window's)",
              "D");
    cl.number("--max-history", &o.max_history, 0.0, 1e9,
              "temporal: the most samples the history counts for (default: the library's)", "N");
    cl.text("--cache", &o.cache_dir,
            "where references are kept (default frame_budget_cache; created if missing)", "DIR");
    cl.text("--images", &o.images_dir,
            "write each mode's image and the reference as PFM in DIR (created if missing)", "DIR");
    cl.text("--csv", &o.csv_path, "write the table as CSV, with the images' paths", "FILE");
    if (!cl.parse_or_print(argc, argv)) {
        std::exit(0);
    }
    o.budgets_ms = parse_budgets(o.budgets_text);
    if (!o.csv_path.empty()) {
        const std::string reason = unwritable_reason(o.csv_path);
        if (!reason.empty()) {
            throw UsageError("--csv " + o.csv_path + ": cannot be written (" + reason + ")");
        }
    }
    if (!o.images_dir.empty()) {
        check_directory("--images", o.images_dir);
    }
    return o;
}

std::unique_ptr<Renderer> make_renderer(const Scene& scene, std::uint64_t seed) {
    return std::make_unique<Renderer>(scene, std::make_unique<CpuBackend>(), seed,
                                      trac0r::PackOptions());
}

// The converged reference of the scene's view: from the cache, or rendered
// (seed 0x5eed; the runs use seed 1) and put there.
Reference reference_image(const Options& o, const Scene& scene) {
    const std::string base = reference_cache_base(o.cache_dir, o.scene_path, o.width, o.height,
                                                  o.reference_spp, "-nee-sobol");
    if (!reference_is_cached(base)) {
        check_directory("--cache", o.cache_dir);
    }
    return cached_reference(base, scene, o.reference_spp);
}

// A measured time: on machine_cores() free cores (CPU seconds / cores) and
// by the wall clock.
struct Seconds {
    double free = 0.0;
    double wall = 0.0;
};

Seconds timed(const std::function<void()>& work) {
    const Clock::time_point start = Clock::now();
    const double cpu = trac0r_bench::process_cpu_seconds();
    work();
    return {(trac0r_bench::process_cpu_seconds() - cpu) / trac0r_bench::machine_cores(),
            std::chrono::duration<double>(Clock::now() - start).count()};
}

struct Costs {
    Seconds spp;       // one frame of one sample a pixel
    Seconds filter;    // guides + filter, on the accumulation
    Seconds temporal;  // guides + temporal_blend
};

Seconds median_of(const std::vector<Seconds>& v) {
    std::vector<double> free;
    std::vector<double> wall;
    for (const Seconds& s : v) {
        free.push_back(s.free);
        wall.push_back(s.wall);
    }
    return {trac0r_bench::median(free), trac0r_bench::median(wall)};
}

// The three costs, measured in turns (frame, filter, blend, frame, ...) so
// that a change in the machine's load falls on all alike, after one round
// of warm-up.
Costs measure_costs(const Scene& scene, const Options& o) {
    std::unique_ptr<Renderer> r = make_renderer(scene, 1);
    TemporalSettings settings;
    settings.max_history = static_cast<float>(o.max_history);
    TemporalFrame history;
    TemporalFrame spare;
    FilterWorkspace workspace;
    GuideImages guides;  // made every round into the same storage, as the window's
    std::vector<Seconds> spp;
    std::vector<Seconds> filter;
    std::vector<Seconds> temporal;
    for (long i = -1; i < o.repeats; ++i) {
        const Seconds a = timed([&] { r->render_frame(); });
        const Seconds b = timed([&] {
            render_surface_guides(r->packed(), r->camera_record(), &guides);
            add_lamp_edges(r->packed(), r->camera_record(), &guides);
            workspace.set_guides(guides);
            filter_image(r->accumulator(), T0_FILTER_PASSES, workspace);
        });
        const Seconds c = timed([&] {
            render_surface_guides(r->packed(), r->camera_record(), &guides);
            // Into the frame before, swapped, as the window's ViewHistory.
            temporal_blend(history, r->image(), 1.0f, r->camera_record(), guides, &spare, settings);
            std::swap(history, spare);
        });
        if (i >= 0) {
            spp.push_back(a);
            filter.push_back(b);
            temporal.push_back(c);
        }
    }
    return {median_of(spp), median_of(filter), median_of(temporal)};
}

// Samples a pixel that fit in budget seconds after overhead; 0: none.
long fitting_spp(double budget, double overhead, double per_spp) {
    const double left = budget - overhead;
    return left < per_spp ? 0 : static_cast<long>(std::floor(left / per_spp));
}

struct Row {
    double budget_ms;  // 0: not a budget (the bias rows)
    std::string mode;
    long spp;        // a pixel, in the frame (temporal: each frame's)
    long frames;     // temporal: frames of the move; else 1
    double used_ms;  // the frame's time at the measured costs
    bool fits;
    ImageError error;
    double reused;  // temporal: share of surface pixels that took history
    std::string image;
};

std::string budget_name(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%gms", ms);
    return text;
}

std::string write_image_file(const Options& o, const std::string& name, const Image& image) {
    if (o.images_dir.empty()) {
        return "";
    }
    const std::string path = o.images_dir + "/" + scene_stem(o.scene_path) + "-" +
                             std::to_string(o.width) + "x" + std::to_string(o.height) + "-" + name +
                             ".pfm";
    write_pfm(path, image);
    return path;
}

// Raw and filtered at each sample count asked for, from one progressive
// render of the scene's view (seed 1): raw_spp and filtered_spp map a
// sample count to the rows that want it.
void render_static(const Scene& scene, const Options& o, const Image& reference,
                   const std::set<long>& counts, const std::set<long>& filtered_counts,
                   std::map<std::pair<std::string, long>, Row>* done) {
    if (counts.empty()) {
        return;
    }
    std::unique_ptr<Renderer> r = make_renderer(scene, 1);
    const std::vector<kernel::FilterGuide> guides =
        filter_guides(render_guides(r->packed(), r->camera_record()));
    const Clock::time_point start = Clock::now();
    for (long n : counts) {
        while (static_cast<long>(r->frames()) < n) {
            r->render_frame();
        }
        std::fprintf(stderr, "raw and filtered: %ld spp, %.0f s\n", n,
                     std::chrono::duration<double>(Clock::now() - start).count());
        const Image raw = r->image();
        Row row{};
        row.mode = "raw";
        row.spp = n;
        row.frames = 1;
        row.fits = true;
        row.error = image_error(raw, reference);
        row.image = write_image_file(o, "raw-" + std::to_string(n) + "spp", raw);
        (*done)[{"raw", n}] = row;
        if (filtered_counts.count(n) != 0) {
            const Image filtered =
                filter_image(r->accumulator(), r->width(), r->height(), guides, T0_FILTER_PASSES);
            row.mode = "filtered";
            row.error = image_error(filtered, reference);
            row.image = write_image_file(o, "filtered-" + std::to_string(n) + "spp", filtered);
            (*done)[{"filtered", n}] = row;
        }
    }
}

// The camera moves right for the last --move-seconds before the frame (at
// least two frames), ending at the scene's view; each frame renders `spp`
// new samples a pixel and blends them with the previous frame reprojected.
Row render_temporal(const Scene& scene, const Options& o, const Image& reference, double budget_ms,
                    long spp) {
    const double budget = budget_ms / 1000.0;
    const long frames = std::max(2L, std::lround(o.move_seconds / budget));
    const float step = static_cast<float>(o.speed * budget) * trac0r_bench::scene_diagonal(scene);
    TemporalSettings settings;
    settings.max_history = static_cast<float>(o.max_history);
    std::unique_ptr<Renderer> r = make_renderer(scene, 1);
    TemporalFrame history;
    TemporalStats stats;
    for (long i = 0; i < frames; ++i) {
        const float back = static_cast<float>(frames - 1 - i) * step;
        r->set_camera(move_camera(scene.camera, glm::vec3(-back, 0.0f, 0.0f)));
        // Each frame its own samples, as the window's.
        r->set_frame_sequence(static_cast<std::uint32_t>(i * spp), 1);
        for (long k = 0; k < spp; ++k) {
            r->render_frame();
        }
        stats = TemporalStats();
        history = temporal_blend(history, r->image(), static_cast<float>(spp), r->camera_record(),
                                 render_surface_guides(r->packed(), r->camera_record()), settings,
                                 &stats);
    }
    std::fprintf(stderr, "temporal: %s, %ld frames of %ld spp\n", budget_name(budget_ms).c_str(),
                 frames, spp);
    const Image shown = history.image();
    Row row{};
    row.budget_ms = budget_ms;
    row.mode = "temporal";
    row.spp = spp;
    row.frames = frames;
    row.fits = true;
    row.error = image_error(shown, reference);
    const long surface = stats.reused + stats.dropped;
    row.reused = surface > 0 ? static_cast<double>(stats.reused) / surface : 0.0;
    row.image = write_image_file(o, "temporal-" + budget_name(budget_ms), shown);
    return row;
}

// The largest width x height of the run's aspect whose frame fits `budget`
// seconds, taking a frame's time as proportional to its pixels.
std::string largest_fitting(const Options& o, double budget, double per_frame) {
    const double pixels = static_cast<double>(o.width * o.height) * budget / per_frame;
    const double aspect = static_cast<double>(o.width) / static_cast<double>(o.height);
    const long h = static_cast<long>(std::floor(std::sqrt(pixels / aspect)));
    const long w = static_cast<long>(std::floor(static_cast<double>(h) * aspect));
    if (w < 1 || h < 1) {
        return "none";
    }
    return std::to_string(w) + " x " + std::to_string(h);
}

int run(int argc, char** argv) {
    const Options o = parse_options(argc, argv);
    Scene scene = o.scene_path.empty() ? builtin_scene() : load_scene_file(o.scene_path);
    scene.render.width = static_cast<int>(o.width);
    scene.render.height = static_cast<int>(o.height);
    const Reference reference = reference_image(o, scene);

    std::fprintf(stderr, "timing: %ld rounds of a 1-spp frame, the filter, the temporal blend\n",
                 o.repeats);
    const Costs costs = measure_costs(scene, o);
    const double t_spp = costs.spp.free;
    const double t_filter = costs.filter.free;
    const double t_temporal = costs.temporal.free;

    std::vector<Row> rows;
    std::set<long> counts;
    std::set<long> filtered_counts;
    for (double ms : o.budgets_ms) {
        const double b = ms / 1000.0;
        const long raw = fitting_spp(b, 0.0, t_spp);
        const long filtered = fitting_spp(b, t_filter, t_spp);
        const long temporal = fitting_spp(b, t_temporal, t_spp);
        rows.push_back({ms, "raw", raw, 1, 1000.0 * raw * t_spp, raw > 0, {}, 0.0, ""});
        rows.push_back({ms,
                        "filtered",
                        filtered,
                        1,
                        1000.0 * (filtered * t_spp + t_filter),
                        filtered > 0,
                        {},
                        0.0,
                        ""});
        rows.push_back({ms,
                        "temporal",
                        temporal,
                        0,
                        1000.0 * (temporal * t_spp + t_temporal),
                        temporal > 0,
                        {},
                        0.0,
                        ""});
        if (raw > 0) {
            counts.insert(raw);
        }
        if (filtered > 0) {
            counts.insert(filtered);
            filtered_counts.insert(filtered);
        }
    }
    if (o.bias_spp > 0) {
        counts.insert(o.bias_spp);
        filtered_counts.insert(o.bias_spp);
        rows.push_back({0.0, "raw", o.bias_spp, 1, 1000.0 * o.bias_spp * t_spp, true, {}, 0.0, ""});
        rows.push_back({0.0,
                        "filtered",
                        o.bias_spp,
                        1,
                        1000.0 * (o.bias_spp * t_spp + t_filter),
                        true,
                        {},
                        0.0,
                        ""});
    }
    std::map<std::pair<std::string, long>, Row> done;
    render_static(scene, o, reference.image, counts, filtered_counts, &done);
    for (Row& row : rows) {
        if (!row.fits) {
            continue;
        }
        if (row.mode == "temporal") {
            const double used = row.used_ms;
            row = render_temporal(scene, o, reference.image, row.budget_ms, row.spp);
            row.used_ms = used;
        } else {
            const Row& d = done.at({row.mode, row.spp});
            row.error = d.error;
            row.image = d.image;
        }
    }
    const std::string reference_path = write_image_file(o, "reference", reference.image);

    std::printf("scene %s, %ld x %ld, CPU backend, NEE, Sobol, %d threads\n",
                o.scene_path.empty() ? "(built-in)" : o.scene_path.c_str(), o.width, o.height,
                trac0r_bench::machine_cores());
    std::printf("reference: %ld spp, another seed, its own estimated relative MSE %.3g\n",
                o.reference_spp, reference.own_rel_mse);
    std::printf("median of %ld rounds, ms on %d free cores (wall ms):\n", o.repeats,
                trac0r_bench::machine_cores());
    std::printf(
        "  1-spp frame %.2f (%.2f), guides + filter %.2f (%.2f), guides + temporal blend "
        "%.2f (%.2f)\n",
        1000.0 * t_spp, 1000.0 * costs.spp.wall, 1000.0 * t_filter, 1000.0 * costs.filter.wall,
        1000.0 * t_temporal, 1000.0 * costs.temporal.wall);
    std::printf(
        "largest resolution at which one sample a pixel fits (frame time taken as "
        "proportional to pixels):\n");
    std::printf("  %10s %16s %16s %16s\n", "budget ms", "raw", "filtered", "temporal");
    for (double ms : o.budgets_ms) {
        const double b = ms / 1000.0;
        std::printf("  %10g %16s %16s %16s\n", ms, largest_fitting(o, b, t_spp).c_str(),
                    largest_fitting(o, b, t_spp + t_filter).c_str(),
                    largest_fitting(o, b, t_spp + t_temporal).c_str());
    }
    std::printf("%10s %-9s %6s %6s %8s %10s %12s %8s %7s\n", "budget ms", "mode", "spp", "frames",
                "used ms", "RMSE", "relative MSE", "PSNR dB", "reused");
    for (const Row& row : rows) {
        const std::string budget = row.budget_ms > 0.0 ? budget_name(row.budget_ms) : "-";
        if (!row.fits) {
            std::printf("%10s %-9s does not fit: %s\n", budget.c_str(), row.mode.c_str(),
                        row.mode == "raw" ? "one sample a pixel takes longer"
                                          : "its overhead and one sample a pixel take longer");
            continue;
        }
        char reused[16] = "";
        if (row.mode == "temporal") {
            std::snprintf(reused, sizeof reused, "%.0f %%", 100.0 * row.reused);
        }
        std::printf("%10s %-9s %6ld %6ld %8.1f %10.4f %12.5f %8.2f %7s\n", budget.c_str(),
                    row.mode.c_str(), row.spp, row.frames, row.used_ms, row.error.rmse,
                    row.error.relative_mse, row.error.psnr, reused);
    }
    if (!o.csv_path.empty()) {
        std::ofstream csv(o.csv_path);
        csv << "scene,width,height,budget_ms,mode,spp,frames,used_ms,fits,rmse,relative_mse,psnr,"
               "reused,spp_ms,filter_ms,temporal_ms,reference_spp,reference_rel_mse,image,"
               "reference\n";
        for (const Row& row : rows) {
            csv << scene_stem(o.scene_path) << "," << o.width << "," << o.height << ",";
            if (row.budget_ms > 0.0) {
                csv << row.budget_ms;
            }
            csv << "," << row.mode << "," << row.spp << "," << row.frames << "," << row.used_ms
                << "," << (row.fits ? 1 : 0) << ",";
            if (row.fits) {
                csv << row.error.rmse << "," << row.error.relative_mse << "," << row.error.psnr;
            } else {
                csv << ",,";
            }
            csv << "," << (row.mode == "temporal" && row.fits ? std::to_string(row.reused) : "")
                << "," << 1000.0 * t_spp << "," << 1000.0 * t_filter << "," << 1000.0 * t_temporal
                << "," << o.reference_spp << "," << reference.own_rel_mse << "," << row.image << ","
                << reference_path << "\n";
        }
        if (!csv) {
            throw std::runtime_error(o.csv_path + ": cannot be written");
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_frame_budget", [&] { return run(argc, argv); });
}
