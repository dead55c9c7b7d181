// Ray/triangle (watertight, Woop et al.), ray/AABB (slabs) and the ray-origin
// offset that keeps a new ray off the surface it leaves.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "trac0r/kernel/aabb.h"
#include "trac0r/kernel/ray.h"
#include "trac0r/kernel/ray_offset.h"
#include "trac0r/kernel/rng.h"
#include "trac0r/kernel/triangle.h"

using namespace trac0r::kernel;

namespace {

TriangleRecord make_triangle(float3 v0, float3 v1, float3 v2) {
    const float3 n = cross(v1 - v0, v2 - v0);
    return make_triangle_record(v0, v1, v2, normalize(n), length(n), 0u, 0u);
}

struct TriangleHit {
    float t;
    float u;
    float v;
    bool hit() const { return t != T0_NO_HIT; }
};

TriangleHit shoot(const TriangleRecord& tri, float3 origin, float3 direction) {
    TriangleHit h = {T0_NO_HIT, -1.0f, -1.0f};
    h.t = intersect_triangle(&tri, make_ray(origin, normalize(direction)), &h.u, &h.v);
    return h;
}

// The unit right triangle in the z = 0 plane: u runs along x, v along y.
// All the rays below use small binary fractions, so the triangle test's
// arithmetic is exact and edge and vertex hits land exactly on 0 or 1.
TriangleRecord unit_triangle() {
    return make_triangle(make_float3(0, 0, 0), make_float3(1, 0, 0), make_float3(0, 1, 0));
}

TriangleHit shoot_down_at(float x, float y) {
    return shoot(unit_triangle(), make_float3(x, y, 2.0f), make_float3(0, 0, -1));
}

double dot_d(float3 a, float3 b) {
    return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y +
           static_cast<double>(a.z) * b.z;
}

}  // namespace

TEST_CASE("intersect_triangle: interior hits give t, u, v", "[kernel][intersect]") {
    SECTION("straight down") {
        const TriangleHit h = shoot_down_at(0.25f, 0.5f);
        REQUIRE(h.hit());
        CHECK(h.t == 2.0f);
        CHECK(h.u == 0.25f);
        CHECK(h.v == 0.5f);
    }
    SECTION("oblique, from a translated origin") {
        // The ray reaches (0.2, 0.3, 0) after distance 3 along d.
        const float3 d = normalize(make_float3(0.3f, -0.4f, -1.2f));
        const float3 origin = make_float3(0.2f, 0.3f, 0.0f) - d * 3.0f;
        const TriangleHit h = shoot(unit_triangle(), origin, d);
        REQUIRE(h.hit());
        // A few float roundings of numbers of size 3: well below 1e-5.
        CHECK(h.t == Approx(3.0f).epsilon(1e-5));
        CHECK(h.u == Approx(0.2f).epsilon(1e-5));
        CHECK(h.v == Approx(0.3f).epsilon(1e-5));
    }
    SECTION("a general triangle: the hit point is v0 + u e1 + v e2 = origin + t d") {
        const TriangleRecord tri =
            make_triangle(make_float3(1.5f, -2.0f, 0.25f), make_float3(-0.5f, 1.0f, 2.0f),
                          make_float3(3.0f, 2.5f, -1.0f));
        const float3 origin = make_float3(-3.0f, 4.0f, 5.0f);
        const float3 target =
            xyz(tri.v0) + (xyz(tri.v1) - xyz(tri.v0)) * 0.3f + (xyz(tri.v2) - xyz(tri.v0)) * 0.45f;
        const TriangleHit h = shoot(tri, origin, target - origin);
        REQUIRE(h.hit());
        CHECK(h.u == Approx(0.3f).epsilon(1e-5));
        CHECK(h.v == Approx(0.45f).epsilon(1e-5));
        CHECK(h.t == Approx(length(target - origin)).epsilon(1e-5));
    }
}

