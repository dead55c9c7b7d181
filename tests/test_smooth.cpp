// Smooth shading: a triangle's vertex normals, interpolated, are its
// shading normal, while the triangle itself decides sides, ray offsets and
// shadow rays (kernel/trace.h, shading_normal).
#include "test_support.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/trace.h"
#include "trac0r/renderer.h"

#include <glm/glm.hpp>

#include <memory>

using namespace trac0r;

namespace {

const float pi = 3.14159265f;

// A 10 x 10 white floor at y = 0 (normal +y) under a lamp at y = 1; the
// floor's vertex normals, where `tilt` is not negative, all tilted by tilt
// radians toward +x. The camera looks straight at the floor from below
// (its underside) or from above; image right is +x.
Scene floor_scene(float tilt, bool from_below, int max_depth = 5) {
    Scene scene;
    Material white;
    white.name = "white";
    white.color = glm::vec3(0.8f);
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = glm::vec3(1.0f);
    lamp.emittance = 10.0f;
    scene.materials = {white, lamp};
    Shape floor = make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(10.0f), 0);
    if (tilt >= 0.0f) {
        const glm::vec3 n(std::sin(tilt), std::cos(tilt), 0.0f);
        floor.normals.assign(floor.triangles.size(), VertexNormalTriple{n, n, n});
    }
    scene.shapes.push_back(floor);
    scene.shapes.push_back(
        make_plane(glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(pi, 0.0f, 0.0f), glm::vec2(1.0f), 1));
    scene.camera.position = glm::vec3(0.0f, from_below ? -1.0f : 0.5f, 0.0f);
    scene.camera.direction = glm::vec3(0.0f, from_below ? 1.0f : -1.0f, 0.0f);
    scene.camera.world_up = glm::vec3(0.0f, 0.0f, from_below ? 1.0f : -1.0f);  // image right: +x
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = 32;
    scene.render.height = 24;
    scene.render.max_depth = max_depth;
    return scene;
}

// Mean luminance of the columns [x0, x1) of the accumulated image.
double columns_mean(Renderer& r, int x0, int x1) {
    const Image image = r.image();
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            sum += kernel::luminance(image.pixels[static_cast<std::size_t>(y) * image.width + x]);
            ++n;
        }
    }
    return sum / n;
}

std::unique_ptr<Backend> make_backend(bool opencl) {
    if (opencl) {
        return std::make_unique<OpenClBackend>(0);
    }
    return std::make_unique<CpuBackend>();
}

// Under the floor nothing can be lit: every path from the camera starts on
// the floor's underside, and the lamp is above it. Shading normals tilted
// far over send half of the scattered directions, and half of the light
// samples' directions, through the floor unless the triangle decides.
void require_no_leak(bool opencl) {
    for (const Integrator integrator : {Integrator::naive, Integrator::nee}) {
        for (const SamplerKind sampler : {SamplerKind::random, SamplerKind::sobol}) {
            for (const float tilt : {1.2f, 1.5f}) {
                CAPTURE(to_string(integrator), to_string(sampler), tilt);
                PackOptions options;
                options.integrator = integrator;
                options.sampler = sampler;
                Renderer r(floor_scene(tilt, true), make_backend(opencl), 3, options);
                REQUIRE((r.packed().features & T0_FEATURE_SMOOTH) != 0u);
                for (int i = 0; i < 16; ++i) {
                    r.render_frame();
                }
                double total = 0.0;
                for (const kernel::AccumPixel& p : r.accumulator()) {
                    total += p.sum.x + p.sum.y + p.sum.z;
                }
                REQUIRE(total == 0.0);
            }
        }
    }
}

}  // namespace

