// Extreme material parameters (issue 5, docs/stability.md): glass of ior
// 1, 1.5 and 3, total internal reflection, mirror and roughness-1 glossy
// lobes, colours 0 and 1, and emittance 1e6.
#include <catch2/catch.hpp>

#include "stability_support.h"

#include <cmath>
#include <memory>

using namespace trac0r;
using namespace trac0r::stability;

namespace {

// The camera at `position` in a scene of one closed box of side 2 around the
// origin, looking at `target` with a 90 degree field of view.
Scene inside_box(const Material& walls, glm::vec3 position, glm::vec3 direction) {
    Scene scene;
    scene.materials.push_back(walls);
    scene.shapes.push_back(make_box(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(2.0f), 0));
    scene.camera.position = position;
    scene.camera.direction = direction;
    scene.camera.vertical_fov = 90.0f;
    scene.render.width = 16;
    scene.render.height = 16;
    return scene;
}

// The image mean over all samples equals `expected` within five standard
// errors (plus 1e-6 relative, the float rounding of the accumulated mean,
// for cases without noise), and the render is precise enough to mean
// something: five standard errors are below `resolution`, the smallest error
// the case is about (each caller says which).
void require_mean(Renderer& r, double expected, double resolution) {
    const Estimate e = estimate(r.accumulator(), all_pixels(r.width(), r.height()));
    CAPTURE(e.mean, e.standard_error(), expected, resolution);
    REQUIRE(5.0 * e.standard_error() < resolution);
    REQUIRE(std::fabs(e.mean - expected) < 5.0 * e.standard_error() + 1e-6 * expected);
    REQUIRE(r.stats().samples_dropped == 0);
}

// The camera looks through a wide glass slab (side 50, 0.5 thick) at an
// emissive wall of radiance le, with a narrow field of view (every ray within
// 3 degrees of the slab's normal). Light that reflects back leaves towards
// the camera side, where nothing is.
Scene glass_slab(float ior, glm::vec3 tint, float le) {
    Scene scene;
    scene.materials.push_back(make_material(MaterialType::glass, tint, 0.0f, 0.0f, ior));
    scene.materials.push_back(make_material(MaterialType::emissive, glm::vec3(1.0f), le));
    scene.shapes.push_back(
        make_box(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(50.0f, 50.0f, 0.5f), 0));
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 0.0f, 3.0f), glm::vec3(-1.5707964f, 0, 0),
                                      glm::vec2(100.0f), 1));
    set_view(scene, glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(0.0f, 0.0f, 1.0f), 5.0f, 16, 1000);
    return scene;
}

// A closed box of side 2 whose walls all emit le and reflect with albedo rho
// (as the furnace of test_render.cpp, for any material type): every path
// vertex is on a wall, so a path of at most D vertices carries
// le (1 + rho + ... + rho^(D-1)) as long as the material never absorbs.
Scene furnace(MaterialType type, float rho, float le, int max_depth) {
    Scene scene = inside_box(make_material(type, glm::vec3(rho), le / rho),
                             glm::vec3(0.1f, -0.2f, 0.05f), glm::vec3(0.2f, 0.1f, 1.0f));
    scene.render.max_depth = max_depth;
    return scene;
}

double furnace_mean(double rho, double le, int max_depth) {
    double sum = 0.0;
    for (int k = 0; k < max_depth; ++k) {
        sum += le * std::pow(rho, k);
    }
    return sum;
}

}  // namespace

