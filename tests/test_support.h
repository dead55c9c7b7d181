// What several test files need: the repository's scenes at a test's size,
// a warning-free OpenCL build of a packed scene, block statistics, and a
// temporary directory.
#ifndef TRAC0R_TESTS_TEST_SUPPORT_H
#define TRAC0R_TESTS_TEST_SUPPORT_H

#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/image_io.h"
#include "trac0r/kernel/types.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "trac0r/shape.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

namespace trac0r {

// PackOptions with the given integrator (and how NEE picks lights).
inline PackOptions with_integrator(Integrator integrator,
                                   LightSampler light_sampler = LightSampler::automatic) {
    PackOptions options;
    options.integrator = integrator;
    options.light_sampler = light_sampler;
    return options;
}

// `frames` frames of `scene` on the CPU backend with the given integrator:
// the accumulator, no sample dropped as non-finite.
inline std::vector<kernel::AccumPixel> render_accumulation(
    const Scene& scene, Integrator integrator, std::uint64_t seed, int frames,
    LightSampler light_sampler = LightSampler::automatic) {
    Renderer r(scene, std::make_unique<CpuBackend>(), seed,
               with_integrator(integrator, light_sampler));
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    REQUIRE(r.stats().samples_dropped == 0);
    return r.accumulator();
}

// A float's bits: equal floats compared bit for bit (0 and -0 apart).
inline std::uint32_t bits_of(float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

// How far apart, relative to the mean, one render's pixel and the same
// frames rendered in parts and merged (accumulator_merge.h) may be: every
// frame's sample is the same bits in both, summed in another order. One
// accumulator's Kahan sum is within 2 units of 2^-24 of the exact sum,
// relative to it (samples are not negative), and so is each part's; the
// merge adds exactly in double and rounds once, and the mean's subtraction
// and division round once each: 8 units bound the difference, and 16 allow
// for the reference's own rounding.
inline double split_render_tolerance() { return 16.0 * std::ldexp(1.0, -24); }

// scenes/NAME from the source tree, rendered at width x height.
inline Scene load_test_scene(const std::string& name, int width, int height) {
    Scene scene = load_scene_file(std::string(TRAC0R_SOURCE_DIR) + "/scenes/" + name);
    scene.render.width = width;
    scene.render.height = height;
    return scene;
}

// The Cornell box with an icosphere of 20,480 triangles filling the view:
// at 96 x 72 the camera rays of the tiles near its silhouette meet more
// BVH leaves than a tile keeps (T0_BUNDLE_LEAVES), and traverse the tree.
inline Scene cornell_with_dense_sphere() {
    Scene scene = builtin_scene();
    scene.shapes.push_back(make_icosphere(glm::vec3(0.0f, 0.31f, 0.6f), glm::vec3(0.0f), 0.25f, 5,
                                          scene.shapes[0].material));
    return scene;
}

// Builds packed's OpenCL program on device 0 with -Werror (any warning
// fails the build, whose log the exception carries) and checks that the
// scene's feature mask is among the build options.
inline void require_warning_free_build(const PackedScene& packed) {
    OpenClBackend backend(0);
    setenv("TRAC0R_OPENCL_OPTIONS", "-Werror", 1);
    REQUIRE_NOTHROW(backend.set_scene(packed));
    unsetenv("TRAC0R_OPENCL_OPTIONS");
    CAPTURE(backend.build_options());
    char mask[32];
    std::snprintf(mask, sizeof mask, "-DT0_FEATURES=0x%xu", packed.features);
    REQUIRE(backend.build_options().find(mask) != std::string::npos);
}

// A furnace render (every pixel has the same expectation): the mean over
// all samples is within 5 standard errors of expected, and the render is
// long enough that 5 standard errors are under 5% of it. The spread is the
// within-pixel one, from the accumulator's per-pixel M2.
// scenes/furnace.json's expected image mean: its walls of albedo rho emit
// Le = rho x emittance, so max depth D gives Le (1 - rho^D) / (1 - rho).
inline double furnace_expected_mean(const Scene& scene) {
    const double rho = scene.materials.at(0).color.x;
    const double le = rho * scene.materials.at(0).emittance;
    return le * (1.0 - std::pow(rho, scene.render.max_depth)) / (1.0 - rho);
}

inline void require_furnace_mean(const std::vector<kernel::AccumPixel>& accum, double expected) {
    double sum = 0.0, m2 = 0.0, n = 0.0;
    for (const kernel::AccumPixel& p : accum) {
        sum += static_cast<double>(p.moments.x) * p.moments.z;
        m2 += p.moments.y;
        n += p.moments.z;
    }
    const double mean = sum / n;
    const double se = std::sqrt(m2 / (n - 1.0) / n);
    CAPTURE(mean, expected, se);
    REQUIRE(se < 0.01 * expected);
    REQUIRE(std::fabs(mean - expected) < 5.0 * se);
}

// The luminance mean of a block of pixels and the variance of that mean:
// each pixel's sample variance M2 / (n - 1) over its n samples, divided by
// n, summed over the block's independent pixels and divided by the pixel
// count squared.
struct BlockMean {
    int x, y;
    double mean;
    double variance;
};

inline std::vector<BlockMean> block_means(const std::vector<kernel::AccumPixel>& accum, int width,
                                          int height, int block_width, int block_height) {
    std::vector<BlockMean> blocks;
    for (int by = 0; by + block_height <= height; by += block_height) {
        for (int bx = 0; bx + block_width <= width; bx += block_width) {
            double sum = 0.0, variance = 0.0;
            for (int y = by; y < by + block_height; ++y) {
                for (int x = bx; x < bx + block_width; ++x) {
                    const kernel::AccumPixel& p = accum[static_cast<std::size_t>(y) * width + x];
                    const double n = p.moments.z;
                    sum += p.moments.x;
                    variance += p.moments.y / (n - 1.0) / n;
                }
            }
            const double pixels = static_cast<double>(block_width) * block_height;
            blocks.push_back({bx, by, sum / pixels, variance / (pixels * pixels)});
        }
    }
    return blocks;
}

// Bonferroni: to keep the chance that any of `comparisons` two-sided tests
// of a true null exceeds k standard errors under family_false_alarm, each
// may do so with probability family_false_alarm / comparisons, i.e.
// erfc(k / sqrt 2) = family_false_alarm / comparisons (normal block means:
// each holds thousands of samples). Solved by bisection; erfc falls in k.
inline double bonferroni_k(int comparisons, double family_false_alarm) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 100; ++i) {
        const double k = 0.5 * (lo + hi);
        if (comparisons * std::erfc(k / std::sqrt(2.0)) > family_false_alarm) {
            lo = k;
        } else {
            hi = k;
        }
    }
    return hi;
}

