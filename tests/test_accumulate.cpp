// The per-pixel accumulator: a compensated running sum whose mean stays
// exact over very many samples, Welford luminance moments, and the
// counting (not summing) of non-finite samples.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "trac0r/kernel/accumulate.h"
#include "trac0r/kernel/rng.h"

using namespace trac0r::kernel;

namespace {

AccumPixel empty_pixel() {
    AccumPixel px = {};
    return px;
}

// Radiance values spread log-uniformly over 1e-3 .. 1e3 (six decades, as a
// pixel that sometimes sees a lamp), from a fixed seed.
std::vector<float3> varied_samples(int n) {
    Rng rng;
    rng_seed(&rng, 20240611);
    std::vector<float3> samples;
    for (int i = 0; i < n; ++i) {
        float c[3];
        for (float& v : c) {
            v = static_cast<float>(std::pow(10.0, -3.0 + 6.0 * rng_float(&rng)));
        }
        samples.push_back(make_float3(c[0], c[1], c[2]));
    }
    return samples;
}

// Distance in units in the last place between two positive floats.
int ulps_apart(float a, float b) {
    const int d = float_bits(a) - float_bits(b);
    return d < 0 ? -d : d;
}

double relative_error(double value, double reference) {
    return std::fabs(value - reference) / std::fabs(reference);
}

}  // namespace

TEST_CASE("accumulated_mean of a constant is the constant", "[kernel][accumulate]") {
    AccumPixel px = empty_pixel();
    CHECK(accumulated_mean(px) == float3_splat(0.0f));  // nothing yet: black
    const float3 c = make_float3(0.1f, 0.7f, 3.3f);
    for (int i = 0; i < 100000; ++i) {
        accumulate_sample(&px, c);
    }
    const float3 mean = accumulated_mean(px);
    // Within one ULP (today: exactly). A naive float sum of 0.1f is off by
    // 1.4e-4 relative after 100,000 additions (each rounds to the ULP of a
    // sum near 1e4), about 1700 ULPs.
    CHECK(ulps_apart(mean.x, 0.1f) <= 1);
    CHECK(ulps_apart(mean.y, 0.7f) <= 1);
    CHECK(ulps_apart(mean.z, 3.3f) <= 1);
    CHECK(px.moments.z == 100000.0f);
    CHECK(px.moments.w == 0.0f);
    // The luminance moments of a constant: mean = luminance, no variance.
    CHECK(px.moments.x == Approx(luminance(c)).epsilon(1e-6));
    CHECK(std::fabs(px.moments.y) < 1e-6f * luminance(c) * luminance(c) * 100000.0f);
}

TEST_CASE("accumulated_mean of varied samples matches a double reference", "[kernel][accumulate]") {
    const int n = 100000;
    const std::vector<float3> samples = varied_samples(n);
    AccumPixel px = empty_pixel();
    double reference[3] = {0.0, 0.0, 0.0};
    float naive[3] = {0.0f, 0.0f, 0.0f};
    for (const float3& s : samples) {
        accumulate_sample(&px, s);
        for (int k = 0; k < 3; ++k) {
            reference[k] += s[k];
            naive[k] += s[k];
        }
    }
    const float3 mean = accumulated_mean(px);
    for (int k = 0; k < 3; ++k) {
        INFO("channel " << k);
        const double expected = reference[k] / n;
        const double kahan_error = relative_error(mean[k], expected);
        const double naive_error = relative_error(naive[k] / n, expected);
        // Compensated summation is accurate to ~2 float roundings (1.2e-7)
        // regardless of n, plus the final division: 1e-6 is a safe bound.
        CHECK(kahan_error < 1e-6);
        // The naive float sum (about 7e6 at the end, ULP 0.5) loses the low
        // bits of every addition: on this data it is off by ~1e-4 in every
        // channel, a hundred times the bound above. That gap is what the
        // compensation buys, and what this test would lose without it.
        CHECK(naive_error > 1e-5);
        CHECK(naive_error > 100.0 * kahan_error);
    }
}

