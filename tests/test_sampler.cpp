// The samplers (issue 30, trac0r/kernel/sampler.h): the Sobol draws are
// stratified, exactly, at any power-of-two count of frames; they are not
// correlated across dimensions or pixels; a sample is a pure function of
// (seed, pixel, frame, dimension); and renders made with either sampler
// converge to the same image.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/sampler.h"
#include "trac0r/renderer.h"
#include "test_support.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

using namespace trac0r;

namespace {

const float largest_uniform = 1.0f - 1.0f / 16777216.0f;  // 1 - 2^-24

std::vector<glm::vec2> draws_2d(int sobol, std::uint64_t seed, std::uint32_t pixel, int dim,
                                std::uint32_t first_frame, int count) {
    std::vector<glm::vec2> points;
    for (int i = 0; i < count; ++i) {
        kernel::Sampler s;
        kernel::sampler_start(&s, sobol, seed, pixel, first_frame + static_cast<std::uint32_t>(i));
        points.push_back(kernel::sample_2d(&s, dim));
    }
    return points;
}

std::vector<float> draws_1d(int sobol, std::uint64_t seed, std::uint32_t pixel, int dim,
                            std::uint32_t first_frame, int count) {
    std::vector<float> values;
    for (int i = 0; i < count; ++i) {
        kernel::Sampler s;
        kernel::sampler_start(&s, sobol, seed, pixel, first_frame + static_cast<std::uint32_t>(i));
        values.push_back(kernel::sample_1d(&s, dim));
    }
    return values;
}

// Whether 2^k points are a (0,k,2)-net in base 2: every elementary interval
// [a 2^-i, (a+1) 2^-i) x [b 2^-(k-i), (b+1) 2^-(k-i)), i = 0..k, holds
// exactly one of them. Exact: the points' 24 bits are the sampler's.
bool is_net(const std::vector<glm::vec2>& points, int k) {
    const int n = 1 << k;
    if (static_cast<int>(points.size()) != n) {
        return false;
    }
    for (int i = 0; i <= k; ++i) {
        std::vector<int> count(static_cast<std::size_t>(n), 0);
        for (const glm::vec2& p : points) {
            if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f)) {
                return false;
            }
            const int cx = static_cast<int>(p.x * static_cast<float>(1 << i));
            const int cy = static_cast<int>(p.y * static_cast<float>(1 << (k - i)));
            if (++count[static_cast<std::size_t>(cx * (1 << (k - i)) + cy)] > 1) {
                return false;
            }
        }
    }
    return true;
}

// Whether 2^k numbers fall one in each interval [a 2^-k, (a+1) 2^-k).
bool is_stratified(const std::vector<float>& values, int k) {
    const int n = 1 << k;
    std::vector<int> count(static_cast<std::size_t>(n), 0);
    for (float v : values) {
        if (!(v >= 0.0f && v < 1.0f) || ++count[static_cast<std::size_t>(v * n)] > 1) {
            return false;
        }
    }
    return static_cast<int>(values.size()) == n;
}

// The 2-D draws a path makes, and the 1-D ones (glass's choice is a 1-D draw
// of the material dimension).
const int dims_2d[] = {T0_DIM_PIXEL, T0_DIM(0, T0_DIM_LIGHT_POINT), T0_DIM(0, T0_DIM_MATERIAL),
                       T0_DIM(7, T0_DIM_LIGHT_POINT), T0_DIM(31, T0_DIM_MATERIAL)};
const int dims_1d[] = {T0_DIM(0, T0_DIM_LIGHT_PICK), T0_DIM(0, T0_DIM_ROULETTE),
                       T0_DIM(3, T0_DIM_MATERIAL), T0_DIM(12, T0_DIM_ROULETTE)};
// Aligned blocks of 2^k frames: the first, later ones, and one far out.
std::vector<std::uint32_t> block_starts(int k) {
    const std::uint32_t n = 1u << k;
    return {0u, n, 5u * n, (1u << 20) + 3u * n, (1u << 24) - n};
}
const std::uint32_t pixels[] = {0u, 1u, 2u, 799u, 800u, 479999u, 2073599u};

}  // namespace