// Two renders of one image, seeds apart, compared per block x block block
// and over the whole image: |a - b| <= k sqrt(se_a^2 + se_b^2), with k
// from bonferroni_k over all these comparisons at a family-wise false
// alarm rate of 1e-3 (k = 4.3 for the 49 comparisons of 4x4 blocks of a
// 32 x 24 image). Returns the whole image's tolerance relative to its
// mean, which the caller requires small, so that the comparison has teeth.
inline double require_same_block_means(const std::vector<kernel::AccumPixel>& accum_a,
                                       const std::vector<kernel::AccumPixel>& accum_b, int width,
                                       int height, int block) {
    std::vector<BlockMean> a = block_means(accum_a, width, height, block, block);
    std::vector<BlockMean> b = block_means(accum_b, width, height, block, block);
    a.push_back(block_means(accum_a, width, height, width, height).at(0));
    b.push_back(block_means(accum_b, width, height, width, height).at(0));
    const double k = bonferroni_k(static_cast<int>(a.size()), 1e-3);
    double worst_z = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double se = std::sqrt(a[i].variance + b[i].variance);
        const double difference = std::fabs(a[i].mean - b[i].mean);
        CAPTURE(a[i].x, a[i].y, a[i].mean, b[i].mean, se, k);
        REQUIRE(difference <= k * se);
        worst_z = std::fmax(worst_z, difference / se);
    }
    const double tolerance = k * std::sqrt(a.back().variance + b.back().variance) / a.back().mean;
    CAPTURE(k, worst_z, tolerance);
    return tolerance;
}

// How many pixels of two renders with the same random numbers (CPU and
// OpenCL) agree to float rounding: the channels' differences summed
// within 1e-3 of one plus the first's channel sum. A path that a last-bit
// difference turns differs outright, so callers require most, not all.
inline int close_pixel_count(const Image& a, const Image& b) {
    int close = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
        close += d.x + d.y + d.z <= 1e-3f * (1.0f + a.pixels[i].x + a.pixels[i].y + a.pixels[i].z);
    }
    return close;
}