TEST_CASE(
    "glass slab: ior 1 is invisible except its tint; ior 1.5 and 3 transmit "
    "(1 - R) / (1 + R)",
    "[stability][material]") {
    // Near normal incidence each interface reflects R = ((n - 1) / (n + 1))^2
    // and the slab's inter-reflections sum to a transmittance of
    // (1 - R) / (1 + R): 0.923 for n = 1.5, 0.6 for n = 3. Index-matched
    // glass (n = 1) bends and reflects nothing and only tints each crossing.
    const float le = 2.0f;
    // Clear ior 1: no randomness at all (nothing reflects, nothing is
    // absorbed), so every sample is the expected value; 1 % of le is below
    // the 1.6 % that even ior 1.2 would reflect at its two interfaces.
    SECTION("ior 1, clear: the wall as if there were no glass") {
        std::unique_ptr<Renderer> r = render(glass_slab(1.0f, glm::vec3(1.0f), le), 4);
        require_mean(*r, le, 0.01 * le);
    }
    SECTION("ior 1, tinted: the wall times the tint squared") {
        // Roulette follows the tinted throughput, so here samples vary; the
        // resolution is what a tint applied once, not at both crossings,
        // would add: le (luminance(tint) - luminance(tint^2)) = 0.37.
        const glm::vec3 tint(0.9f, 0.7f, 0.5f);
        std::unique_ptr<Renderer> r = render(glass_slab(1.0f, tint, le), 4);
        require_mean(*r, le * kernel::luminance(tint * tint),
                     le * (kernel::luminance(tint) - kernel::luminance(tint * tint)));
    }
    SECTION("ior 1.5 and 3: the slab's inter-reflections") {
        // Each sample is le or 0 (transmitted or reflected back), so the
        // standard error is le sqrt(T (1 - T) / n): with 16 x 16 x 32 samples
        // five of them are 0.03 le at most, below le R (0.04 le and 0.25 le),
        // the error of a slab that reflected at only one interface.
        const float iors[] = {1.5f, 3.0f};
        for (float ior : iors) {
            CAPTURE(ior);
            const double reflectance = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
            std::unique_ptr<Renderer> r = render(glass_slab(ior, glm::vec3(1.0f), le), 32);
            require_mean(*r, le * (1.0 - reflectance) / (1.0 + reflectance), le * reflectance);
        }
    }
}

TEST_CASE("total internal reflection traps light inside a glass cube", "[stability][material]") {
    // The camera is inside a glass cube (ior 1.5) in an emissive room and
    // looks along a diagonal: every ray meets every face at more than the
    // critical angle (41.8 degrees; each direction component stays below
    // cos 41.8 = 0.745 under reflections), so no light from outside can
    // reach it along these rays: exactly black, at max depth 1000. With
    // ior 1.2 (critical angle 56.4 degrees) the same rays see the room.
    auto scene = [](float ior) {
        Scene s;
        s.materials.push_back(make_material(MaterialType::glass, glm::vec3(1.0f), 0.0f, 0.0f, ior));
        s.materials.push_back(make_material(MaterialType::emissive, glm::vec3(1.0f), 1.0f));
        s.shapes.push_back(make_box(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(2.0f), 0));
        s.shapes.push_back(make_box(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(10.0f), 1));
        set_view(s, glm::vec3(0.1f, -0.2f, 0.05f), glm::vec3(1.0f, 1.0f, 1.0f), 8.0f, 16, 1000);
        return s;
    };
    std::unique_ptr<Renderer> trapped = render(scene(1.5f), 4);
    for (const glm::vec3& p : trapped->image().pixels) {
        REQUIRE(p == glm::vec3(0.0f));
    }
    REQUIRE(trapped->stats().samples_dropped == 0);
    std::unique_ptr<Renderer> escaping = render(scene(1.2f), 4);
    const Estimate e =
        estimate(escaping->accumulator(), all_pixels(escaping->width(), escaping->height()));
    CHECK(e.mean > 0.5);
}

TEST_CASE("a roughness-0 mirror furnace conserves energy like the diffuse one",
          "[stability][material]") {
    // A perfect mirror never absorbs (its direction is always above the
    // surface), so a closed mirror box obeys the furnace formula.
    const float rho = 0.8f;
    const int depth = 8;
    std::unique_ptr<Renderer> r = render(furnace(MaterialType::glossy, rho, 1.0f, depth), 24);
    // Resolution: the last vertex's share, rho^(D-1) = 0.21 (a mirror that
    // lost one bounce in D, or absorbed a fifth of its paths once).
    require_mean(*r, furnace_mean(rho, 1.0, depth), std::pow(rho, depth - 1));
}

