// The converged reference image that the error benchmarks measure against
// (bench_convergence, bench_frame_budget): rendered once on the CPU
// (seed 0x5eed; the runs use others) and kept in a cache folder under a
// name that holds the scene's text hash, the size and the samples.
#ifndef TRAC0R_BENCHMARKS_REFERENCE_CACHE_H
#define TRAC0R_BENCHMARKS_REFERENCE_CACHE_H

#include "trac0r/cpu_backend.h"
#include "trac0r/image_io.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/scene_loader.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace trac0r_bench {

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline bool file_exists(const std::string& path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

// FNV-1a of a scene's text: the cache key of its reference.
inline std::string text_hash(const std::string& text) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) {
        h = (h ^ c) * 1099511628211ull;
    }
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
    return out;
}

// The scene file's name without folder and extension; "builtin" for "".
inline std::string scene_stem(const std::string& scene_path) {
    if (scene_path.empty()) {
        return "builtin";
    }
    const std::size_t slash = scene_path.find_last_of('/');
    const std::string name = slash == std::string::npos ? scene_path : scene_path.substr(slash + 1);
    return name.substr(0, name.rfind('.'));
}

// The cache's name of a reference, without its extension:
// DIR/STEM-HASH-WxH-Nspp, then `suffix`.
inline std::string reference_cache_base(const std::string& dir, const std::string& scene_path,
                                        int width, int height, long spp,
                                        const std::string& suffix = "") {
    const std::string text =
        scene_path.empty() ? std::string(trac0r::builtin_scene_json()) : read_text(scene_path);
    return dir + "/" + scene_stem(scene_path) + "-" + text_hash(text) + "-" +
           std::to_string(width) + "x" + std::to_string(height) + "-" + std::to_string(spp) +
           "spp" + suffix;
}

inline bool reference_is_cached(const std::string& base) {
    return file_exists(base + ".pfm") && file_exists(base + ".relmse");
}

// A reference and its own estimated relative MSE (what its noise adds to
// every error measured against it).
struct Reference {
    trac0r::Image image;
    double own_rel_mse;
};

// The reference cached under `base` (reference_cache_base), or `scene`
// rendered to `spp` samples a pixel on the CPU, with progress on stderr,
// and cached there (its folder must exist).
inline Reference cached_reference(const std::string& base, const trac0r::Scene& scene, long spp) {
    if (reference_is_cached(base)) {
        std::fprintf(stderr, "reference: cached %s.pfm\n", base.c_str());
        return {trac0r::read_pfm(base + ".pfm"), std::stod(read_text(base + ".relmse"))};
    }
    std::fprintf(stderr,
                 "reference: rendering %ld spp on the CPU (seed 0x5eed), cached as %s.pfm\n", spp,
                 base.c_str());
    trac0r::Renderer r(scene, std::make_unique<trac0r::CpuBackend>(), 0x5eed,
                       trac0r::PackOptions());
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    long next_report = std::max(1L, spp / 10);
    while (static_cast<long>(r.frames()) < spp) {
        r.render_frame();
        if (static_cast<long>(r.frames()) >= next_report) {
            std::fprintf(stderr, "  reference %u / %ld spp, %.0f s\n", r.frames(), spp,
                         std::chrono::duration<double>(Clock::now() - start).count());
            next_report += std::max(1L, spp / 10);
        }
    }
    Reference ref{r.image(), trac0r::estimate_relative_mse(r.accumulator(), r.width(), r.height())};
    trac0r::write_pfm(base + ".pfm", ref.image);
    std::ofstream(base + ".relmse") << ref.own_rel_mse << "\n";
    return ref;
}

}  // namespace trac0r_bench

#endif