TEST_CASE("the shading normal is the vertex normals interpolated at the hit", "[smooth]") {
    Scene scene = floor_scene(-1.0f, false);
    scene.shapes.resize(1);
    scene.shapes[0].triangles.resize(1);
    const Triangle& t = scene.shapes[0].triangles[0];
    const glm::vec3 g = t.normal;  // +y
    REQUIRE(g.y > 0.99f);
    // Vertex normals on the far side of the triangle: turned to its side.
    const glm::vec3 n0 = glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f));
    const glm::vec3 n1 = glm::normalize(glm::vec3(0.0f, 1.0f, 0.4f));
    const glm::vec3 n2 = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.1f));
    scene.shapes[0].normals = {VertexNormalTriple{n0, n1, n2}};
    const PackedScene packed = pack_scene(scene);
    REQUIRE((packed.features & T0_FEATURE_SMOOTH) != 0u);
    const kernel::SceneView view = packed.view();
    kernel::Hit hit;
    hit.t = 1.0f;
    hit.u = 0.2f;
    hit.v = 0.3f;
    hit.triangle = 0;
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    const glm::vec3 expected = glm::normalize(n0 * 0.5f + n1 * 0.2f + n2 * 0.3f);
    const glm::vec3 expected_up = expected.y < 0.0f ? -expected : expected;
    CHECK(glm::length(kernel::shading_normal(&view, hit, down, g) - expected_up) < 1e-6f);
    // From below the same.
    CHECK(glm::length(kernel::shading_normal(&view, hit, -down, g) - expected_up) < 1e-6f);
    // An incoming ray above the triangle but below the shading normal's
    // horizon: shaded flat.
    const glm::vec3 tilt_direction = glm::normalize(expected_up - expected_up.y * g);
    const glm::vec3 grazing = glm::normalize(tilt_direction - 0.01f * g);
    REQUIRE(glm::dot(grazing, g) < 0.0f);
    REQUIRE(glm::dot(grazing, expected_up) > 0.0f);
    CHECK(kernel::shading_normal(&view, hit, grazing, g) == g);
    // A flat scene leaves the feature out; its shading normal is the
    // geometric one.
    scene.shapes[0].normals.clear();
    const PackedScene flat = pack_scene(scene);
    CHECK((flat.features & T0_FEATURE_SMOOTH) == 0u);
    CHECK(flat.normals.empty());
    const kernel::SceneView flat_view = flat.view();
    CHECK(kernel::shading_normal(&flat_view, hit, down, g) == g);
}

TEST_CASE("nothing leaks through a smooth-shaded surface (CPU)", "[smooth]") {
    require_no_leak(false);
}

TEST_CASE("nothing leaks through a smooth-shaded surface (OpenCL)", "[smooth][opencl]") {
    require_no_leak(true);
}

TEST_CASE("a smooth surface is lit as its shading normal faces", "[smooth]") {
    // Direct light only (max_depth 2). Normals tilted by t toward +x face
    // the lamp above the image's centre better from the left half of the
    // floor than from the right. The view and the lamp are symmetric about
    // x = 0, and there n.l = cos(t) l_y + sin(t) l_x, whose second term
    // cancels between mirrored points (no n.l is negative here, and every
    // camera ray meets the floor above the shading normal's horizon): the
    // whole image is cos(t) times the flat floor's, in expectation.
    const auto halves = [](float tilt, double* left, double* right) {
        PackOptions options;
        options.integrator = Integrator::nee;
        Renderer r(floor_scene(tilt, false, 2), std::make_unique<CpuBackend>(), 5, options);
        for (int i = 0; i < 64; ++i) {
            r.render_frame();
        }
        *left = columns_mean(r, 0, 16);
        *right = columns_mean(r, 16, 32);
    };
    const float tilt = 0.5f;
    double flat_left = 0.0, flat_right = 0.0, smooth_left = 0.0, smooth_right = 0.0;
    halves(-1.0f, &flat_left, &flat_right);
    halves(tilt, &smooth_left, &smooth_right);
    CAPTURE(flat_left, flat_right, smooth_left, smooth_right);
    CHECK(std::fabs(flat_left - flat_right) < 0.02 * flat_left);
    CHECK(smooth_left > 1.1 * smooth_right);
    const double ratio = (smooth_left + smooth_right) / (flat_left + flat_right);
    CHECK(std::fabs(ratio - std::cos(tilt)) < 0.02);
}