TEST_CASE("intersect_triangle: misses just outside each edge", "[kernel][intersect]") {
    const float eps = 1.0f / 1024.0f;
    CHECK_FALSE(shoot_down_at(0.5f, -eps).hit());        // below edge v0-v1 (v < 0)
    CHECK_FALSE(shoot_down_at(-eps, 0.5f).hit());        // left of edge v0-v2 (u < 0)
    CHECK_FALSE(shoot_down_at(0.5f + eps, 0.5f).hit());  // beyond edge v1-v2 (u + v > 1)
    CHECK_FALSE(shoot_down_at(1.0f + eps, 0.0f).hit());  // past vertex v1 (u > 1)
    CHECK_FALSE(shoot_down_at(0.0f, 1.0f + eps).hit());  // past vertex v2
    CHECK_FALSE(shoot_down_at(-eps, -eps).hit());        // past vertex v0
    CHECK_FALSE(shoot_down_at(3.0f, 3.0f).hit());        // far away
    // ...and just inside the same edges hits.
    CHECK(shoot_down_at(0.5f, eps).hit());
    CHECK(shoot_down_at(eps, 0.5f).hit());
    CHECK(shoot_down_at(0.5f - eps, 0.5f).hit());
}

TEST_CASE("intersect_triangle: edges and vertices count as inside", "[kernel][intersect]") {
    struct Case {
        float x, y;
    };
    const Case on_boundary[] = {
        {0.5f, 0.0f}, {0.0f, 0.5f}, {0.5f, 0.5f}, {0.25f, 0.75f},  // the three edges
        {0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f},                  // the three vertices
    };
    for (const Case& c : on_boundary) {
        INFO("at (" << c.x << ", " << c.y << ")");
        const TriangleHit h = shoot_down_at(c.x, c.y);
        REQUIRE(h.hit());
        CHECK(h.t == 2.0f);
        CHECK(h.u == c.x);
        CHECK(h.v == c.y);
    }
}

TEST_CASE("intersect_triangle: two-sided, and misses behind or parallel rays",
          "[kernel][intersect]") {
    const TriangleRecord tri = unit_triangle();
    SECTION("the back face is hit with the same t, u, v") {
        const TriangleHit front = shoot(tri, make_float3(0.25f, 0.5f, 2.0f), make_float3(0, 0, -1));
        const TriangleHit back = shoot(tri, make_float3(0.25f, 0.5f, -2.0f), make_float3(0, 0, 1));
        REQUIRE(back.hit());
        CHECK(back.t == front.t);
        CHECK(back.u == front.u);
        CHECK(back.v == front.v);
    }
    SECTION("a triangle behind the ray is missed") {
        CHECK_FALSE(shoot(tri, make_float3(0.25f, 0.5f, 2.0f), make_float3(0, 0, 1)).hit());
        CHECK_FALSE(shoot(tri, make_float3(0.25f, 0.5f, -2.0f), make_float3(0, 0, -1)).hit());
    }
    SECTION("rays parallel to the plane miss, in it or above it") {
        CHECK_FALSE(shoot(tri, make_float3(-1.0f, 0.25f, 0.0f), make_float3(1, 0, 0)).hit());
        CHECK_FALSE(shoot(tri, make_float3(-1.0f, 0.25f, 0.5f), make_float3(1, 0, 0)).hit());
        CHECK_FALSE(shoot(tri, make_float3(-1.0f, -1.0f, 0.0f), make_float3(1, 1, 0)).hit());
        // cos = 1e-8 to the plane: below the 1e-7 parallel threshold.
        CHECK_FALSE(shoot(tri, make_float3(-1.0f, 0.25f, 1e-8f), make_float3(1, 0, -1e-8f)).hit());
    }
    SECTION("a ray at a shallow but real angle hits") {
        // cos = 1e-3 to the plane, crossing it at (0.5, 0.25).
        const float3 d = normalize(make_float3(1.0f, 0.0f, -1e-3f));
        const float3 origin = make_float3(0.5f, 0.25f, 0.0f) - d * 10.0f;
        const TriangleHit h = shoot(tri, origin, d);
        REQUIRE(h.hit());
        CHECK(h.t == Approx(10.0f).epsilon(1e-4));
        // Shallow rays amplify the origin's rounding along the ray; 1e-4
        // (in units of the triangle's size) is still far below a wrong hit.
        CHECK(h.u == Approx(0.5f).margin(1e-4));
        CHECK(h.v == Approx(0.25f).margin(1e-4));
    }
}

