// Direction sampling: the orthonormal frame, and the sphere, hemisphere and
// cone samplers' directions, densities and distributions (moments and
// chi-square tests with fixed seeds).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "trac0r/kernel/rng.h"
#include "trac0r/kernel/sampling.h"

using namespace trac0r::kernel;

namespace {

const double pi = 3.14159265358979323846;

// Rounding error of a handful of float operations on numbers of size one is
// a few units of 2^-24 (6e-8); 1e-5 is far above that and far below any
// real mistake in a formula.
const float unit_tolerance = 1e-5f;

double dot_d(float3 a, float3 b) {
    return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y +
           static_cast<double>(a.z) * b.z;
}

float3 random_unit_vector(Rng* rng) {
    const float u1 = rng_float(rng);
    const float u2 = rng_float(rng);
    return sample_uniform_sphere(u1, u2).direction;
}

// Normals that stress the frame: the axes (both signs, where Frisvad's
// original construction divides by zero at -z), directions a hair away from
// them, and a few hundred random ones.
std::vector<float3> test_normals() {
    std::vector<float3> normals = {
        make_float3(0, 0, 1),
        make_float3(0, 0, -1),
        make_float3(1, 0, 0),
        make_float3(-1, 0, 0),
        make_float3(0, 1, 0),
        make_float3(0, -1, 0),
        make_float3(1, 0, -0.0f),
        normalize(make_float3(1e-4f, 0, -1)),
        normalize(make_float3(0, 1e-4f, -1)),
        normalize(make_float3(1e-7f, -1e-7f, -1)),
        normalize(make_float3(1e-4f, 1e-4f, 1)),
        normalize(make_float3(1, 1, 1e-6f)),
        normalize(make_float3(1, 1, -1e-6f)),
    };
    Rng rng;
    rng_seed(&rng, 31337);
    for (int i = 0; i < 500; ++i) {
        normals.push_back(random_unit_vector(&rng));
    }
    return normals;
}

// Pearson's chi-square statistic of observed counts against expected ones.
double chi_square(const std::vector<int>& observed, const std::vector<double>& expected) {
    double chi2 = 0.0;
    for (size_t i = 0; i < observed.size(); ++i) {
        const double d = observed[i] - expected[i];
        chi2 += d * d / expected[i];
    }
    return chi2;
}

// Upper 1e-4 quantiles of the chi-square distribution (computed from the
// regularised incomplete gamma function): a correct sampler fails the test
// with probability 1e-4 for a random seed; with the fixed seeds used here the
// outcome is deterministic. With 200,000 samples in 20 bins (10,000 each,
// standard deviation 100), a density 5% too high over a quarter of the range
// adds about 5 x 500^2 / 10,000 = 125 to the statistic.
const double chi2_1e4_19_dof = 50.80;
const double chi2_1e4_15_dof = 44.26;

}  // namespace

TEST_CASE("frame_from_normal is a right-handed orthonormal frame", "[kernel][sampling]") {
    for (float3 n : test_normals()) {
        INFO("n = " << n.x << ", " << n.y << ", " << n.z);
        const Frame f = frame_from_normal(n);
        CHECK(std::fabs(length(f.tangent) - 1.0f) < unit_tolerance);
        CHECK(std::fabs(length(f.bitangent) - 1.0f) < unit_tolerance);
        CHECK(std::fabs(dot(f.tangent, f.bitangent)) < unit_tolerance);
        CHECK(std::fabs(dot(f.tangent, n)) < unit_tolerance);
        CHECK(std::fabs(dot(f.bitangent, n)) < unit_tolerance);
        CHECK(length(cross(f.tangent, f.bitangent) - n) < unit_tolerance);
        CHECK(f.normal == n);
        // frame_to_world maps local z to n and local x, y to the tangents.
        CHECK(length(frame_to_world(f, make_float3(0, 0, 1)) - n) < unit_tolerance);
        CHECK(length(frame_to_world(f, make_float3(1, 0, 0)) - f.tangent) < unit_tolerance);
    }
}

