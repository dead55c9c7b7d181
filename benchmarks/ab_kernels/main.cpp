// Two versions of the kernel headers timed side by side in one process:
// frames of version A and version B alternated on one thread (AB, then BA),
// each frame's thread CPU time taken, and the ratio B / A of each pair
// reported as the median and quartiles over the pairs. Each version is
// linked four times, its code 0, 16, 32 and 48 bytes further on, and the
// pairs take the four in turn: where a hot loop falls against the
// processor's 64-byte fetch blocks moved frame times by 2 % where the code
// itself did not change. A slow spell of the
// machine then slows both frames of a pair, and not one build's runs, so
// the ratio resolves differences of a few tenths of a per cent
// (docs/performance.md, "Measuring side by side") where alternated runs
// of two builds resolve a few per cent. Built and run by
// benchmarks/ab_kernels.sh, which compiles variant.cpp once for each
// version.
#include "../cli.h"
#include "../timing.h"
#include "buffers.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/scene_loader.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

// Each version compiled at four offsets (variant.cpp, AB_PAD): kernel_a0
// to kernel_a3, kernel_b0 to kernel_b3.
#define AB_VERSION(name)                                                                        \
    extern "C" void name##_frame(const void*, const void*, void*, std::uint64_t, std::uint32_t, \
                                 int);                                                          \
    extern "C" void name##_sizes(std::size_t*);
AB_VERSION(kernel_a0)
AB_VERSION(kernel_a1)
AB_VERSION(kernel_a2)
AB_VERSION(kernel_a3)
AB_VERSION(kernel_b0)
AB_VERSION(kernel_b1)
AB_VERSION(kernel_b2)
AB_VERSION(kernel_b3)