TEST_CASE("sobol: every 2-D draw of 2^k aligned frames is a (0,k,2)-net", "[sampler]") {
    int nets = 0;
    for (int k : {1, 4, 8, 10}) {
        for (std::uint32_t first : block_starts(k)) {
            for (std::uint32_t pixel : pixels) {
                for (int dim : dims_2d) {
                    CAPTURE(k, first, pixel, dim);
                    REQUIRE(is_net(draws_2d(1, 90210, pixel, dim, first, 1 << k), k));
                    ++nets;
                }
            }
        }
    }
    CHECK(nets == 4 * 5 * 7 * 5);
}

TEST_CASE("sobol: every 1-D draw of 2^k aligned frames has one number per stratum", "[sampler]") {
    for (int k : {1, 5, 12}) {
        for (std::uint32_t first : block_starts(k)) {
            for (std::uint32_t pixel : pixels) {
                for (int dim : dims_1d) {
                    CAPTURE(k, first, pixel, dim);
                    REQUIRE(is_stratified(draws_1d(1, 7, pixel, dim, first, 1 << k), k));
                }
                // Each coordinate of a 2-D draw is so too.
                std::vector<float> x, y;
                for (const glm::vec2& p :
                     draws_2d(1, 7, pixel, T0_DIM(2, T0_DIM_MATERIAL), first, 1 << k)) {
                    x.push_back(p.x);
                    y.push_back(p.y);
                }
                REQUIRE(is_stratified(x, k));
                REQUIRE(is_stratified(y, k));
            }
        }
    }
}

TEST_CASE("random: the thesis' generator's draws are not stratified", "[sampler]") {
    // The tests above have teeth: independent uniforms almost never form a
    // net (16 points filling 16 columns alone: 16! / 16^16 = 1e-6).
    int nets = 0, strata = 0;
    for (std::uint32_t pixel : pixels) {
        for (int dim : dims_2d) {
            nets += is_net(draws_2d(0, 90210, pixel, dim, 0, 16), 4);
        }
        for (int dim : dims_1d) {
            strata += is_stratified(draws_1d(0, 7, pixel, dim, 0, 32), 5);
        }
    }
    CHECK(nets == 0);
    CHECK(strata == 0);
}

TEST_CASE("sobol: draws of other dimensions and pixels are uncorrelated", "[sampler]") {
    // Pearson's correlation of 4096 frames of two draws. Each dimension's
    // frames are shuffled by a nested uniform scramble (so that every
    // power-of-two prefix stays stratified), and two such shuffles of the
    // same 2^k frames differ by a hierarchical permutation: the draws'
    // leading digits agree or differ together in groups of frames, which
    // makes the correlation's spread about 3 times that of independent
    // numbers' (1 / sqrt(4096) = 0.016): 0.05. The bound is 5 of those;
    // a copy, a mirror or a half shift of one draw by another is |r| >= 0.5.
    const int n = 4096;
    const double bound = 0.25;
    struct Pair {
        std::uint32_t pixel_a;
        int dim_a;
        int coordinate_a;
        std::uint32_t pixel_b;
        int dim_b;
        int coordinate_b;
    };
    const Pair pairs[] = {
        {5, T0_DIM_PIXEL, 0, 5, T0_DIM_PIXEL, 1},
        {5, T0_DIM_PIXEL, 0, 5, T0_DIM(0, T0_DIM_LIGHT_POINT), 0},
        {5, T0_DIM_PIXEL, 1, 5, T0_DIM(0, T0_DIM_MATERIAL), 1},
        {5, T0_DIM(0, T0_DIM_LIGHT_POINT), 0, 5, T0_DIM(0, T0_DIM_MATERIAL), 0},
        {5, T0_DIM(0, T0_DIM_LIGHT_PICK), 0, 5, T0_DIM(0, T0_DIM_LIGHT_POINT), 0},
        {5, T0_DIM(0, T0_DIM_MATERIAL), 0, 5, T0_DIM(1, T0_DIM_MATERIAL), 0},
        {5, T0_DIM(0, T0_DIM_ROULETTE), 0, 5, T0_DIM(1, T0_DIM_ROULETTE), 0},
        {5, T0_DIM_PIXEL, 0, 6, T0_DIM_PIXEL, 0},    // neighbours
        {5, T0_DIM_PIXEL, 1, 805, T0_DIM_PIXEL, 1},  // the pixel below
        {5, T0_DIM(0, T0_DIM_MATERIAL), 0, 6, T0_DIM(0, T0_DIM_MATERIAL), 0},
    };
    auto coordinate = [&](std::uint32_t pixel, int dim, int c) {
        std::vector<double> v;
        for (const glm::vec2& p : draws_2d(1, 1, pixel, dim, 0, n)) {
            v.push_back(c == 0 ? p.x : p.y);
        }
        return v;
    };
    auto correlation = [&](const std::vector<double>& a, const std::vector<double>& b) {
        double ma = 0.0, mb = 0.0;
        for (int i = 0; i < n; ++i) {
            ma += a[i] / n;
            mb += b[i] / n;
        }
        double sab = 0.0, saa = 0.0, sbb = 0.0;
        for (int i = 0; i < n; ++i) {
            sab += (a[i] - ma) * (b[i] - mb);
            saa += (a[i] - ma) * (a[i] - ma);
            sbb += (b[i] - mb) * (b[i] - mb);
        }
        return sab / std::sqrt(saa * sbb);
    };
    double worst = 0.0;
    for (const Pair& p : pairs) {
        const double r = correlation(coordinate(p.pixel_a, p.dim_a, p.coordinate_a),
                                     coordinate(p.pixel_b, p.dim_b, p.coordinate_b));
        CAPTURE(p.pixel_a, p.dim_a, p.coordinate_a, p.pixel_b, p.dim_b, p.coordinate_b, r);
        REQUIRE(std::fabs(r) < bound);
        worst = std::fmax(worst, std::fabs(r));
    }
    // The statistic sees a dependence: a draw against itself shifted by a
    // half (mod 1).
    const std::vector<double> a = coordinate(5, T0_DIM_PIXEL, 0);
    std::vector<double> shifted;
    for (double x : a) {
        shifted.push_back(std::fmod(x + 0.5, 1.0));
    }
    CAPTURE(worst);
    REQUIRE(std::fabs(correlation(a, shifted)) > bound);
}

