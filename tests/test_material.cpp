// Materials: Fresnel reflectance spot checks, and the diffuse, glass and
// glossy scatter samples (directions, weights, reflection frequencies).
#include <catch2/catch.hpp>
#include <cmath>

#include "trac0r/kernel/material.h"
#include "trac0r/kernel/rng.h"

using namespace trac0r::kernel;

namespace {

const double pi = 3.14159265358979323846;

// Directions are a few float operations on unit vectors: rounding error is
// a few times 6e-8, so 1e-5 is generous and still catches any wrong formula.
const float direction_tolerance = 1e-5f;

MaterialRecord make_material(t0_u32 type, float3 color, float emittance, float roughness,
                             float ior) {
    return make_material_record(type, color, emittance, roughness, ior);
}

// Unpolarised Fresnel reflectance from the angle form of the equations
// (Born & Wolf), in double: independent of the kernel's cosine form.
double fresnel_reference(double theta_i, double eta) {
    const double sin_t = eta * std::sin(theta_i);
    if (sin_t >= 1.0) {
        return 1.0;
    }
    if (theta_i == 0.0) {
        const double r = (eta - 1.0) / (eta + 1.0);
        return r * r;
    }
    const double theta_t = std::asin(sin_t);
    const double rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
    return 0.5 * (rs * rs + rp * rp);
}

// A unit direction arriving at angle theta from the normal +z, travelling
// downwards (towards -z) in the xz plane.
float3 incoming_at(double theta) {
    return make_float3(static_cast<float>(std::sin(theta)), 0.0f,
                       static_cast<float>(-std::cos(theta)));
}

bool finite3(float3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool same_direction(float3 a, float3 b) { return length(a - b) < direction_tolerance; }

}  // namespace

TEST_CASE("fresnel_dielectric: spot checks", "[kernel][material]") {
    SECTION("normal incidence is ((n1 - n2) / (n1 + n2))^2, from either side") {
        // 1e-6: float rounding of a handful of operations on values near 1.
        CHECK(fresnel_dielectric(1.0f, 1.0f / 1.5f) == Approx(0.04).margin(1e-6));
        CHECK(fresnel_dielectric(1.0f, 1.5f) == Approx(0.04).margin(1e-6));
        CHECK(fresnel_dielectric(1.0f, 1.0f / 3.0f) == Approx(0.25).margin(1e-6));
        CHECK(fresnel_dielectric(1.0f, 3.0f) == Approx(0.25).margin(1e-6));
    }
    SECTION("matches the angle form of the Fresnel equations") {
        const double etas[] = {1.0 / 1.5, 1.5, 1.0 / 3.0, 1.0 / 1.33};
        for (double eta : etas) {
            for (int degrees = 0; degrees < 90; degrees += 5) {
                const double theta = degrees * pi / 180.0;
                INFO("eta " << eta << ", theta " << degrees << " degrees");
                // 1e-5 absolute: float cos/sqrt error near 1 is ~1e-7 and the
                // reflectance is a smooth function of them away from the
                // critical angle (none of these angles is within 1 degree).
                CHECK(fresnel_dielectric(static_cast<float>(std::cos(theta)),
                                         static_cast<float>(eta)) ==
                      Approx(fresnel_reference(theta, eta)).margin(1e-5));
            }
        }
    }
    SECTION("grazing incidence reflects everything") {
        CHECK(fresnel_dielectric(0.0f, 1.0f / 1.5f) == 1.0f);
        CHECK(fresnel_dielectric(0.0f, 1.0f / 3.0f) == 1.0f);
        CHECK(fresnel_dielectric(0.0f, 1.5f) == 1.0f);
        // ...and approaches it continuously: 1 - F grows linearly with
        // cos_i (slope ~5.8 for eta = 1/1.5), so at cos 1e-4 F > 0.999.
        CHECK(fresnel_dielectric(1e-4f, 1.0f / 1.5f) > 0.999f);
        CHECK(fresnel_dielectric(1e-4f, 1.0f / 1.5f) < 1.0f);
    }
    SECTION("total internal reflection beyond the critical angle") {
        // Inside glass of ior 1.5 the critical angle is asin(1/1.5) = 41.81
        // degrees.
        const double critical = std::asin(1.0 / 1.5);
        const double beyond[] = {critical + 0.01, 0.8, 1.0, 1.3, 1.5};
        for (double theta : beyond) {
            CHECK(fresnel_dielectric(static_cast<float>(std::cos(theta)), 1.5f) == 1.0f);
        }
        CHECK(fresnel_dielectric(static_cast<float>(std::cos(critical - 0.01)), 1.5f) < 1.0f);
        CHECK(fresnel_dielectric(static_cast<float>(std::cos(critical - 0.01)), 1.5f) > 0.2f);
    }
    SECTION("eta = 1 reflects nothing except at exactly grazing") {
        const float cosines[] = {1.0f, 0.9f, 0.5f, 0.1f, 0.01f, 1e-3f, 1e-4f, 1e-6f, 1e-15f};
        for (float c : cosines) {
            INFO("cos_i " << c);
            // Exactly 0: for eta = 1 the refracted cos^2 is c * c rounded,
            // and IEEE sqrt returns c from it, so cos_t == cos_i. (Computed
            // as 1 - (1 - c^2) it would not be: below c = 2.4e-4 that is 0
            // and the interface reflected totally.)
            CHECK(fresnel_dielectric(c, 1.0f) == 0.0f);
        }
        CHECK(fresnel_dielectric(0.0f, 1.0f) == 1.0f);
    }
    SECTION("finite and in [0, 1] for cos_i 0, 1 and tiny") {
        const float cosines[] = {0.0f, 1.0f, 1e-30f, 1e-38f, 1e-45f, 1e-7f};
        const float etas[] = {1.0f / 1.5f, 1.5f, 1.0f, 1.0f / 3.0f, 3.0f};
        for (float c : cosines) {
            for (float eta : etas) {
                INFO("cos_i " << c << ", eta " << eta);
                const float f = fresnel_dielectric(c, eta);
                CHECK(std::isfinite(f));
                CHECK(f >= 0.0f);
                CHECK(f <= 1.0f);
            }
        }
    }
}

TEST_CASE("reflect_direction mirrors about the normal", "[kernel][material]") {
    const float3 n = make_float3(0, 1, 0);
    const float3 d = normalize(make_float3(1, -1, 0));
    CHECK(same_direction(reflect_direction(d, n), normalize(make_float3(1, 1, 0))));
    // A general case: the tangential part is kept, the normal part flips,
    // and the length is preserved (either sign of the normal works).
    const float3 n2 = normalize(make_float3(0.3f, -0.5f, 0.8f));
    const float3 d2 = normalize(make_float3(-0.7f, 0.2f, -0.4f));
    const float3 r2 = reflect_direction(d2, n2);
    CHECK(std::fabs(length(r2) - 1.0f) < direction_tolerance);
    CHECK(dot(r2, n2) == Approx(-dot(d2, n2)).margin(1e-6));
    CHECK(same_direction(r2 - n2 * dot(r2, n2), d2 - n2 * dot(d2, n2)));
    CHECK(same_direction(reflect_direction(d2, -n2), r2));
}

TEST_CASE("material_emission is colour times emittance", "[kernel][material]") {
    const MaterialRecord lamp =
        make_material(T0_MATERIAL_EMISSIVE, make_float3(1.0f, 0.93f, 0.85f), 15.0f, 0.0f, 1.0f);
    const float3 e = material_emission(&lamp);
    CHECK(e.x == 15.0f);
    CHECK(e.y == Approx(13.95f));
    CHECK(e.z == Approx(12.75f));
}

TEST_CASE("scatter_diffuse: facing hemisphere, weight = colour, cosine pdf", "[kernel][material]") {
    const float3 color = make_float3(0.2f, 0.5f, 0.8f);
    const MaterialRecord m = make_material(T0_MATERIAL_DIFFUSE, color, 0.0f, 0.0f, 1.0f);
    Rng rng;
    rng_seed(&rng, 51);
    const float3 normals[] = {make_float3(0, 0, 1), make_float3(0, 0, -1),
                              normalize(make_float3(-0.4f, 0.9f, 0.1f))};
    for (float3 n : normals) {
        int bad = 0;
        for (int i = 0; i < 20000; ++i) {
            const ScatterSample s = scatter_diffuse(&m, n, rng_float2(&rng));
            const float c = dot(s.direction, n);
            bad += !(c > 0.0f);
            bad += !(std::fabs(length(s.direction) - 1.0f) < direction_tolerance);
            bad += !(s.weight == color);
            bad += !(std::fabs(s.pdf - c / static_cast<float>(pi)) < direction_tolerance);
            bad += s.is_delta != 0;
        }
        CHECK(bad == 0);
    }
}

TEST_CASE("scatter_glass: Fresnel-weighted choice between mirror and refraction",
          "[kernel][material]") {
    const float3 color = make_float3(0.5f, 0.5f, 0.9f);
    const float3 up = make_float3(0, 0, 1);
    Rng rng;
    rng_seed(&rng, 52);

    SECTION("normal incidence reflects with frequency F and refracts straight through") {
        const MaterialRecord glass = make_material(T0_MATERIAL_GLASS, color, 0.0f, 0.0f, 1.5f);
        const float3 down = make_float3(0, 0, -1);
        const int n = 100000;
        int reflected = 0;
        int other = 0;
        for (int i = 0; i < n; ++i) {
            const ScatterSample s = scatter_glass(&glass, down, up, rng_float(&rng));
            other += s.is_delta != 1 || s.pdf != 0.0f;
            if (same_direction(s.direction, up) && s.weight == float3_splat(1.0f)) {
                ++reflected;
            } else if (!(same_direction(s.direction, down) && s.weight == color)) {
                ++other;
            }
        }
        CHECK(other == 0);
        // Binomial(n, F = 0.04): standard deviation sqrt(n F (1 - F)) = 62;
        // five of them (a correct material fails with probability 6e-7).
        const double expected = 0.04 * n;
        CHECK(std::fabs(reflected - expected) < 5.0 * std::sqrt(n * 0.04 * 0.96));
    }
    SECTION("oblique incidence obeys Snell's law and reflects with frequency F") {
        const float ior = 1.5f;
        const MaterialRecord glass = make_material(T0_MATERIAL_GLASS, color, 0.0f, 0.0f, ior);
        const double theta = 60.0 * pi / 180.0;
        const float3 in = incoming_at(theta);
        const double f = fresnel_reference(theta, 1.0 / ior);  // 0.0918
        const int n = 100000;
        int reflected = 0;
        int bad = 0;
        for (int i = 0; i < n; ++i) {
            const ScatterSample s = scatter_glass(&glass, in, up, rng_float(&rng));
            bad += !(std::fabs(length(s.direction) - 1.0f) < direction_tolerance);
            if (s.direction.z > 0.0f) {
                ++reflected;
                bad += !same_direction(s.direction, reflect_direction(in, up));
            } else {
                // Refracted: in the plane of incidence, sin(theta_t) =
                // sin(theta_i) / ior.
                bad += !(std::fabs(s.direction.y) < direction_tolerance);
                bad += !(std::fabs(s.direction.x - std::sin(theta) / ior) < direction_tolerance);
                bad += !(s.weight == color);
            }
        }
        CHECK(bad == 0);
        // Binomial, five standard deviations, as above.
        CHECK(std::fabs(reflected - f * n) < 5.0 * std::sqrt(n * f * (1.0 - f)));
    }
    SECTION("ior 1 passes straight through with weight colour, from either side") {
        const MaterialRecord air = make_material(T0_MATERIAL_GLASS, color, 0.0f, 0.0f, 1.0f);
        // acos(1e-4): a hair from grazing, where index-matched glass used to
        // reflect totally.
        const double angles[] = {0.0, 0.5, 1.2, std::acos(1e-4)};
        for (double theta : angles) {
            const float3 in = incoming_at(theta);
            int bad = 0;
            for (int i = 0; i < 2000; ++i) {
                const ScatterSample from_outside = scatter_glass(&air, in, up, rng_float(&rng));
                bad += !same_direction(from_outside.direction, in);
                bad += !(from_outside.weight == color);
                const ScatterSample from_inside = scatter_glass(&air, in, -up, rng_float(&rng));
                bad += !same_direction(from_inside.direction, in);
                bad += !(from_inside.weight == color);
            }
            CHECK(bad == 0);
        }
    }
    SECTION("from inside beyond the critical angle it always reflects") {
        // Leaving glass of ior 1.5 (the ray travels along the outward normal
        // -z here, so it is inside) at 60 degrees > 41.8.
        const MaterialRecord glass = make_material(T0_MATERIAL_GLASS, color, 0.0f, 0.0f, 1.5f);
        const float3 outward = make_float3(0, 0, -1);
        const float3 in = incoming_at(60.0 * pi / 180.0);
        const float3 mirror = reflect_direction(in, up);
        int bad = 0;
        for (int i = 0; i < 20000; ++i) {
            const ScatterSample s = scatter_glass(&glass, in, outward, rng_float(&rng));
            bad += !same_direction(s.direction, mirror);
            bad += !(s.weight == float3_splat(1.0f));
        }
        CHECK(bad == 0);
        // Below the critical angle some light gets out.
        const float3 shallow = incoming_at(30.0 * pi / 180.0);
        int refracted = 0;
        for (int i = 0; i < 1000; ++i) {
            refracted += scatter_glass(&glass, shallow, outward, rng_float(&rng)).direction.z < 0.0f;
        }
        CHECK(refracted > 900);
    }
}

TEST_CASE("scatter_glossy: a mirror at roughness 0, a cone otherwise", "[kernel][material]") {
    const float3 color = make_float3(0.9f, 0.8f, 0.7f);
    const float3 up = make_float3(0, 0, 1);
    Rng rng;
    rng_seed(&rng, 53);

    SECTION("roughness 0 returns the mirror direction as a delta") {
        const MaterialRecord mirror = make_material(T0_MATERIAL_GLOSSY, color, 0.0f, 0.0f, 1.0f);
        const double angles[] = {0.0, 0.4, 1.0, 1.5};
        for (double theta : angles) {
            const float3 in = incoming_at(theta);
            const ScatterSample s = scatter_glossy(&mirror, in, up, rng_float2(&rng));
            CHECK(same_direction(s.direction, reflect_direction(in, up)));
            CHECK(s.is_delta == 1);
            CHECK(s.pdf == 0.0f);
            CHECK(s.weight == color);
        }
    }
    SECTION("directions stay in the cone of half-angle roughness * pi/2 around the mirror") {
        const float roughness = 0.3f;
        const MaterialRecord metal =
            make_material(T0_MATERIAL_GLOSSY, color, 0.0f, roughness, 1.0f);
        const float3 in = incoming_at(30.0 * pi / 180.0);
        const float3 mirror = reflect_direction(in, up);
        // 30 + 27 degrees: the whole cone is above the surface.
        const float cos_cone = std::cos(roughness * 0.5f * static_cast<float>(pi));
        int bad = 0;
        for (int i = 0; i < 20000; ++i) {
            const ScatterSample s = scatter_glossy(&metal, in, up, rng_float2(&rng));
            bad += !(dot(s.direction, mirror) >= cos_cone - direction_tolerance);
            bad += !(s.direction.z > 0.0f);
            bad += !(s.weight == color);
            bad += !(s.pdf > 0.0f);
            bad += s.is_delta != 0;
        }
        CHECK(bad == 0);
    }
    SECTION("near grazing, cone directions below the surface fail with weight zero") {
        const float roughness = 0.5f;
        const MaterialRecord metal =
            make_material(T0_MATERIAL_GLOSSY, color, 0.0f, roughness, 1.0f);
        const float3 in = incoming_at(80.0 * pi / 180.0);
        const float3 mirror = reflect_direction(in, up);
        const float cos_cone = std::cos(roughness * 0.5f * static_cast<float>(pi));
        int failed = 0;
        int bad = 0;
        for (int i = 0; i < 20000; ++i) {
            const ScatterSample s = scatter_glossy(&metal, in, up, rng_float2(&rng));
            bad += !finite3(s.direction) || !finite3(s.weight) || !std::isfinite(s.pdf);
            if (s.weight == float3_splat(0.0f)) {
                ++failed;
            } else {
                bad += !(s.direction.z > 0.0f);
                bad += !(dot(s.direction, mirror) >= cos_cone - direction_tolerance);
                bad += !(s.weight == color);
            }
        }
        CHECK(bad == 0);
        // The mirror is 10 degrees above the surface and the cone 45 wide, so
        // a sizeable share (but not all) of the cone lies below.
        CHECK(failed > 1000);
        CHECK(failed < 10000);
    }
}

TEST_CASE("scatter_material dispatches on the type and the feature mask", "[kernel][material]") {
    const float3 color = make_float3(0.3f, 0.6f, 0.9f);
    const MaterialRecord diffuse = make_material(T0_MATERIAL_DIFFUSE, color, 0.0f, 0.0f, 1.0f);
    const MaterialRecord lamp = make_material(T0_MATERIAL_EMISSIVE, color, 5.0f, 0.0f, 1.0f);
    const float3 n = make_float3(0, 0, 1);
    const float3 in = incoming_at(0.3);
    SceneView scene = {};
    Rng rng;
    rng_seed(&rng, 54);

    scene.features = T0_FEATURE_DIFFUSE | T0_FEATURE_EMISSIVE;
    CHECK(scatter_material(&scene, &diffuse, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).weight == color);
    // A pure emitter ends the path: a failed sample.
    CHECK(scatter_material(&scene, &lamp, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).weight == float3_splat(0.0f));
    // Glass (ior 1: straight through) and a mirror, each told apart by its
    // direction.
    const MaterialRecord air = make_material(T0_MATERIAL_GLASS, color, 0.0f, 0.0f, 1.0f);
    const MaterialRecord mirror = make_material(T0_MATERIAL_GLOSSY, color, 0.0f, 0.0f, 1.0f);
    scene.features = T0_FEATURE_GLASS | T0_FEATURE_GLOSSY;
    CHECK(same_direction(scatter_material(&scene, &air, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).direction, in));
    CHECK(same_direction(scatter_material(&scene, &mirror, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).direction,
                         reflect_direction(in, n)));
    // A type the mask leaves out is not scattered.
    scene.features = T0_FEATURE_GLASS;
    CHECK(scatter_material(&scene, &diffuse, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).weight == float3_splat(0.0f));
    CHECK(scatter_material(&scene, &mirror, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).weight == float3_splat(0.0f));
    scene.features = T0_FEATURE_DIFFUSE;
    CHECK(scatter_material(&scene, &air, float3_splat(1.0f), make_float2(1.0f, 1.0f), 1, in, n, n, rng_float2(&rng), 0.0f).weight == float3_splat(0.0f));
}