// A scene rendered with `options` on the CPU backend and on OpenCL device
// 0, `frames` frames from the same seed, which gives both the same random
// numbers: at least `close_share` of the pixels agree to float rounding (a
// path that takes another branch on a last-bit difference diverges), and
// every 6x6 block's mean is within 5 standard errors of the difference
// (twice one render's variance: an upper bound, as the seed correlates
// them).
inline void require_opencl_agrees_with_cpu(const Scene& scene, const PackOptions& options,
                                           int frames, double close_share) {
    Renderer cpu(scene, std::make_unique<CpuBackend>(), 11, options);
    Renderer gpu(scene, std::make_unique<OpenClBackend>(0), 11, options);
    for (int i = 0; i < frames; ++i) {
        cpu.render_frame();
        gpu.render_frame();
    }
    const Image a = cpu.image();
    const Image b = gpu.image();
    const int close_pixels = close_pixel_count(a, b);
    CAPTURE(close_pixels, a.pixels.size());
    REQUIRE(close_pixels >= static_cast<int>(close_share * a.pixels.size()));
    const std::vector<BlockMean> ca = block_means(cpu.accumulator(), a.width, a.height, 6, 6);
    const std::vector<BlockMean> gb = block_means(gpu.accumulator(), a.width, a.height, 6, 6);
    for (std::size_t i = 0; i < ca.size(); ++i) {
        const double se = std::sqrt(2.0 * ca[i].variance);
        CAPTURE(ca[i].x, ca[i].y, ca[i].mean, gb[i].mean, se);
        REQUIRE(std::fabs(ca[i].mean - gb[i].mean) <= 5.0 * se + 1e-6);
    }
}

// Pearson's chi-square of observed counts against expected ones, the cells
// expecting fewer than 5 pooled into one, and its quantile at 1 - 1e-4
// for cells - 1 degrees of freedom by Wilson and Hilferty's cube-root
// normal approximation (z = 3.719).
struct ChiSquare {
    double value;
    int cells;
    double critical;
};

inline ChiSquare chi_square(const std::vector<double>& expected,
                            const std::vector<double>& observed) {
    ChiSquare c{0.0, 0, 0.0};
    double pooled_expected = 0.0, pooled_observed = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        if (expected[i] < 5.0) {
            pooled_expected += expected[i];
            pooled_observed += observed[i];
            continue;
        }
        c.value += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++c.cells;
    }
    if (pooled_expected >= 5.0) {
        c.value += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) /
                   pooled_expected;
        ++c.cells;
    }
    const double dof = c.cells - 1;
    const double q = 2.0 / (9.0 * dof);
    c.critical = dof * std::pow(1.0 - q + 3.719 * std::sqrt(q), 3.0);
    return c;
}

// `bytes` in base64 (RFC 4648), for data: URIs in test glTF files.
inline std::string base64(const std::string& bytes) {
    static const char* const digits =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
        v |= i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0;
        v |= i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0;
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[v & 63] : '=';
    }
    return out;
}

// The end of a glTF file whose mesh 0 is one triangle, (0, 0, 0),
// (1, 0, 0), (0, 1, 0), its buffer inline: "meshes" to "accessors" and the
// closing brace; a test writes the rest (asset, scenes, nodes, ...) before.
inline std::string gltf_one_triangle_tail() {
    const float values[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::string buffer(reinterpret_cast<const char*>(values), sizeof values);
    return R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}]})";
}

// A directory under /tmp holding files written by a test; removed after.
class TempDir {
  public:
    TempDir() {
        char name[] = "/tmp/trac0r_test_XXXXXX";
        REQUIRE(mkdtemp(name) != nullptr);
        path_ = name;
    }
    ~TempDir() {
        for (const std::string& f : files_) {
            std::remove(f.c_str());
        }
        rmdir(path_.c_str());
    }
    std::string write(const std::string& name, const std::string& text) {
        const std::string file = path_ + "/" + name;
        std::ofstream(file) << text;
        files_.push_back(file);
        return file;
    }
    const std::string& path() const { return path_; }

  private:
    std::string path_;
    std::vector<std::string> files_;
};

}  // namespace trac0r

#endif