TEST_CASE(
    "roughness 1: the cosine hemisphere around the mirror direction, the part below the "
    "surface absorbed",
    "[stability][material]") {
    // At roughness 1 the glossy cone is a cosine-weighted hemisphere around
    // the mirror direction m. Projected onto the disc perpendicular to m
    // (Malley) it is uniform, and the directions below the surface fill the
    // part x^2 > (1 - y^2) cos^2 b of one half, b the angle of m from the
    // normal: a fraction (1 - cos b) / 2 fails (weight zero), the rest has
    // weight = colour. At normal incidence none fails and E[cos] = 2/3, as
    // for a diffuse surface. Checked within five standard errors.
    const kernel::MaterialRecord m = kernel::make_material_record(
        T0_MATERIAL_GLOSSY, glm::vec3(0.8f, 0.6f, 0.4f), 0.0f, 1.0f, 1.5f);
    const glm::vec3 normal = glm::normalize(glm::vec3(0.2f, 1.0f, -0.3f));
    const glm::vec3 tangent = glm::normalize(glm::cross(normal, glm::vec3(1.0f, 0.0f, 0.0f)));
    kernel::Rng rng;
    kernel::rng_seed(&rng, 31);
    const int n = 20000;
    for (double degrees : {0.0, 30.0, 60.0, 85.0}) {
        CAPTURE(degrees);
        const double b = degrees * 3.14159265358979 / 180.0;
        const glm::vec3 incoming = glm::normalize(static_cast<float>(-std::cos(b)) * normal +
                                                  static_cast<float>(std::sin(b)) * tangent);
        int failed = 0;
        int bad = 0;
        double cos_sum = 0.0;
        double cos2_sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const kernel::ScatterSample s = kernel::scatter_glossy(&m, incoming, normal, kernel::rng_float2(&rng));
            if (s.weight == glm::vec3(0.0f)) {
                ++failed;
                continue;
            }
            const double c = glm::dot(s.direction, normal);
            bad += !(c > 0.0) || s.weight != glm::vec3(m.color) || !(s.pdf > 0.0f);
            cos_sum += c;
            cos2_sum += c * c;
        }
        CHECK(bad == 0);
        const double p = (1.0 - std::cos(b)) / 2.0;
        if (degrees == 0.0) {
            CHECK(failed == 0);
            const double mean = cos_sum / n;
            const double standard_error = std::sqrt((cos2_sum / n - mean * mean) / n);
            CHECK(std::fabs(mean - 2.0 / 3.0) < 5.0 * standard_error);
        } else {
            const double standard_error = std::sqrt(p * (1.0 - p) / n);
            CHECK(std::fabs(static_cast<double>(failed) / n - p) < 5.0 * standard_error);
        }
    }
}

TEST_CASE("colour 1 reflects everything (furnace mean le D); colour 0 reflects nothing",
          "[stability][material]") {
    SECTION("colour 1") {
        const int depth = 8;
        std::unique_ptr<Renderer> r = render(furnace(MaterialType::diffuse, 1.0f, 0.5f, depth), 24);
        // Resolution: one vertex's emission, 0.5 (a path one bounce short).
        require_mean(*r, 0.5 * depth, 0.5);
    }
    SECTION("colour 0, diffuse and glossy: black wherever the lamp is not seen directly") {
        // The room looking down at the floor: the lamp is out of view, so
        // every pixel's light would have to be reflected.
        for (MaterialType type : {MaterialType::diffuse, MaterialType::glossy}) {
            CAPTURE(to_string(type));
            for (float colour : {0.0f, 0.5f}) {
                CAPTURE(colour);
                Scene scene = room(1.0f, glm::vec3(0.0f));
                scene.materials[0] = make_material(type, glm::vec3(colour), 0.0f, 0.5f);
                scene.materials[2] = make_material(type, glm::vec3(colour), 0.0f, 0.5f);
                scene.camera.direction = glm::vec3(0.0f, -1.0f, 0.3f);
                std::unique_ptr<Renderer> r = render(scene, 4);
                const Estimate e = estimate(r->accumulator(), all_pixels(r->width(), r->height()));
                if (colour == 0.0f) {
                    CHECK(e.mean == 0.0);
                } else {
                    CHECK(e.mean > 0.01);  // the control: some light is reflected
                }
                CHECK(r->stats().samples_dropped == 0);
            }
        }
    }
}

TEST_CASE("emittance 1e6 scales the image by exactly 1e6", "[stability][material]") {
    // Emission never steers a path (roulette looks at the throughput), so
    // the same seed draws the same paths: every pixel scales, to float
    // rounding (1e-5 relative covers a few roundings per path vertex).
    std::unique_ptr<Renderer> unit = render(room(1.0f, glm::vec3(0.0f), 1.0f), 32, 4);
    std::unique_ptr<Renderer> bright = render(room(1.0f, glm::vec3(0.0f), 1e6f), 32, 4);
    const Image a = unit->image();
    const Image b = bright->image();
    int lit = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const double expected = 1e6 * a.pixels[i][k];
            REQUIRE(std::isfinite(b.pixels[i][k]));
            REQUIRE(std::fabs(b.pixels[i][k] - expected) <= 1e-5 * expected);
        }
        lit += a.pixels[i].x > 0.0f;
    }
    // The control: the lamp is out of view, so a pixel is lit once one of its
    // 32 paths has reached the lamp; most must be, or the check is empty.
    CHECK(lit > static_cast<int>(a.pixels.size()) / 2);
    CHECK(bright->stats().samples_dropped == 0);
}
