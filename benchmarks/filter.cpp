// What the edge-preserving filter (docs/filter.md) costs against a frame,
// and what it buys: on the CPU backend (NEE, Sobol: the viewer's defaults),
// 1-spp frames and filter runs over a --spp accumulation alternate (frame,
// filter, frame, filter, ...), so that the machine's load falls on both
// alike; prints the medians and their ratio (issue 31's target: at most
// 0.15), for the filter in new buffers and in a workspace kept between
// calls with its guides (FilterWorkspace::set_guides). With --reference,
// also the errors of the filtered --spp image, the raw one and the raw
// --compare-spp one, over --seeds renders.
//
//   build/benchmarks/bench_filter [SCENE.json] [options]
//
// See --help. Timings live here, never in the tests.
#include "cli.h"
#include "timing.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/filter.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

using Clock = std::chrono::steady_clock;

const char* const description =
    "The filter's cost against a frame on the CPU backend (NEE, Sobol): 1-spp frames and "
    "filter runs over a --spp accumulation alternate, and the medians of each (wall clock and "
    "the process's CPU time) and their ratio are printed. With --reference, also the RMSE, "
    "relative MSE and mean of the filtered --spp image, the raw one and the raw "
    "--compare-spp one, averaged over --seeds renders, and with two or more seeds the "
    "filtered image's squared bias and variance.";

struct Options {
    std::string scene_path;
    int width = 800;
    int height = 600;
    int rounds = 11;
    int spp = 4;
    int compare_spp = 64;
    int seeds = 1;
    int passes = T0_FILTER_PASSES;
    std::string reference_path;
};

std::unique_ptr<Renderer> render(const Scene& scene, std::uint64_t seed, int spp) {
    std::unique_ptr<Renderer> r(
        new Renderer(scene, std::make_unique<CpuBackend>(), seed, trac0r::PackOptions()));
    for (int i = 0; i < spp; ++i) {
        r->render_frame();
    }
    return r;
}

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double mean_luminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels) {
        sum += kernel::luminance(p);
    }
    return sum / static_cast<double>(image.pixels.size());
}

void timing(const Scene& scene, const Options& o) {
    const std::unique_ptr<Renderer> r = render(scene, 1, o.spp);
    const std::vector<kernel::FilterGuide> guides =
        filter_guides(render_guides(r->packed(), r->camera_record()));
    const std::vector<kernel::AccumPixel> accum = r->accumulator();
    filter_image(accum, o.width, o.height, guides, o.passes);  // warm-up
    FilterWorkspace workspace;
    workspace.set_guides(guides, o.width, o.height);
    filter_image(accum, o.passes, workspace);
    // Per round: a frame, the filter in new buffers (as --filter runs it
    // once), the filter in a workspace kept from the last round, with its
    // guides (as the window filters a view again and again).
    std::vector<double> wall[3], cpu[3];
    for (int i = 0; i < o.rounds; ++i) {
        for (int k = 0; k < 3; ++k) {
            const Clock::time_point start = Clock::now();
            const double cpu_start = trac0r_bench::process_cpu_seconds();
            if (k == 0) {
                r->render_frame();
            } else if (k == 1) {
                filter_image(accum, o.width, o.height, guides, o.passes);
            } else {
                filter_image(accum, o.passes, workspace);
            }
            wall[k].push_back(seconds_since(start));
            cpu[k].push_back(trac0r_bench::process_cpu_seconds() - cpu_start);
        }
    }
    using trac0r_bench::median;
    std::printf("%d x %d, CPU backend, %d threads; medians of %d alternated rounds\n\n", o.width,
                o.height, omp_get_max_threads(), o.rounds);
    std::printf(
        "| | 1-spp frame | filter (%d passes), new buffers | filter, workspace kept | new / frame "
        "| kept / frame |\n",
        o.passes);
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: |\n");
    const char* names[2] = {"wall clock", "CPU time"};
    std::vector<double>* figures[2] = {wall, cpu};
    for (int m = 0; m < 2; ++m) {
        const double frame = median(figures[m][0]);
        const double fresh = median(figures[m][1]);
        const double kept = median(figures[m][2]);
        std::printf("| %s | %.4f s | %.4f s | %.4f s | %.3f | %.3f |\n", names[m], frame, fresh,
                    kept, fresh / frame, kept / frame);
    }
    std::fflush(stdout);
}

struct Errors {
    double rmse = 0.0;
    double relative_mse = 0.0;
    double mean = 0.0;
    void add(const Image& image, const Image& reference, int n) {
        const ImageError e = image_error(image, reference);
        rmse += e.rmse / n;
        relative_mse += e.relative_mse / n;
        mean += mean_luminance(image) / n;
    }
};