TEST_CASE("sample_uniform_sphere: unit directions, density 1/(4 pi), right moments",
          "[kernel][sampling]") {
    Rng rng;
    rng_seed(&rng, 1001);
    const int n = 200000;
    double sum_z = 0.0;
    double sum_z2 = 0.0;
    double sum_x = 0.0;
    double sum_y = 0.0;
    int bad = 0;
    for (int i = 0; i < n; ++i) {
        const float u1 = rng_float(&rng);
        const float u2 = rng_float(&rng);
        const DirectionSample s = sample_uniform_sphere(u1, u2);
        bad += !(std::fabs(length(s.direction) - 1.0f) < unit_tolerance);
        bad += !(std::fabs(s.pdf - 1.0 / (4.0 * pi)) < 1e-7);
        sum_x += s.direction.x;
        sum_y += s.direction.y;
        sum_z += s.direction.z;
        sum_z2 += static_cast<double>(s.direction.z) * s.direction.z;
    }
    CHECK(bad == 0);
    // On the uniform sphere each coordinate is uniform on [-1, 1]: mean 0,
    // variance 1/3; z^2 has mean 1/3 and variance 1/5 - 1/9 = 4/45. Five
    // standard errors each.
    const double se_coordinate = std::sqrt(1.0 / 3.0 / n);
    const double se_square = std::sqrt(4.0 / 45.0 / n);
    CHECK(std::fabs(sum_z / n) < 5.0 * se_coordinate);
    CHECK(std::fabs(sum_x / n) < 5.0 * se_coordinate);
    CHECK(std::fabs(sum_y / n) < 5.0 * se_coordinate);
    CHECK(std::fabs(sum_z2 / n - 1.0 / 3.0) < 5.0 * se_square);
}

TEST_CASE("turn_cos_sin is cos and sin of 2 pi u within a few ulps", "[kernel][sampling]") {
    double worst = 0.0;
    std::vector<float> us;
    for (int i = 0; i < (1 << 20); ++i) {
        us.push_back(static_cast<float>(i) / static_cast<float>(1 << 20));
    }
    // Around each quarter and eighth turn (where the reduction switches
    // quadrant or reaches pi/4), and the largest uniform below 1.
    for (int k = 0; k <= 8; ++k) {
        const float at = static_cast<float>(k) / 8.0f;
        for (float u : {std::nextafter(at, 0.0f), at, std::nextafter(at, 1.0f)}) {
            if (u >= 0.0f && u < 1.0f) {
                us.push_back(u);
            }
        }
    }
    us.push_back(1.0f - 1.0f / 16777216.0f);
    for (float u : us) {
        const float2_cs r = turn_cos_sin(u);
        const double angle = 2.0 * 3.14159265358979323846 * static_cast<double>(u);
        worst = std::max(worst, std::fabs(r.c - std::cos(angle)));
        worst = std::max(worst, std::fabs(r.s - std::sin(angle)));
    }
    CAPTURE(worst);
    // About 3 ulps of numbers just below 1 (6e-8 each); measured: 1.0e-7.
    CHECK(worst < 2.0e-7);
}

TEST_CASE("the hemisphere is the cone of half-angle pi/2, float for float", "[kernel][sampling]") {
    REQUIRE(cone_sin2(0.5f * T0_PI) == 1.0f);
    const float3 axis = normalize(make_float3(0.3f, -0.5f, 0.8f));
    for (float u1 : {0.0f, 0.25f, 0.7f, 0.999f}) {
        for (float u2 : {0.0f, 0.1f, 0.5f, 0.93f}) {
            const DirectionSample h = sample_cosine_hemisphere(axis, u1, u2);
            const DirectionSample c = cosine_cone_direction(axis, cone_sin2(0.5f * T0_PI), u1, u2);
            REQUIRE(h.direction == c.direction);
            REQUIRE(h.pdf == c.pdf);
            // The renormalised cone differs by the rounding of the length.
            const DirectionSample r =
                sample_cosine_cone_sin2(axis, cone_sin2(0.5f * T0_PI), u1, u2);
            REQUIRE(length(h.direction - r.direction) < 1e-6f);
            REQUIRE(h.pdf == r.pdf);
        }
    }
}