TEST_CASE("intersect_triangle is scale invariant", "[kernel][intersect]") {
    // The same triangle and ray scaled by 1e-4, 1 and 1e4: u and v are
    // unchanged and t scales. The parallel test is relative to |e1 x e2|,
    // so a triangle of area 1e-8 is hit as surely as one of area 1e8 (an
    // absolute determinant threshold would miss the small one).
    const float3 v0 = make_float3(0.3f, -0.2f, 1.1f);
    const float3 v1 = make_float3(1.7f, 0.4f, 0.6f);
    const float3 v2 = make_float3(0.1f, 1.3f, 0.2f);
    const float3 origin = make_float3(-0.8f, 0.9f, 3.0f);
    const float3 aim = v0 * 0.35f + v1 * 0.4f + v2 * 0.25f;
    const TriangleHit reference = shoot(make_triangle(v0, v1, v2), origin, aim - origin);
    REQUIRE(reference.hit());
    const float scales[] = {1e-4f, 1e4f, 3.0e-3f, 7.0e2f};
    for (float s : scales) {
        INFO("scale " << s);
        const TriangleHit h =
            shoot(make_triangle(v0 * s, v1 * s, v2 * s), origin * s, (aim - origin) * s);
        REQUIRE(h.hit());
        // Scaling by a non-power of two rounds every input once (relative
        // 6e-8), which moves the results by a few times that: 1e-5 relative
        // leaves a wide margin and still rules out any scale dependence.
        CHECK(h.u == Approx(reference.u).epsilon(1e-5));
        CHECK(h.v == Approx(reference.v).epsilon(1e-5));
        CHECK(h.t / s == Approx(reference.t).epsilon(1e-5));
    }
    SECTION("a shallow ray (cos 1e-3 to the plane) hits at every scale") {
        const TriangleRecord unit = unit_triangle();
        const float3 d = normalize(make_float3(1.0f, 0.0f, -1e-3f));
        for (float s : scales) {
            INFO("scale " << s);
            TriangleRecord tri =
                make_triangle(xyz(unit.v0) * s, xyz(unit.v1) * s, xyz(unit.v2) * s);
            const float3 origin_s = (make_float3(0.5f, 0.25f, 0.0f) - d * 10.0f) * s;
            const TriangleHit h = shoot(tri, origin_s, d);
            REQUIRE(h.hit());
            CHECK(h.u == Approx(0.5f).margin(1e-4));
            CHECK(h.v == Approx(0.25f).margin(1e-4));
        }
    }
}

TEST_CASE("intersect_aabb: slab test with axis-parallel rays", "[kernel][intersect]") {
    const float3 lo = make_float3(1.0f, 2.0f, 3.0f);
    const float3 hi = make_float3(2.0f, 4.0f, 6.0f);
    const float far = 1e30f;
    auto hits = [&](float3 origin, float3 direction, float t_max) {
        return intersect_aabb(lo, hi, make_ray(origin, direction), t_max) != 0;
    };
    const float3 plus_z = make_float3(0, 0, 1);
    const float3 minus_z = make_float3(0, 0, -1);
    const float3 plus_x = make_float3(1, 0, 0);

    SECTION("through the inside") {
        CHECK(hits(make_float3(1.5f, 3.0f, 0.0f), plus_z, far));
        CHECK(hits(make_float3(1.5f, 3.0f, 10.0f), minus_z, far));
        CHECK(hits(make_float3(-5.0f, 3.0f, 4.0f), plus_x, far));
        CHECK(hits(make_float3(1.5f, 3.0f, 0.0f), make_float3(-0.0f, 0.0f, 1.0f), far));
    }
    SECTION("outside the box in a perpendicular axis") {
        CHECK_FALSE(hits(make_float3(2.5f, 3.0f, 0.0f), plus_z, far));
        CHECK_FALSE(hits(make_float3(0.5f, 3.0f, 0.0f), plus_z, far));
        CHECK_FALSE(hits(make_float3(1.5f, 4.5f, 0.0f), plus_z, far));
        CHECK_FALSE(hits(make_float3(-5.0f, 3.0f, 7.0f), plus_x, far));
    }
    SECTION("on a boundary plane counts as inside (conservative)") {
        CHECK(hits(make_float3(1.0f, 3.0f, 0.0f), plus_z, far));
        CHECK(hits(make_float3(2.0f, 3.0f, 0.0f), plus_z, far));
        CHECK(hits(make_float3(1.5f, 4.0f, 10.0f), minus_z, far));
        CHECK(hits(make_float3(2.0f, 4.0f, 0.0f), plus_z, far));  // along an edge
        CHECK(hits(make_float3(-5.0f, 2.0f, 3.0f), plus_x, far));
        // A negative zero component on the min plane, and on the max plane.
        CHECK(hits(make_float3(1.0f, 3.0f, 0.0f), make_float3(-0.0f, 0.0f, 1.0f), far));
        CHECK(hits(make_float3(2.0f, 3.0f, 0.0f), make_float3(-0.0f, 0.0f, 1.0f), far));
        // One float step outside a boundary plane is outside.
        CHECK_FALSE(hits(make_float3(std::nextafter(2.0f, 3.0f), 3.0f, 0.0f), plus_z, far));
        CHECK_FALSE(hits(make_float3(std::nextafter(1.0f, 0.0f), 3.0f, 0.0f), plus_z, far));
    }
    SECTION("starting inside the box") {
        CHECK(hits(make_float3(1.5f, 3.0f, 4.0f), plus_z, far));
        CHECK(hits(make_float3(1.5f, 3.0f, 4.0f), minus_z, far));
        CHECK(hits(make_float3(1.5f, 3.0f, 4.0f), plus_z, 1e-3f));
    }
    SECTION("a box behind the ray is missed") {
        CHECK_FALSE(hits(make_float3(1.5f, 3.0f, 7.0f), plus_z, far));
        CHECK_FALSE(hits(make_float3(1.5f, 3.0f, 0.0f), minus_z, far));
        CHECK_FALSE(hits(make_float3(5.0f, 3.0f, 4.0f), plus_x, far));
    }
    SECTION("t_max before the entry misses, after it hits") {
        // Entry at t = 3 (z from 0 to 3).
        CHECK_FALSE(hits(make_float3(1.5f, 3.0f, 0.0f), plus_z, 2.9f));
        CHECK(hits(make_float3(1.5f, 3.0f, 0.0f), plus_z, 3.0f));
        CHECK(hits(make_float3(1.5f, 3.0f, 0.0f), plus_z, 3.1f));
        CHECK_FALSE(hits(make_float3(1.5f, 3.0f, 10.0f), minus_z, 3.9f));
    }
    SECTION("a diagonal ray: through a corner region, and past the box") {
        const float3 d = normalize(make_float3(1, 1, 1));
        CHECK(hits(make_float3(0.0f, 1.5f, 2.5f), d, far));        // enters at x = 1
        CHECK_FALSE(hits(make_float3(0.0f, 3.5f, 2.0f), d, far));  // y > 4 once x > 1
    }
}