void errors(const Scene& scene, const Options& o, const Image& reference) {
    Errors filtered, raw, compare;
    const std::size_t pixels = reference.pixels.size();
    std::vector<glm::dvec3> sum(pixels, glm::dvec3(0.0));
    double squared_error = 0.0;  // of the filtered images, summed over seeds
    for (int seed = 1; seed <= o.seeds; ++seed) {
        const std::unique_ptr<Renderer> r = render(scene, static_cast<std::uint64_t>(seed), o.spp);
        const std::vector<kernel::FilterGuide> guides =
            filter_guides(render_guides(r->packed(), r->camera_record()));
        const Image f = filter_image(r->accumulator(), o.width, o.height, guides, o.passes);
        filtered.add(f, reference, o.seeds);
        raw.add(r->image(), reference, o.seeds);
        for (std::size_t i = 0; i < pixels; ++i) {
            const glm::dvec3 d = glm::dvec3(f.pixels[i]) - glm::dvec3(reference.pixels[i]);
            sum[i] += glm::dvec3(f.pixels[i]);
            squared_error += glm::dot(d, d) / 3.0;
        }
        compare.add(render(scene, static_cast<std::uint64_t>(seed), o.compare_spp)->image(),
                    reference, o.seeds);
    }
    std::printf("\nagainst %s, mean over %d seed(s); reference mean %.4f\n\n",
                o.reference_path.c_str(), o.seeds, mean_luminance(reference));
    std::printf("| image | RMSE | relative MSE | mean |\n| --- | ---: | ---: | ---: |\n");
    std::printf("| %d spp, filtered | %.4f | %.5f | %.4f |\n", o.spp, filtered.rmse,
                filtered.relative_mse, filtered.mean);
    std::printf("| %d spp, raw | %.4f | %.5f | %.4f |\n", o.spp, raw.rmse, raw.relative_mse,
                raw.mean);
    std::printf("| %d spp, raw | %.4f | %.5f | %.4f |\n", o.compare_spp, compare.rmse,
                compare.relative_mse, compare.mean);
    std::printf("\nfiltered / raw %d spp RMSE: %.3f; filtered mean / raw %d spp mean: %.4f\n",
                o.compare_spp, filtered.rmse / compare.rmse, o.spp, filtered.mean / raw.mean);
    if (o.seeds >= 2) {
        // Per pixel, the mean over seeds against the reference: its squared
        // error less the variance share it still holds is the bias.
        const double n = o.seeds;
        double mean_error = 0.0;
        for (std::size_t i = 0; i < pixels; ++i) {
            const glm::dvec3 d = sum[i] / n - glm::dvec3(reference.pixels[i]);
            mean_error += glm::dot(d, d) / 3.0;
        }
        const double mse = squared_error / (n * pixels);
        const double variance = (mse - mean_error / pixels) * n / (n - 1.0);
        const double bias2 = mse - variance;
        std::printf("filtered MSE %.6f = squared bias %.6f + variance %.6f\n", mse, bias2,
                    variance);
    }
}

int run(const Options& o) {
    Scene scene = o.scene_path.empty() ? builtin_scene() : load_scene_file(o.scene_path);
    scene.render.width = o.width;
    scene.render.height = o.height;
    // A reference that will not do is refused before anything is timed.
    Image reference;
    if (!o.reference_path.empty()) {
        reference = read_pfm(o.reference_path);
        if (reference.width != o.width || reference.height != o.height) {
            throw std::runtime_error("--reference " + o.reference_path + ": is " +
                                     std::to_string(reference.width) + " x " +
                                     std::to_string(reference.height) + ", the render " +
                                     std::to_string(o.width) + " x " + std::to_string(o.height));
        }
    }
    timing(scene, o);
    if (!o.reference_path.empty()) {
        errors(scene, o, reference);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_filter", [&] {
        Options o;
        trac0r_cli::CommandLine cl("bench_filter", "bench_filter [SCENE.json] [options]",
                                   description, 22);
        cl.positional("SCENE.json", &o.scene_path, "the scene (default: the built-in Cornell box)");
        cl.on_extra([](const std::string& a) {
            throw trac0r_bench::UsageError(a + ": only one scene file");
        });
        cl.size("--size", &o.width, &o.height, 16384,
                "resolution, each in [1, 16384] (default 800 x 600)");
        cl.integer("--rounds", &o.rounds, 1, 10000,
                   "timed frame-and-filter rounds, in [1, 10000] (default 11)");
        cl.integer("--spp", &o.spp, 2, 1L << 16,
                   "samples per pixel of the filtered image, in [2, 65536] (default 4)");
        cl.integer("--passes", &o.passes, 0, 16,
                   "filter passes, in [0, 16] (default the filter's, " +
                       std::to_string(T0_FILTER_PASSES) + ")");
        cl.text("--reference", &o.reference_path,
                "a converged image (.pfm, the same resolution): also print the errors");
        cl.integer("--compare-spp", &o.compare_spp, 1, 1L << 16,
                   "samples per pixel of the raw image the filtered one is held against, in "
                   "[1, 65536] (default 64)");
        cl.integer("--seeds", &o.seeds, 1, 1000,
                   "renders the errors are averaged over, in [1, 1000] (default 1)");
        return cl.parse_or_print(argc, argv) ? run(o) : 0;
    });
}
