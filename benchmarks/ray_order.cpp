// How much of a ray's time through the BVH depends on the rays around it:
// the same ray sets as bench_backends (benchmarks/ray_cast.h: one primary
// ray per pixel, one diffuse bounce from each primary hit), cast on one
// thread in several orders, and each ray cast twice in a row. What changes
// between the orders is what the branch predictor and the caches have seen
// before a ray; the second of two casts of one ray takes the branches the
// first took, so its time bounds what mispredicted branches cost.
//
//   build/benchmarks/bench_ray_order [SCENE.json] [--size W H] [--passes N]
//
// Prints a Markdown table: the median over N passes (default 7) of a ray's
// thread CPU time, in nanoseconds.
#include "cli.h"
#include "ray_cast.h"

#include "trac0r/scene_loader.h"

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace trac0r;
using namespace trac0r::kernel;

namespace {

const char* const description =
    "Casts the primary and diffuse-bounce rays of SCENE at W x H through its BVH on one "
    "thread, in pixel order, shuffled, sorted by direction octant (within runs of 64 rays, as "
    "a tile's paths, and over the whole set), and each ray twice in a row; prints a ray's "
    "time, the median of N passes. A set of fewer than 4096 rays is too short a pass to time "
    "on one thread: its rows say so.";

// Fewer rays than this make a pass of tens of microseconds, which the
// thread's CPU clock and the machine's interrupts time no better than to
// some tens of per cent (the second-of-two-casts difference came out
// negative at 1 x 1).
const std::size_t min_rays_to_time = 4096;

struct Options {
    std::string scene = "scenes/cornell.json";
    int width = 800;
    int height = 600;
    int passes = 7;
};

// false for --help and --version (printed).
bool parse(int argc, char** argv, Options& o) {
    trac0r_cli::CommandLine cl("bench_ray_order",
                               "bench_ray_order [SCENE.json] [--size W H] [--passes N]",
                               description, 16);
    cl.positional("SCENE.json", &o.scene,
                  "the scene (default scenes/cornell.json, relative to the working directory)");
    cl.on_extra([](const std::string& a) {
        throw trac0r_bench::UsageError("'" + a +
                                       "': only one scene file may be given (see --help)");
    });
    cl.size("--size", &o.width, &o.height, 16384,
            "resolution (default 800 x 600; at least 4096 pixels, e.g. 128 x 128, each side at "
            "most 16384)");
    cl.integer("--passes", &o.passes, 1, 1000, "timed passes, in [1, 1000] (default 7)");
    if (!cl.parse_or_print(argc, argv)) {
        return false;
    }
    const long pixels = static_cast<long>(o.width) * o.height;
    if (pixels < static_cast<long>(min_rays_to_time)) {
        throw trac0r_bench::UsageError(
            "--size " + std::to_string(o.width) + " " + std::to_string(o.height) + ": " +
            std::to_string(pixels) + " pixel" + (pixels == 1 ? "" : "s") + ", expected at least " +
            std::to_string(min_rays_to_time) +
            " (e.g. 128 x 128): fewer rays are too short a pass to time");
    }
    return true;
}

int octant(const Ray& r) {
    return (r.direction.x < 0.0f ? 1 : 0) | (r.direction.y < 0.0f ? 2 : 0) |
           (r.direction.z < 0.0f ? 4 : 0);
}

void sort_by_octant(std::vector<Ray>::iterator begin, std::vector<Ray>::iterator end) {
    std::stable_sort(begin, end, [](const Ray& a, const Ray& b) { return octant(a) < octant(b); });
}

struct Cast {
    double seconds_per_ray;
    long checksum;  // sum of the triangles hit (-1 a miss): the same in every order
};

// The median over passes of one pass's thread CPU time per ray, each ray
// cast `repeats` times in a row.
Cast cast(const SceneView& scene, const std::vector<Ray>& rays, int passes, int repeats) {
    const trac0r::DenormalsAreZero denormals;  // as the CPU backend renders
    std::vector<double> seconds;
    long checksum = 0;
    for (int pass = 0; pass <= passes; ++pass) {  // pass 0: warm-up
        long sum = 0;
        const double start = trac0r_bench::thread_cpu_seconds();
        for (const Ray& ray : rays) {
            for (int r = 0; r < repeats; ++r) {
                sum += intersect_scene(&scene, &ray).triangle;
            }
        }
        const double elapsed = trac0r_bench::thread_cpu_seconds() - start;
        if (pass > 0) {
            seconds.push_back(elapsed / static_cast<double>(rays.size()));
        }
        checksum = sum / repeats;
    }
    return Cast{trac0r_bench::median(seconds), checksum};
}

void report(const char* set, const SceneView& scene, const std::vector<Ray>& pixel_order,
            int passes) {
    if (pixel_order.size() < min_rays_to_time) {
        std::printf("| %s | (%zu rays: too few to time, under %zu) | | |\n", set,
                    pixel_order.size(), min_rays_to_time);
        return;
    }
    std::vector<Ray> shuffled = pixel_order;
    std::mt19937 engine(1);
    std::shuffle(shuffled.begin(), shuffled.end(), engine);
    std::vector<Ray> tiles = pixel_order;
    for (std::size_t i = 0; i < tiles.size(); i += 64) {
        sort_by_octant(tiles.begin() + static_cast<long>(i),
                       tiles.begin() + static_cast<long>(std::min(tiles.size(), i + 64)));
    }
    std::vector<Ray> sorted = pixel_order;
    sort_by_octant(sorted.begin(), sorted.end());

    const Cast base = cast(scene, pixel_order, passes, 1);
    auto row = [&](const char* order, const Cast& c) {
        if (c.checksum != base.checksum) {
            throw std::runtime_error(std::string(set) + ", " + order +
                                     ": other hits than in pixel order");
        }
        if (!(c.seconds_per_ray > 0.0)) {
            // Only the difference of two timings can be: noise larger than it.
            std::printf("| %s | %s | (under the timing noise) | |\n", set, order);
            return;
        }
        std::printf("| %s | %s | %.1f | %.3f |\n", set, order, 1e9 * c.seconds_per_ray,
                    c.seconds_per_ray / base.seconds_per_ray);
    };
    row("pixel order", base);
    row("shuffled", cast(scene, shuffled, passes, 1));
    row("by octant, within runs of 64", cast(scene, tiles, passes, 1));
    row("by octant, whole set", cast(scene, sorted, passes, 1));
    // Twice in a row: the second cast's time is what the two take less the
    // time of one.
    const Cast twice = cast(scene, pixel_order, passes, 2);
    row("pixel order, the second of two casts of each ray",
        Cast{twice.seconds_per_ray - base.seconds_per_ray, twice.checksum});
}

int run(const Options& o) {
    const Scene scene = load_scene_file(o.scene);
    PackOptions options;
    options.accel = Accel::bvh;
    const PackedScene packed = pack_scene(scene, options);
    if (packed.triangles.empty()) {
        throw std::runtime_error(o.scene +
                                 ": the scene has no triangles (degenerate ones dropped: " +
                                 std::to_string(packed.dropped_degenerate_triangles) +
                                 "): every ray would miss, there is nothing to time");
    }
    const CameraRecord camera = make_camera_record(scene.camera, o.width, o.height);
    const trac0r_bench::RaySets sets = trac0r_bench::make_ray_sets(packed, camera);
    auto rays_of = [](const trac0r_bench::RaySet& set) {
        std::vector<Ray> rays;
        rays.reserve(set.size());
        for (std::size_t i = 0; i < set.size(); ++i) {
            rays.push_back(make_ray(xyz(set.origins[i]), xyz(set.directions[i])));
        }
        return rays;
    };
    std::printf(
        "%s, BVH, %d x %d: %zu primary and %zu diffuse-bounce rays; a ray's thread CPU "
        "time on one thread of the CPU backend's kernel, median of %d passes after one "
        "warm-up\n\n",
        o.scene.c_str(), o.width, o.height, sets.primary.size(), sets.bounce.size(), o.passes);
    std::printf("| rays | order | ns a ray | / pixel order |\n| --- | --- | ---: | ---: |\n");
    const SceneView view = packed.view();
    report("primary", view, rays_of(sets.primary), o.passes);
    report("diffuse bounce", view, rays_of(sets.bounce), o.passes);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_ray_order", [&] {
        Options o;
        return parse(argc, argv, o) ? run(o) : 0;
    });
}
