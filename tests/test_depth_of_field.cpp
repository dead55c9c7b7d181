// Depth of field: the thin lens (kernel/trace.h, camera_lens_ray) keeps an
// edge at the focus distance sharp and blurs an edge at another depth to
// the circle of confusion the thin lens predicts; a pinhole (aperture 0)
// draws exactly what it drew before lenses existed.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/shape.h"

#include <cmath>
#include <memory>
#include <vector>

using namespace trac0r;

namespace {

const double pi = 3.14159265358979323846;
const float half_pi = 1.5707963f;
const int width = 256;
const int height = 8;
// tan(vfov / 2): a pixel is 2 * 0.005 / 8 = 1.25e-3 wide on the image plane
// at distance one.
const double half_height = 0.005;
const double pixel = 2.0 * half_height / height;

// A lamp of radiance 1 over the left half of the view (x < 0: the camera at
// the origin looks along -z, so +x is right), facing the camera at depth
// `depth`; nothing else: right of its edge the view is black.
// Every length times `unit` (a power of two: the same floats, scaled).
Scene edge_scene(float depth, float aperture_radius, float focus_distance, float unit = 1.0f) {
    Scene scene;
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = glm::vec3(1.0f);
    lamp.emittance = 1.0f;
    scene.materials = {lamp};
    // A plane's normal is local +y: turned by pi/2 about x it is +z.
    scene.shapes.push_back(make_plane(glm::vec3(-50.0f, 0.0f, -depth) * unit,
                                      glm::vec3(half_pi, 0.0f, 0.0f), glm::vec2(100.0f * unit),
                                      0));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.vertical_fov = static_cast<float>(2.0 * std::atan(half_height) * 180.0 / pi);
    scene.camera.aperture_radius = aperture_radius * unit;
    scene.camera.focus_distance = focus_distance * unit;
    scene.render.width = width;
    scene.render.height = height;
    scene.render.max_depth = 1;
    return scene;
}

// Each column's mean radiance over its rows, after `frames` samples.
std::vector<double> column_profile(const Scene& scene, int frames) {
    PackOptions options;
    options.sampler = SamplerKind::sobol;  // stratified: a smoother profile
    Renderer r(scene, std::make_unique<CpuBackend>(), 3, options);
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    const Image image = r.image();
    std::vector<double> columns(width, 0.0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            columns[x] += image.pixels[static_cast<std::size_t>(y) * width + x].x / height;
        }
    }
    return columns;
}

// Where, in pixels from the left edge of the image, the profile (falling
// from 1 to 0 across the edge) first drops below `level`: linear between
// column centres.
double crossing(const std::vector<double>& columns, double level) {
    for (int x = 1; x < width; ++x) {
        if (columns[x] < level && columns[x - 1] >= level) {
            const double f = (columns[x - 1] - level) / (columns[x - 1] - columns[x]);
            return x - 0.5 + f;
        }
    }
    FAIL("the profile never crosses " << level);
    return 0.0;
}

// The width between the 75 % and 25 % levels of the edge's profile.
double edge_width(const std::vector<double>& columns) {
    return crossing(columns, 0.25) - crossing(columns, 0.75);
}

// A disc of radius 1 seen through a straight edge: the share of it beyond
// x = t is (acos t - t sqrt(1 - t^2)) / pi. Where that share is 1/4
// (bisection; the share falls in t).
double disc_quarter_point() {
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 60; ++i) {
        const double t = 0.5 * (lo + hi);
        const double share = (std::acos(t) - t * std::sqrt(1.0 - t * t)) / pi;
        (share > 0.25 ? lo : hi) = t;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("a thin lens keeps the focus plane sharp and blurs by the circle of confusion",
          "[camera][dof]") {
    const float aperture = 0.08f;
    const float focus = 2.0f;
    const int frames = 256;  // 2,048 samples a column: the 25 % and 75 % points within ~0.3 px

    SECTION("an edge at the focus distance is as sharp as a pinhole's") {
        const std::vector<double> lens = column_profile(edge_scene(focus, aperture, focus), frames);
        const std::vector<double> pinhole = column_profile(edge_scene(focus, 0.0f, focus), frames);
        CAPTURE(edge_width(lens), edge_width(pinhole));
        // A pixel's box spreads the edge over one column: 25 % to 75 % is
        // half a pixel; the lens may not add more than half a pixel to it.
        CHECK(edge_width(pinhole) < 1.0);
        CHECK(edge_width(lens) < 1.0);
        // The edge stays at the image centre.
        CHECK(std::fabs(0.5 * (crossing(lens, 0.25) + crossing(lens, 0.75)) - 128.0) < 0.5);
    }

    for (const float depth : {4.0f, 1.5f}) {
        SECTION("an edge behind or in front of the focus plane blurs to the predicted disc") {
            // Thin lens: a point at depth z spreads to a disc of radius
            // A |z - f| / (z f) on the image plane at distance one.
            const double radius_px =
                aperture * std::fabs(depth - focus) / (depth * focus) / pixel;
            const double expected = 2.0 * disc_quarter_point() * radius_px;
            const std::vector<double> profile =
                column_profile(edge_scene(depth, aperture, focus), frames);
            const double measured = edge_width(profile);
            CAPTURE(depth, radius_px, expected, measured);
            REQUIRE(radius_px > 8.0);  // far wider than a pixel's own spread
            CHECK(std::fabs(measured - expected) < 0.1 * expected);
            CHECK(std::fabs(0.5 * (crossing(profile, 0.25) + crossing(profile, 0.75)) - 128.0) <
                  1.0);
        }
    }
}

TEST_CASE("a lens in a scene packed at another scale blurs the same", "[camera][dof]") {
    // A scene of 2^-50 m is packed scaled up to ordinary floats
    // (PackedScene::scale): the lens' lengths scale with it.
    const float unit = std::ldexp(1.0f, -50);
    const std::vector<double> ordinary = column_profile(edge_scene(4.0f, 0.08f, 2.0f), 64);
    const std::vector<double> tiny = column_profile(edge_scene(4.0f, 0.08f, 2.0f, unit), 64);
    CAPTURE(edge_width(ordinary), edge_width(tiny));
    CHECK(std::fabs(edge_width(ordinary) - edge_width(tiny)) < 0.02 * edge_width(ordinary));
}

TEST_CASE("a pinhole draws the same numbers whatever its focus distance", "[camera][dof]") {
    // The lens' dimension is drawn only with an open aperture: a pinhole's
    // image is the same bits for any focus distance.
    Scene a = edge_scene(3.0f, 0.0f, 1.0f);
    Scene b = edge_scene(3.0f, 0.0f, 7.0f);
    a.render.max_depth = b.render.max_depth = 2;
    Renderer ra(a, std::make_unique<CpuBackend>(), 5);
    Renderer rb(b, std::make_unique<CpuBackend>(), 5);
    for (int i = 0; i < 4; ++i) {
        ra.render_frame();
        rb.render_frame();
    }
    const Image ia = ra.image();
    const Image ib = rb.image();
    REQUIRE(ia.pixels.size() == ib.pixels.size());
    for (std::size_t i = 0; i < ia.pixels.size(); ++i) {
        REQUIRE(ia.pixels[i] == ib.pixels[i]);
    }
}
