// Sampling a triangle by solid angle (trac0r/kernel/spherical_triangle.h):
// the solid angle against closed forms, the samples' distribution by
// chi-square against the solid angles of sub-triangles, and the
// irradiance they estimate against Lambert's formula. Fixed seeds.
#include <catch2/catch.hpp>

#include "test_support.h"

#include "trac0r/kernel/rng.h"
#include "trac0r/kernel/spherical_triangle.h"

#include <cmath>
#include <vector>

using namespace trac0r::kernel;
using trac0r::chi_square;
using trac0r::ChiSquare;

namespace {

struct Seen {
    const char* name;
    float3 p;
    float3 v0;
    float3 v1;
    float3 v2;
};

// Triangles and points that stress the formulas: near and facing (a large
// solid angle), grazing (beside it, close to its plane), far, from behind,
// and a slim obtuse triangle seen from just above its long edge.
std::vector<Seen> cases() {
    const float3 o = make_float3(0.0f, 0.0f, 0.0f);
    const float3 x = make_float3(1.0f, 0.0f, 0.0f);
    const float3 y = make_float3(0.0f, 1.0f, 0.0f);
    return {
        {"near, facing", make_float3(0.2f, 0.2f, 0.08f), o, x, y},
        {"grazing", make_float3(1.1f, 0.5f, 0.03f), o, x, y},
        {"far", make_float3(0.3f, 0.3f, 3.0f), o, x, y},
        {"behind", make_float3(0.2f, 0.3f, -0.4f), o, x, y},
        {"slim, obtuse", make_float3(1.0f, 0.02f, 0.15f), o, make_float3(2.0f, 0.0f, 0.0f),
         make_float3(1.0f, 0.1f, 0.0f)},
        // Close over its centre: 6.07 sr, near the 6.22 sr bound.
        {"nearly a hemisphere", make_float3(1.0f / 3.0f, 1.0f / 3.0f, 0.012f), o, x, y},
    };
}

float3 lerp_point(const Seen& s, float b1, float b2) {
    return s.v0 + (s.v1 - s.v0) * b1 + (s.v2 - s.v0) * b2;
}

// The M^2 sub-triangles of the barycentric grid of M steps: for cell
// (i, j), i + j < M, the one with its right angle at (i, j) (index
// 2 (i M + j)) and, where i + j < M - 1, the one opposite (index + 1).
int sub_triangle(float b1, float b2, int m) {
    const float s = b1 * static_cast<float>(m);
    const float t = b2 * static_cast<float>(m);
    int i = std::min(m - 1, static_cast<int>(s));
    int j = std::min(m - 1 - i, static_cast<int>(t));
    const bool opposite =
        (s - static_cast<float>(i)) + (t - static_cast<float>(j)) > 1.0f && i + j < m - 1;
    return 2 * (i * m + j) + (opposite ? 1 : 0);
}

}  // namespace

TEST_CASE("spherical_triangle: an octant's solid angle is pi/2, and solid angles add up",
          "[kernel][spherical_triangle]") {
    const SphericalTriangle octant =
        spherical_triangle(make_float3(0.0f, 0.0f, 0.0f), make_float3(1.0f, 0.0f, 0.0f),
                           make_float3(0.0f, 2.0f, 0.0f), make_float3(0.0f, 0.0f, 0.5f));
    CHECK(octant.solid_angle == Approx(0.5 * 3.14159265358979).epsilon(1e-6));
    for (const Seen& s : cases()) {
        INFO(s.name);
        // Split at the midpoint of v1 v2: the halves' solid angles add up.
        const float3 mid = (s.v1 + s.v2) * 0.5f;
        const float whole = spherical_triangle(s.p, s.v0, s.v1, s.v2).solid_angle;
        const float halves = spherical_triangle(s.p, s.v0, s.v1, mid).solid_angle +
                             spherical_triangle(s.p, s.v0, mid, s.v2).solid_angle;
        CHECK(whole > 0.0f);
        CHECK(halves == Approx(whole).epsilon(1e-5));
    }
    // In the triangle's plane it covers nothing.
    CHECK(spherical_triangle(make_float3(3.0f, 2.0f, 0.0f), make_float3(0.0f, 0.0f, 0.0f),
                             make_float3(1.0f, 0.0f, 0.0f), make_float3(0.0f, 1.0f, 0.0f))
              .solid_angle == 0.0f);
}