TEST_CASE("offset_ray_origin moves to the requested side, by a small amount",
          "[kernel][intersect]") {
    Rng rng;
    rng_seed(&rng, 4242);
    auto uniform = [&rng](float lo, float hi) { return lo + (hi - lo) * rng_float(&rng); };
    const float magnitudes[] = {1e-4f, 1.0f, 1e5f};
    for (float magnitude : magnitudes) {
        INFO("magnitude " << magnitude);
        int wrong_side = 0;
        int too_far = 0;
        for (int i = 0; i < 20000; ++i) {
            // Coordinates of every size up to the magnitude, some zero.
            float3 p;
            for (int k = 0; k < 3; ++k) {
                const float size = magnitude * std::pow(10.0f, -uniform(0.0f, 4.0f));
                p[k] = (rng_float(&rng) < 0.5f ? -1.0f : 1.0f) * size;
            }
            if (i % 7 == 0) {
                p[i % 3] = 0.0f;
            }
            const float3 n = normalize(make_float3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
            const float3 out = offset_ray_origin(p, n, magnitude);
            const float3 in = offset_ray_origin(p, -n, magnitude);
            wrong_side += !(dot_d(out - p, n) > 0.0);
            wrong_side += !(dot_d(in - p, n) < 0.0);
            // The offset is 8 eps of the magnitude plus one float per
            // coordinate (kernel/ray_offset.h): the whole offset stays under
            // 1e-4 of the magnitude, invisible at the scene's scale.
            too_far += !(length(out - p) < 1e-4f * magnitude);
            too_far += !(length(in - p) < 1e-4f * magnitude);
        }
        CHECK(wrong_side == 0);
        CHECK(too_far == 0);
    }
}

TEST_CASE("offset hit points leave the exact plane of their triangle", "[kernel][intersect]") {
    // Triangles at distance ~magnitude from the origin, hit by random rays:
    // the float hit point has rounding error of a few ULPs of the magnitude,
    // and the offset must beat it. The side is judged against the plane of
    // the float vertices in double precision.
    Rng rng;
    rng_seed(&rng, 777);
    auto uniform = [&rng](float lo, float hi) { return lo + (hi - lo) * rng_float(&rng); };
    const float magnitudes[] = {1e-4f, 1.0f, 1e5f};
    for (float magnitude : magnitudes) {
        INFO("magnitude " << magnitude);
        int hits = 0;
        int wrong_side = 0;
        for (int i = 0; i < 20000; ++i) {
            const float3 centre =
                make_float3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * magnitude;
            const float size = magnitude * std::pow(10.0f, -uniform(0.0f, 3.0f));
            auto vertex = [&]() {
                return centre + make_float3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * size;
            };
            const TriangleRecord tri = make_triangle(vertex(), vertex(), vertex());
            if (!(tri.normal.w > 0.0f)) {
                continue;
            }
            const float3 origin =
                vertex() + make_float3(uniform(-3, 3), uniform(-3, 3), uniform(-3, 3)) * size;
            const float3 v0 = xyz(tri.v0);
            const float3 aim = v0 + (xyz(tri.v1) - v0) * uniform(0.05f, 0.45f) +
                               (xyz(tri.v2) - v0) * uniform(0.05f, 0.45f);
            const Ray ray = make_ray(origin, normalize(aim - origin));
            Hit hit;
            hit.triangle = 0;
            hit.t = intersect_triangle(&tri, ray, &hit.u, &hit.v);
            if (hit.t == T0_NO_HIT) {
                continue;
            }
            ++hits;
            const float3 position = hit_position(&tri, hit);
            const float3 normal = xyz(tri.normal);
            const float m = hit_magnitude(&tri, position);
            const float3 out = offset_ray_origin(position, normal, m);
            const float3 in = offset_ray_origin(position, -normal, m);
            // Signed distance to the plane through the float vertices, in
            // double: (q - v0) . (e1 x e2).
            const double e1[3] = {static_cast<double>(tri.v1.x) - tri.v0.x,
                                  static_cast<double>(tri.v1.y) - tri.v0.y,
                                  static_cast<double>(tri.v1.z) - tri.v0.z};
            const double e2[3] = {static_cast<double>(tri.v2.x) - tri.v0.x,
                                  static_cast<double>(tri.v2.y) - tri.v0.y,
                                  static_cast<double>(tri.v2.z) - tri.v0.z};
            const double nx = e1[1] * e2[2] - e1[2] * e2[1];
            const double ny = e1[2] * e2[0] - e1[0] * e2[2];
            const double nz = e1[0] * e2[1] - e1[1] * e2[0];
            auto side = [&](float3 q) {
                return (static_cast<double>(q.x) - tri.v0.x) * nx +
                       (static_cast<double>(q.y) - tri.v0.y) * ny +
                       (static_cast<double>(q.z) - tri.v0.z) * nz;
            };
            wrong_side += !(side(out) > 0.0);
            wrong_side += !(side(in) < 0.0);
        }
        CHECK(hits > 15000);
        CHECK(wrong_side == 0);
    }
}

TEST_CASE(
    "exact edge functions: the exact sign, the same in doubles and in floats, and "
    "exact negatives when the vertices swap",
    "[kernel][intersect]") {
    // Nearly parallel p and q, whose float products round to equal floats
    // about half the time, at scales where the float version is exact.
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const float scales[] = {1e-9f, 1e-3f, 1.0f, 1e4f, 1e9f};
    for (float scale : scales) {
        CAPTURE(scale);
        int rounded_to_zero = 0;
        for (int i = 0; i < 100000; ++i) {
            const float px = scale * u(rng);
            const float py = scale * u(rng);
            const float k = 1.0f + 1e-6f * u(rng);
            const float qx = std::nextafter(px * k, px * 2.0f * u(rng));
            const float qy = py * k;
            const double exact = static_cast<double>(px) * qy - static_cast<double>(py) * qx;
            const int sign = (exact > 0.0) - (exact < 0.0);
            rounded_to_zero += px * qy - py * qx == 0.0f;
            const float d = exact_edge_double(px, py, qx, qy);
            const float f = exact_edge_float(px, py, qx, qy);
            REQUIRE(((d > 0.0f) - (d < 0.0f)) == sign);
            REQUIRE(((f > 0.0f) - (f < 0.0f)) == sign);
            REQUIRE(exact_edge_double(qx, qy, px, py) == -d);
            REQUIRE(exact_edge_float(qx, qy, px, py) == -f);
        }
        CHECK(rounded_to_zero > 1000);
        // In line: exactly 0, both ways.
        REQUIRE(exact_edge_double(scale, 2.0f * scale, 3.0f * scale, 6.0f * scale) == 0.0f);
        REQUIRE(exact_edge_float(scale, 2.0f * scale, 3.0f * scale, 6.0f * scale) == 0.0f);
    }
}