TEST_CASE("a finite sample whose sum would overflow is dropped and counted, never NaN",
          "[kernel][accumulate]") {
    AccumPixel px = empty_pixel();
    const float big = 2e38f;  // finite; two of them are not
    accumulate_sample(&px, make_float3(big, 1.0f, 1.0f));
    const AccumPixel before = px;
    accumulate_sample(&px, make_float3(big, 1.0f, 1.0f));
    CHECK(px.moments.w == 1.0f);
    CHECK(px.moments.z == 1.0f);
    CHECK(px.sum == before.sum);
    CHECK(px.compensation == before.compensation);
    const float3 mean = accumulated_mean(px);
    CHECK(mean.x == big);
    CHECK(mean.y == 1.0f);
}

TEST_CASE("non-finite samples are counted and dropped", "[kernel][accumulate]") {
    AccumPixel px = empty_pixel();
    accumulate_sample(&px, make_float3(1.0f, 2.0f, 3.0f));
    accumulate_sample(&px, make_float3(0.5f, 0.25f, 0.125f));
    const AccumPixel before = px;

    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float3 bad[] = {make_float3(nan, nan, nan), make_float3(inf, 1.0f, 1.0f),
                          make_float3(1.0f, -inf, 1.0f), make_float3(1.0f, 1.0f, nan)};
    for (const float3& s : bad) {
        accumulate_sample(&px, s);
    }
    CHECK(px.moments.w == 4.0f);
    // Nothing else moved: sum, compensation, mean, M2 and the count.
    CHECK(px.sum == before.sum);
    CHECK(px.compensation == before.compensation);
    CHECK(px.moments.x == before.moments.x);
    CHECK(px.moments.y == before.moments.y);
    CHECK(px.moments.z == 2.0f);
    const float3 mean = accumulated_mean(px);
    CHECK(mean.x == 0.75f);
    CHECK(mean.y == 1.125f);
    CHECK(mean.z == 1.5625f);
    // A pixel that only ever saw non-finite samples stays black.
    AccumPixel only_bad = empty_pixel();
    accumulate_sample(&only_bad, make_float3(nan, 0.0f, 0.0f));
    CHECK(accumulated_mean(only_bad) == float3_splat(0.0f));
    CHECK(only_bad.moments.w == 1.0f);
}

TEST_CASE("Welford luminance moments match a double reference", "[kernel][accumulate]") {
    SECTION("a short sequence, where the n / (n - 1) details show") {
        const float values[] = {1.0f, 2.0f, 4.0f, 8.0f};
        AccumPixel px = empty_pixel();
        double sum = 0.0;
        for (float v : values) {
            accumulate_sample(&px, float3_splat(v));
            sum += luminance(float3_splat(v));
        }
        const double mean = sum / 4.0;
        double m2 = 0.0;
        for (float v : values) {
            const double d = luminance(float3_splat(v)) - mean;
            m2 += d * d;
        }
        // Four float operations on numbers below 10: 1e-6 relative.
        CHECK(px.moments.x == Approx(mean).epsilon(1e-6));
        CHECK(px.moments.y == Approx(m2).epsilon(1e-6));
        CHECK(px.moments.z == 4.0f);
    }
    SECTION("100,000 varied samples") {
        const int n = 100000;
        const std::vector<float3> samples = varied_samples(n);
        AccumPixel px = empty_pixel();
        double sum = 0.0;
        for (const float3& s : samples) {
            accumulate_sample(&px, s);
            sum += luminance(s);  // the kernel's float luminance, summed in double
        }
        const double mean = sum / n;
        double m2 = 0.0;
        for (const float3& s : samples) {
            const double d = luminance(s) - mean;
            m2 += d * d;
        }
        const double variance = m2 / (n - 1);
        const double kernel_variance = static_cast<double>(px.moments.y) / (px.moments.z - 1.0);
        // The mean's float updates err like a random walk of n roundings of
        // relative size 6e-8 (~2e-5 after 1e5 steps; 6e-7 measured): 1e-4.
        // M2 is a plain float running sum of positive terms, so it errs like
        // the naive sum above (~1e-4 on this data; 4e-5 measured): 1e-3.
        // A wrong update formula is caught by the short sequence above.
        CHECK(relative_error(px.moments.x, mean) < 1e-4);
        CHECK(relative_error(kernel_variance, variance) < 1e-3);
    }
}