TEST_CASE("cosine_cone_direction is unit length to a few ulps without renormalising",
          "[kernel][sampling]") {
    // Normals anywhere, and near the poles and axes, where the frame's
    // 1 / (1 + |n.z|) is largest or smallest; cones from a hair to the
    // hemisphere.
    Rng rng;
    rng_seed(&rng, 4004);
    double worst = 0.0;
    for (int i = 0; i < 400000; ++i) {
        float3 axis = random_unit_vector(&rng);
        const float e = rng_float(&rng) * 1e-3f;
        if (i % 4 == 1) {
            axis = normalize(make_float3(e, -0.5f * e, -1.0f));
        } else if (i % 4 == 2) {
            axis = normalize(make_float3(-e, e, 1.0f));
        } else if (i % 4 == 3) {
            const float pole = i & 8 ? 1.0f : -1.0f;
            axis = i & 4 ? make_float3(1.0f, 0.0f, 0.0f) : make_float3(0.0f, 0.0f, pole);
        }
        const float sin2 = i & 16 ? 1.0f : cone_sin2(rng_float(&rng) * 0.5f * T0_PI);
        const float u1 = rng_float(&rng);
        const float u2 = rng_float(&rng);
        const float3 cone = cosine_cone_direction(axis, sin2, u1, u2).direction;
        const float3 hemisphere = sample_cosine_hemisphere(axis, u1, u2).direction;
        worst = std::max(worst, std::fabs(std::sqrt(dot_d(cone, cone)) - 1.0));
        worst = std::max(worst, std::fabs(std::sqrt(dot_d(hemisphere, hemisphere)) - 1.0));
    }
    CAPTURE(worst);
    // Measured: 2.4e-7 (4 ulps of 1, 2^-24 each); normalize itself leaves
    // 1 or 2.
    CHECK(worst < 8.0 * 5.9604645e-8);
}

TEST_CASE("sample_cosine_hemisphere: inside the hemisphere, pdf cos/pi, E[cos] = 2/3",
          "[kernel][sampling]") {
    Rng rng;
    rng_seed(&rng, 2002);
    const std::vector<float3> normals = {make_float3(0, 0, 1), make_float3(0, 0, -1),
                                         normalize(make_float3(0.3f, -0.8f, 0.2f))};
    for (float3 normal : normals) {
        INFO("normal = " << normal.x << ", " << normal.y << ", " << normal.z);
        const int n = 200000;
        double sum_cos = 0.0;
        int bad = 0;
        for (int i = 0; i < n; ++i) {
            const float u1 = rng_float(&rng);
            const float u2 = rng_float(&rng);
            const DirectionSample s = sample_cosine_hemisphere(normal, u1, u2);
            const double cos_theta = dot_d(s.direction, normal);
            bad += !(std::fabs(length(s.direction) - 1.0f) < unit_tolerance);
            bad += !(cos_theta >= 0.0);
            // pdf = cos/pi, to float accuracy of cos (the tolerance above).
            bad += !(std::fabs(s.pdf - cos_theta / pi) < unit_tolerance);
            sum_cos += cos_theta;
        }
        CHECK(bad == 0);
        // cos(theta) under the cosine density: mean 2/3, E[cos^2] = 1/2,
        // variance 1/2 - 4/9 = 1/18. Five standard errors.
        CHECK(std::fabs(sum_cos / n - 2.0 / 3.0) < 5.0 * std::sqrt(1.0 / 18.0 / n));
    }
}