TEST_CASE("sobol: a draw is a pure function of seed, pixel, frame and dimension", "[sampler]") {
    const int dim = T0_DIM(1, T0_DIM_LIGHT_POINT);
    const std::vector<glm::vec2> a = draws_2d(1, 42, 17, dim, 3, 64);
    REQUIRE(draws_2d(1, 42, 17, dim, 3, 64) == a);
    REQUIRE(draws_2d(1, 43, 17, dim, 3, 64) != a);      // another seed
    REQUIRE(draws_2d(1, 42, 18, dim, 3, 64) != a);      // another pixel
    REQUIRE(draws_2d(1, 42, 17, dim + 1, 3, 64) != a);  // another dimension
    // The order of draws does not matter: a dimension's numbers are the
    // same whether or not others were drawn first (random mode's are not).
    kernel::Sampler s;
    kernel::sampler_start(&s, 1, 42, 17, 3);
    kernel::sample_1d(&s, T0_DIM(0, T0_DIM_ROULETTE));
    kernel::sample_2d(&s, T0_DIM(0, T0_DIM_MATERIAL));
    REQUIRE(kernel::sample_2d(&s, dim) == a[0]);
    kernel::Sampler r;
    kernel::sampler_start(&r, 0, 42, 17, 3);
    const glm::vec2 first = kernel::sample_2d(&r, dim);
    REQUIRE(kernel::sample_2d(&r, dim) != first);
}

TEST_CASE("both samplers draw in [0, 1 - 2^-24], the ends included", "[sampler]") {
    for (int sobol : {0, 1}) {
        float lo = 1.0f, hi = 0.0f;
        for (std::uint32_t pixel = 0; pixel < 64; ++pixel) {
            for (const glm::vec2& p : draws_2d(sobol, 3, pixel, T0_DIM_PIXEL, 0, 256)) {
                REQUIRE(p.x >= 0.0f);
                REQUIRE(p.x <= largest_uniform);
                REQUIRE(p.y >= 0.0f);
                REQUIRE(p.y <= largest_uniform);
                lo = std::fmin(lo, std::fmin(p.x, p.y));
                hi = std::fmax(hi, std::fmax(p.x, p.y));
            }
        }
        CAPTURE(sobol, lo, hi);
        CHECK(lo < 1e-3f);
        CHECK(hi > 1.0f - 1e-3f);
    }
}