TEST_CASE("sample_spherical_triangle: uniform in solid angle, chi-square over sub-triangles",
          "[kernel][spherical_triangle]") {
    // 64 sub-triangles, each expecting its solid angle's share of 200,000
    // samples; at 1 - 1e-4 (test_support.h's chi_square). A density 5 %
    // off over a quarter of the triangle adds about 125 to the statistic.
    const int m = 8;
    const int samples = 200000;
    for (const Seen& s : cases()) {
        INFO(s.name);
        const SphericalTriangle t = spherical_triangle(s.p, s.v0, s.v1, s.v2);
        std::vector<double> expected(2 * m * m, 0.0);
        double total = 0.0;
        for (int i = 0; i < m; ++i) {
            for (int j = 0; i + j < m; ++j) {
                const float fm = static_cast<float>(m);
                const float3 a = lerp_point(s, i / fm, j / fm);
                const float3 b = lerp_point(s, (i + 1) / fm, j / fm);
                const float3 c = lerp_point(s, i / fm, (j + 1) / fm);
                expected[2 * (i * m + j)] = spherical_triangle(s.p, a, b, c).solid_angle;
                if (i + j < m - 1) {
                    const float3 d = lerp_point(s, (i + 1) / fm, (j + 1) / fm);
                    expected[2 * (i * m + j) + 1] = spherical_triangle(s.p, b, d, c).solid_angle;
                }
            }
        }
        for (double e : expected) {
            total += e;
        }
        CHECK(total == Approx(t.solid_angle).epsilon(1e-4));
        for (double& e : expected) {
            e *= samples / total;
        }
        std::vector<double> observed(expected.size(), 0.0);
        Rng rng;
        rng_seed(&rng, 2024);
        int failed = 0;
        for (int k = 0; k < samples; ++k) {
            const float u1 = rng_float(&rng);
            const float u2 = rng_float(&rng);
            float b1 = -1.0f;
            float b2 = -1.0f;
            if (!sample_spherical_triangle(t, s.p, s.v0, s.v1, s.v2, make_float2(u1, u2), &b1,
                                           &b2)) {
                ++failed;
                continue;
            }
            REQUIRE(b1 >= 0.0f);
            REQUIRE(b2 >= 0.0f);
            REQUIRE(b1 + b2 <= 1.0f + 1e-6f);
            observed[sub_triangle(b1, b2, m)] += 1.0;
        }
        CHECK(failed == 0);
        const ChiSquare chi2 = chi_square(expected, observed);
        CAPTURE(chi2.value, chi2.cells, chi2.critical);
        CHECK(chi2.cells > 40);
        CHECK(chi2.value < chi2.critical);
    }
}

TEST_CASE("sampling by solid angle estimates a triangle lamp's irradiance (Lambert's formula)",
          "[kernel][spherical_triangle]") {
    for (const Seen& s : cases()) {
        INFO(s.name);
        // A receiver facing the triangle's plane (z = 0 in every case), so
        // all of it is above the horizon, where Lambert's formula for a
        // polygon holds: E = 1/2 sum over edges of (angle subtended) (n .
        // unit normal of the plane through p and the edge), radiance 1.
        const float3 n = make_float3(0.0f, 0.0f, s.p.z > 0.0f ? -1.0f : 1.0f);
        const float3 corners[3] = {s.v0, s.v1, s.v2};
        double lambert = 0.0;
        for (int e = 0; e < 3; ++e) {
            const float3 a = normalize(corners[e] - s.p);
            const float3 b = normalize(corners[(e + 1) % 3] - s.p);
            const double angle = std::atan2(static_cast<double>(length(cross(a, b))),
                                            static_cast<double>(dot(a, b)));
            lambert += 0.5 * angle * static_cast<double>(dot(n, normalize(cross(a, b))));
        }
        lambert = std::fabs(lambert);

        // The estimator: cos at the receiver over the density 1 / omega.
        const SphericalTriangle t = spherical_triangle(s.p, s.v0, s.v1, s.v2);
        Rng rng;
        rng_seed(&rng, 77);
        const int samples = 100000;
        double sum = 0.0;
        double sum2 = 0.0;
        for (int k = 0; k < samples; ++k) {
            const float u1 = rng_float(&rng);
            const float u2 = rng_float(&rng);
            float b1 = 0.0f;
            float b2 = 0.0f;
            REQUIRE(
                sample_spherical_triangle(t, s.p, s.v0, s.v1, s.v2, make_float2(u1, u2), &b1, &b2));
            const float3 w = normalize(lerp_point(s, b1, b2) - s.p);
            const double f = std::max(0.0, static_cast<double>(dot(n, w))) * t.solid_angle;
            sum += f;
            sum2 += f * f;
        }
        const double mean = sum / samples;
        const double se = std::sqrt(std::max(0.0, sum2 / samples - mean * mean) / samples);
        CAPTURE(mean, lambert, se);
        // Five standard errors, and the float rounding of the solid angle.
        CHECK(std::fabs(mean - lambert) <= 5.0 * se + 1e-5 * lambert);
    }
}