namespace {

typedef void (*FrameFunction)(const void*, const void*, void*, std::uint64_t, std::uint32_t, int);
typedef void (*SizesFunction)(std::size_t*);
const int layouts = 4;
const FrameFunction frames_a[layouts] = {kernel_a0_frame, kernel_a1_frame, kernel_a2_frame,
                                         kernel_a3_frame};
const FrameFunction frames_b[layouts] = {kernel_b0_frame, kernel_b1_frame, kernel_b2_frame,
                                         kernel_b3_frame};
const SizesFunction sizes[2 * layouts] = {kernel_a0_sizes, kernel_a1_sizes, kernel_a2_sizes,
                                          kernel_a3_sizes, kernel_b0_sizes, kernel_b1_sizes,
                                          kernel_b2_sizes, kernel_b3_sizes};

struct Options {
    std::string scene = "scenes/cornell.json";
    trac0r::Accel accel = trac0r::Accel::bvh;
    trac0r::Integrator integrator = trac0r::Integrator::naive;
    trac0r::SamplerKind sampler = trac0r::SamplerKind::random;
    int pairs = 150;
    int width = 200;
    int height = 150;
};

// A library's name as a flag's value, or a UsageError naming the flag.
template <typename Parse>
auto named(const std::string& flag, const std::string& value, Parse parse)
    -> decltype(parse(value)) {
    try {
        return parse(value);
    } catch (const std::invalid_argument& e) {
        throw trac0r_bench::UsageError(flag + ": " + e.what());
    }
}

// The options after A and B (benchmarks/ab_kernels.sh, which has the usage).
// false for --help and --version (printed).
bool parse(int argc, char** argv, Options& o) {
    trac0r_cli::CommandLine cl("ab_kernels", "benchmarks/ab_kernels.sh A B [SCENE.json] [options]",
                               "Times two versions of the kernel headers against each other "
                               "(benchmarks/ab_kernels.sh builds and runs this).",
                               22);
    cl.positional("SCENE.json", &o.scene, "the scene (default scenes/cornell.json)");
    cl.on_extra([](const std::string& a) {
        throw trac0r_bench::UsageError("unexpected argument '" + a +
                                       "' (see benchmarks/ab_kernels.sh --help)");
    });
    cl.value("--accel", "flat|bvh", "acceleration structure (default bvh)",
             [&o](const std::string& v) {
                 o.accel = named("--accel", v, [](const std::string& n) {
                     const trac0r::Accel accel = trac0r::parse_accel(n);
                     if (accel == trac0r::Accel::automatic) {
                         throw std::invalid_argument("expected flat or bvh");
                     }
                     return accel;
                 });
             });
    cl.value("--integrator", "naive|nee", "integrator (default naive)", [&o](const std::string& v) {
        o.integrator = named("--integrator", v,
                             [](const std::string& n) { return trac0r::parse_integrator(n); });
    });
    cl.value("--sampler", "random|sobol", "sampler (default random)", [&o](const std::string& v) {
        o.sampler =
            named("--sampler", v, [](const std::string& n) { return trac0r::parse_sampler(n); });
    });
    cl.integer("--pairs", &o.pairs, 1, 100000, "timed pairs of frames (default 150)");
    cl.size("--size", &o.width, &o.height, 16384, "resolution (default 200 x 150)");
    return cl.parse_or_print(argc, argv);
}

void check_layouts() {
#define AB_NAME(type) #type,
#define AB_SIZE(type) sizeof(trac0r::kernel::type),
    const char* const names[] = {AB_BUFFERS(AB_NAME)};
    const std::size_t here[] = {AB_BUFFERS(AB_SIZE)};
#undef AB_NAME
#undef AB_SIZE
    const std::size_t count = sizeof here / sizeof here[0];
    for (int v = 0; v < 2 * layouts; ++v) {
        std::size_t got[count];
        sizes[v](got);
        for (std::size_t i = 0; i < count; ++i) {
            if (got[i] != here[i]) {
                throw std::runtime_error(std::string(names[i]) + " is " + std::to_string(got[i]) +
                                         " bytes in " + (v < layouts ? "A" : "B") +
                                         ", but this tree packs " + std::to_string(here[i]) +
                                         ": the versions must share the buffer layouts");
            }
        }
    }
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

int run(const Options& o) {
    check_layouts();
    const trac0r::Scene scene = trac0r::load_scene_file(o.scene);
    trac0r::PackOptions pack;
    pack.accel = o.accel;
    pack.integrator = o.integrator;
    pack.sampler = o.sampler;
    const trac0r::PackedScene packed = trac0r::pack_scene(scene, pack);
    const trac0r::kernel::SceneView view = packed.view();
    const trac0r::kernel::CameraRecord camera = trac0r::scaled_camera(
        trac0r::make_camera_record(scene.camera, o.width, o.height), packed.scale);
    const std::size_t pixels =
        static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height);
    std::vector<trac0r::kernel::AccumPixel> accum_a(pixels, trac0r::kernel::AccumPixel{});
    std::vector<trac0r::kernel::AccumPixel> accum_b(pixels, trac0r::kernel::AccumPixel{});
    const trac0r::DenormalsAreZero denormals;  // as the CPU backend renders
    std::vector<double> seconds_a;
    std::vector<double> seconds_b;
    std::vector<double> ratios;
    std::vector<double> layout_ratios[layouts];
    for (int pair = -layouts; pair < o.pairs; ++pair) {  // one warm-up pair a layout
        const int layout = (pair + layouts) % layouts;
        const std::uint32_t frame = static_cast<std::uint32_t>(pair + layouts);
        double a = 0.0;
        double b = 0.0;
        for (int k = 0; k < 2; ++k) {
            const bool run_a = (k == 0) == ((pair + layouts) / layouts % 2 == 0);  // AB, BA, ...
            const double start = trac0r_bench::thread_cpu_seconds();
            if (run_a) {
                frames_a[layout](&view, &camera, accum_a.data(), 1, frame, scene.render.max_depth);
                a = trac0r_bench::thread_cpu_seconds() - start;
            } else {
                frames_b[layout](&view, &camera, accum_b.data(), 1, frame, scene.render.max_depth);
                b = trac0r_bench::thread_cpu_seconds() - start;
            }
        }
        if (pair >= 0) {
            seconds_a.push_back(a);
            seconds_b.push_back(b);
            ratios.push_back(b / a);
            layout_ratios[layout].push_back(b / a);
        }
    }
    const bool same = std::memcmp(accum_a.data(), accum_b.data(),
                                  pixels * sizeof(trac0r::kernel::AccumPixel)) == 0;
    std::string per_layout;
    for (int l = 0; l < layouts; ++l) {
        char text[32];
        std::snprintf(text, sizeof text, "%s%.4f", l == 0 ? "" : ", ",
                      layout_ratios[l].empty() ? 0.0 : trac0r_bench::median(layout_ratios[l]));
        per_layout += text;
    }
    std::printf(
        "%s, %s, %s, %s, %d x %d, %d pairs on one thread: A %.3f ms, B %.3f ms a frame (medians); "
        "B / A %.4f (quartiles %.4f to %.4f; at code offsets 0, 16, 32, 48 bytes: %s); "
        "images %s\n",
        o.scene.c_str(), trac0r::to_string(o.accel), trac0r::to_string(o.integrator),
        trac0r::to_string(o.sampler), o.width, o.height, o.pairs,
        1e3 * trac0r_bench::median(seconds_a), 1e3 * trac0r_bench::median(seconds_b),
        trac0r_bench::median(ratios), quantile(ratios, 0.25), quantile(ratios, 0.75),
        per_layout.c_str(), same ? "the same bit for bit" : "DIFFERENT");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("ab_kernels", [&] {
        Options o;
        return parse(argc, argv, o) ? run(o) : 0;
    });
}