namespace {

// The upper tail of Student's t with nu degrees of freedom beyond k, by
// Simpson's rule on its density out to k + 400 (the rest is below 1e-12
// for nu >= 8).
double student_t_tail(double k, double nu) {
    const double c = std::exp(std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu)) /
                     std::sqrt(nu * 3.14159265358979323846);
    auto density = [&](double t) { return c * std::pow(1.0 + t * t / nu, -0.5 * (nu + 1.0)); };
    const int steps = 40000;
    const double h = 400.0 / steps;
    double sum = density(k) + density(k + 400.0);
    for (int i = 1; i < steps; ++i) {
        sum += (i % 2 ? 4.0 : 2.0) * density(k + i * h);
    }
    return sum * h / 3.0;
}

// As bonferroni_k, for differences whose standard error is estimated from
// replicas with nu degrees of freedom.
double bonferroni_t(int comparisons, double family_false_alarm, double nu) {
    double lo = 0.0, hi = 60.0;
    for (int i = 0; i < 60; ++i) {
        const double k = 0.5 * (lo + hi);
        if (comparisons * 2.0 * student_t_tail(k, nu) > family_false_alarm) {
            lo = k;
        } else {
            hi = k;
        }
    }
    return hi;
}

// The mean of independent replicas' estimates and its standard error.
struct ReplicaMean {
    double mean;
    double standard_error;
};

ReplicaMean replica_mean(const std::vector<double>& values) {
    const double n = static_cast<double>(values.size());
    double mean = 0.0;
    for (double v : values) {
        mean += v / n;
    }
    double spread = 0.0;
    for (double v : values) {
        spread += (v - mean) * (v - mean) / (n - 1.0);
    }
    return {mean, std::sqrt(spread / n)};
}

std::vector<kernel::AccumPixel> render(const Scene& scene, Integrator integrator,
                                       SamplerKind sampler, std::uint64_t seed,
                                       std::uint32_t first_frame, int frames) {
    PackOptions options;
    options.integrator = integrator;
    options.sampler = sampler;
    Renderer r(scene, std::make_unique<CpuBackend>(), seed, options);
    r.set_frame_sequence(first_frame, 1);
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    REQUIRE(r.stats().samples_dropped == 0);
    return r.accumulator();
}

// 512 frames of the random sampler against 16 independent Sobol renders
// (seeds, so scrambles, of their own) of 32 frames, half of them from frame
// 2^20 on, compared per 4x4-pixel block and over the whole image. A Sobol
// render's pixel samples are not independent, so its error is not the
// per-pixel spread over sqrt(n): the Sobol block mean's variance is
// estimated from the spread of the 16 replicas' block means (randomised
// quasi-Monte Carlo), the random one's from its pixels' spread as in
// test_nee. |a - b| <= k se with k from Student's t (Welch-Satterthwaite's
// degrees of freedom, at least the replicas' 15), Bonferroni over all the
// comparisons at a family-wise false alarm rate of 1e-3.
void require_same_image(const std::string& name, Integrator integrator) {
    const int width = 32, height = 24, block = 4, replicas = 16, replica_frames = 32;
    const Scene scene = load_test_scene(name, width, height);
    const std::vector<kernel::AccumPixel> random_accum =
        render(scene, integrator, SamplerKind::random, 101, 0, replicas * replica_frames);
    std::vector<BlockMean> random = block_means(random_accum, width, height, block, block);
    random.push_back(block_means(random_accum, width, height, width, height).at(0));

    std::vector<std::vector<double>> replica_means(random.size());
    for (int r = 0; r < replicas; ++r) {
        const std::uint32_t first =
            r < replicas / 2 ? 0u : (1u << 20) + static_cast<std::uint32_t>(r * replica_frames);
        const std::vector<kernel::AccumPixel> accum =
            render(scene, integrator, SamplerKind::sobol, 5000 + r, first, replica_frames);
        std::vector<BlockMean> blocks = block_means(accum, width, height, block, block);
        blocks.push_back(block_means(accum, width, height, width, height).at(0));
        for (std::size_t i = 0; i < blocks.size(); ++i) {
            replica_means[i].push_back(blocks[i].mean);
        }
    }
    const double k = bonferroni_t(static_cast<int>(random.size()), 1e-3, replicas - 1);
    double image_tolerance = 0.0;
    for (std::size_t i = 0; i < random.size(); ++i) {
        const ReplicaMean sobol = replica_mean(replica_means[i]);
        const double mean = sobol.mean;
        const double se =
            std::sqrt(random[i].variance + sobol.standard_error * sobol.standard_error);
        CAPTURE(name, random[i].x, random[i].y, random[i].mean, mean, se, k);
        REQUIRE(std::fabs(random[i].mean - mean) <= k * se);
        image_tolerance = k * se / random[i].mean;  // the last: the whole image
    }
    // Teeth: a bias of a few percent of the image mean (a light or a
    // material sampled from a dimension's wrong half is tens) is outside.
    CAPTURE(name, k, image_tolerance);
    REQUIRE(image_tolerance < 0.05);
}

}  // namespace