TEST_CASE("sample_cosine_cone_sin2: inside the cone, right pdf and moments, chi-square",
          "[kernel][sampling]") {
    Rng rng;
    rng_seed(&rng, 3003);
    const float angles[] = {0.05f, 0.4f, 1.0f, 1.5707964f};
    for (float cone_angle : angles) {
        const float3 axis = random_unit_vector(&rng);
        INFO("cone angle " << cone_angle << ", axis " << axis.x << ", " << axis.y << ", "
                           << axis.z);
        const double sin_a = std::sin(static_cast<double>(cone_angle));
        const double cos_a = std::cos(static_cast<double>(cone_angle));
        const double sin2_a = sin_a * sin_a;
        const int n = 200000;
        const int bins = 20;
        std::vector<int> cos2_counts(bins, 0);
        std::vector<int> azimuth_counts(16, 0);
        const Frame frame = frame_from_normal(axis);
        double sum_cos = 0.0;
        int bad = 0;
        for (int i = 0; i < n; ++i) {
            const float u1 = rng_float(&rng);
            const float u2 = rng_float(&rng);
            const DirectionSample s = sample_cosine_cone_sin2(axis, cone_sin2(cone_angle), u1, u2);
            const double cos_theta = dot_d(s.direction, axis);
            bad += !(std::fabs(length(s.direction) - 1.0f) < unit_tolerance);
            // Inside the cone, allowing float rounding of the direction.
            bad += !(cos_theta >= cos_a - unit_tolerance);
            // pdf = cos / (pi sin^2 a). The cosine measured here carries the
            // world direction's rounding (~1e-7 absolute), so the tolerance
            // is relative to the largest density, 1 / (pi sin^2 a).
            const double pdf = cos_theta / (pi * sin2_a);
            bad += !(std::fabs(s.pdf - pdf) < unit_tolerance / (pi * sin2_a));
            sum_cos += cos_theta;
            // cos^2(theta) = 1 - u1 sin^2(a) is uniform on [cos^2 a, 1].
            const double t = (cos_theta * cos_theta - cos_a * cos_a) / sin2_a;
            cos2_counts[std::min(bins - 1, std::max(0, static_cast<int>(t * bins)))]++;
            // The azimuth around the axis is uniform.
            const double phi =
                std::atan2(dot_d(s.direction, frame.bitangent), dot_d(s.direction, frame.tangent));
            const int k = static_cast<int>((phi + pi) / (2.0 * pi) * 16.0);
            azimuth_counts[std::min(15, std::max(0, k))]++;
        }
        CHECK(bad == 0);
        // E[cos] = (2/3)(1 - cos^3 a)/sin^2 a; E[cos^2] = (1 + cos^2 a)/2.
        // Five standard errors of the sample mean.
        const double mean_cos = (2.0 / 3.0) * (1.0 - cos_a * cos_a * cos_a) / sin2_a;
        const double mean_cos2 = 0.5 * (1.0 + cos_a * cos_a);
        const double se = std::sqrt((mean_cos2 - mean_cos * mean_cos) / n);
        CHECK(std::fabs(sum_cos / n - mean_cos) < 5.0 * se);
        // cos^2 uniform on [cos^2 a, 1]: 20 equal bins, 19 degrees of freedom.
        const std::vector<double> expected(bins, static_cast<double>(n) / bins);
        CHECK(chi_square(cos2_counts, expected) < chi2_1e4_19_dof);
        const std::vector<double> expected_azimuth(16, static_cast<double>(n) / 16);
        CHECK(chi_square(azimuth_counts, expected_azimuth) < chi2_1e4_15_dof);
    }
}

TEST_CASE("sample_cosine_cone_sin2 of zero width is the axis with a delta pdf",
          "[kernel][sampling]") {
    const float3 axis = normalize(make_float3(0.2f, 0.3f, -0.9f));
    const DirectionSample s = sample_cosine_cone_sin2(axis, cone_sin2(0.0f), 0.7f, 0.3f);
    CHECK(length(s.direction - axis) < unit_tolerance);
    CHECK(s.pdf == 0.0f);
}

TEST_CASE("extreme uniforms give finite unit directions and finite densities",
          "[kernel][sampling]") {
    // 1 - 2^-24 is the largest value rng_float returns.
    const float extremes[] = {0.0f, 1.0f - std::ldexp(1.0f, -24)};
    const float3 axes[] = {make_float3(0, 0, 1), make_float3(0, 0, -1),
                           normalize(make_float3(1, -2, 3))};
    const float cone_angles[] = {1e-6f, 0.3f, 1.5707964f};
    auto check = [](DirectionSample s) {
        CHECK(std::isfinite(s.direction.x));
        CHECK(std::isfinite(s.direction.y));
        CHECK(std::isfinite(s.direction.z));
        CHECK(std::fabs(length(s.direction) - 1.0f) < unit_tolerance);
        CHECK(std::isfinite(s.pdf));
        CHECK(s.pdf >= 0.0f);
    };
    for (float u1 : extremes) {
        for (float u2 : extremes) {
            INFO("u1 = " << u1 << ", u2 = " << u2);
            check(sample_uniform_sphere(u1, u2));
            for (float3 axis : axes) {
                const DirectionSample h = sample_cosine_hemisphere(axis, u1, u2);
                check(h);
                CHECK(dot(h.direction, axis) >= 0.0f);
                for (float a : cone_angles) {
                    check(sample_cosine_cone_sin2(axis, cone_sin2(a), u1, u2));
                }
            }
        }
    }
}