TEST_CASE("random and sobol converge to the same image of cornell_diffuse.json",
          "[sampler][render]") {
    require_same_image("cornell_diffuse.json", Integrator::nee);
}

TEST_CASE("random and sobol converge to the same image of cornell.json (glass, glossy)",
          "[sampler][render]") {
    require_same_image("cornell.json", Integrator::nee);
    require_same_image("cornell.json", Integrator::naive);
}

TEST_CASE("sobol: at equal samples, less error than random on cornell_diffuse.json",
          "[sampler][render]") {
    // Against a 4096-frame random render, the RMSE of 64 frames over the
    // image. Stratification is the point of the sampler: it must show.
    const int width = 32, height = 24;
    const Scene scene = load_test_scene("cornell_diffuse.json", width, height);
    const Image reference = accumulated_image(
        render(scene, Integrator::nee, SamplerKind::random, 9, 0, 4096), width, height);
    auto rmse = [&](SamplerKind sampler, std::uint64_t seed) {
        const Image image =
            accumulated_image(render(scene, Integrator::nee, sampler, seed, 0, 64), width, height);
        double sum = 0.0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            const glm::vec3 d = image.pixels[i] - reference.pixels[i];
            sum += glm::dot(d, d) / 3.0;
        }
        return std::sqrt(sum / image.pixels.size());
    };
    double random = 0.0, sobol = 0.0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        random += rmse(SamplerKind::random, seed);
        sobol += rmse(SamplerKind::sobol, seed);
    }
    CAPTURE(random / 4, sobol / 4);
    REQUIRE(sobol < 0.9 * random);
}

TEST_CASE("the furnace stays exact with sobol", "[sampler][furnace]") {
    // scenes/furnace.json: diffuse walls of albedo rho = 0.5 that emit
    // Le = 0.5; its max depth D gives Le (1 - rho^D) / (1 - rho). As in
    // the random sampler's furnace tests, the mean within 5 standard errors;
    // the error from 16 independent replicas' image means.
    Scene scene = load_test_scene("furnace.json", 32, 24);
    const double expected = furnace_expected_mean(scene);
    const double le = scene.materials.at(0).color.x * scene.materials.at(0).emittance;
    for (Integrator integrator : {Integrator::naive, Integrator::nee}) {
        std::vector<double> means;
        for (int r = 0; r < 16; ++r) {
            const std::vector<kernel::AccumPixel> accum =
                render(scene, integrator, SamplerKind::sobol, 300 + r, 0, 8);
            means.push_back(block_means(accum, 32, 24, 32, 24).at(0).mean);
        }
        const ReplicaMean e = replica_mean(means);
        const double mean = e.mean;
        const double se = e.standard_error;
        CAPTURE(static_cast<int>(integrator), mean, expected, se);
        REQUIRE(se < 0.01 * expected);
        REQUIRE(std::fabs(mean - expected) < 5.0 * se);
    }
    // Max depth 1 sees only the emission: exactly, with no noise.
    scene.render.max_depth = 1;
    const std::vector<kernel::AccumPixel> accum =
        render(scene, Integrator::nee, SamplerKind::sobol, 1, 0, 4);
    const BlockMean image = block_means(accum, 32, 24, 32, 24).at(0);
    REQUIRE(image.mean == Approx(le).epsilon(1e-6));
    REQUIRE(image.variance < 1e-12);
}
