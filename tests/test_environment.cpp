// The environment: a furnace (a diffuse sphere of albedo a under a
// constant environment of radiance 1 converges to a, the background is
// 1); the map's sampler (its density integrates to one over the sphere,
// its samples follow it by a chi-square test, and each sample's density is
// the density looked up for its direction); the map's convention (its
// right half lies towards +x, its top row up, its middle ahead of the
// default view; a rotation turns it about +y); the map's sampler alone and
// cosine sampling alone estimate the same irradiance; next-event
// estimation and scattering alone converge to the same image under a map
// and a sun disc;
// OpenCL agrees with the CPU; and the scene file's messages.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/image_io.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/kernel/environment.h"
#include "trac0r/kernel/sampling.h"
#include "trac0r/lights.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/scene_loader.h"
#include "trac0r/shape.h"
#include "test_support.h"

#include <cmath>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace trac0r;
using Catch::Matchers::Contains;

namespace {

const double pi = 3.14159265358979323846;

Material diffuse(const std::string& name, glm::vec3 color) {
    Material m;
    m.name = name;
    m.type = MaterialType::diffuse;
    m.color = color;
    return m;
}

// A diffuse sphere of radius 0.5 at the origin, seen from (0, 0, 2)
// looking along -z (image right is +x), filling the middle of the view.
Scene sphere_scene(int width, int height, glm::vec3 albedo) {
    Scene scene;
    scene.materials = {diffuse("ball", albedo)};
    scene.shapes.push_back(make_icosphere(glm::vec3(0.0f), glm::vec3(0.0f), 0.5f, 3, 0));
    scene.camera.position = glm::vec3(0.0f, 0.0f, 2.0f);
    scene.camera.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.vertical_fov = 45.0f;
    scene.render.width = width;
    scene.render.height = height;
    scene.render.max_depth = 4;
    return scene;
}

Environment constant_environment(glm::vec3 color) {
    Environment e;
    e.present = true;
    e.color = color;
    return e;
}

Renderer render(const Scene& scene, int frames, Integrator integrator, std::uint64_t seed = 5,
                std::unique_ptr<Backend> backend = nullptr) {
    PackOptions options;
    options.integrator = integrator;
    options.sampler = SamplerKind::sobol;
    Renderer r(scene, backend ? std::move(backend) : std::make_unique<CpuBackend>(), seed, options);
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    REQUIRE(r.stats().samples_dropped == 0);
    return r;
}

// A map whose right half (u >= 0.5) is red, whose top half (v < 0.5) is
// green, with a little blue everywhere, and in it a bright patch (a "sun"
// of radiance 40 at u 0.7, v 0.3) that sampling by luminance must find.
Environment quadrant_map(int width, int height, bool with_patch) {
    Environment e;
    e.present = true;
    e.map = "quadrants";
    e.width = width;
    e.height = height;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float u = (x + 0.5f) / width;
            const float v = (y + 0.5f) / height;
            glm::vec3 t(u >= 0.5f ? 1.0f : 0.0f, v < 0.5f ? 1.0f : 0.0f, 0.2f);
            if (with_patch && std::fabs(u - 0.7f) < 0.04f && std::fabs(v - 0.3f) < 0.04f) {
                t = glm::vec3(40.0f);
            }
            e.texels.push_back(t);
        }
    }
    return e;
}

// An irregular map: texels of random radiance, a fifth of them black.
Environment random_map(int width, int height, float rotation) {
    Environment e;
    e.present = true;
    e.map = "random";
    e.width = width;
    e.height = height;
    e.rotation = rotation;
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int i = 0; i < width * height; ++i) {
        const float r = uniform(rng);
        e.texels.push_back(r < 0.2f ? glm::vec3(0.0f)
                                    : glm::vec3(uniform(rng), uniform(rng), uniform(rng)) * 3.0f);
    }
    return e;
}

glm::dvec3 direction_at(double theta, double phi) {
    return glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                      std::sin(theta) * std::sin(phi));
}

}  // namespace

TEST_CASE("a furnace: a diffuse sphere under a constant environment of 1 converges to its albedo",
          "[environment][furnace]") {
    const int width = 32, height = 24;
    const float a = 0.6f;
    for (Integrator integrator : {Integrator::nee, Integrator::naive}) {
        Scene scene = sphere_scene(width, height, glm::vec3(a));
        scene.environment = constant_environment(glm::vec3(1.0f));
        Renderer r = render(scene, 512, integrator);
        REQUIRE((r.packed().features & T0_FEATURE_ENVIRONMENT) != 0u);
        const std::vector<kernel::AccumPixel> accum = r.accumulator();
        // The sphere, a convex polyhedron, sees only the environment: one
        // bounce gives a. The central 8 x 8 pixels (four 4 x 4 blocks) lie
        // on it; their mean within 5 standard errors, and the test's
        // tolerance under 2 %.
        const std::vector<BlockMean> blocks = block_means(accum, width, height, 4, 4);
        double mean = 0.0, variance = 0.0;
        for (int index : {19, 20, 27, 28}) {
            const BlockMean& b = blocks.at(static_cast<std::size_t>(index));
            REQUIRE(std::abs(b.x + 2 - width / 2) <= 2);
            REQUIRE(std::abs(b.y + 2 - height / 2) <= 2);
            mean += b.mean / 4.0;
            variance += b.variance / 16.0;
        }
        const double se = std::sqrt(variance);
        CAPTURE(to_string(integrator), mean, se);
        REQUIRE(std::fabs(mean - a) <= 5.0 * se + 1e-6);
        REQUIRE(5.0 * se < 0.02 * a);
        // The corners see the environment itself: 1 in every sample.
        const Image image = r.image();
        for (int i : {0, width - 1, (height - 1) * width, height * width - 1}) {
            REQUIRE(image.pixels[static_cast<std::size_t>(i)] == glm::vec3(1.0f));
        }
    }
}

TEST_CASE("the map's density integrates to one and each sample's density is its direction's",
          "[environment][sampling]") {
    for (float rotation : {0.0f, 30.0f, -135.0f}) {
        Scene scene = sphere_scene(8, 8, glm::vec3(0.5f));
        scene.environment = random_map(24, 12, rotation);
        const PackedScene packed = pack_scene(scene);
        const kernel::SceneView view = packed.view();
        REQUIRE(packed.distant_count == 1u);
        const kernel::LightRecord* light = &packed.lights[0];
        REQUIRE(light->ids.y == T0_LIGHT_ENVIRONMENT);
        // The midpoint rule over 1024 x 2048 cells of theta and phi: its
        // error is the cells that straddle a texel's edge, about 1e-3.
        const int rows = 1024, columns = 2048;
        double integral = 0.0;
        for (int i = 0; i < rows; ++i) {
            const double theta = pi * (i + 0.5) / rows;
            for (int j = 0; j < columns; ++j) {
                const double phi = 2.0 * pi * (j + 0.5) / columns;
                const glm::vec3 d(direction_at(theta, phi));
                integral += kernel::environment_pdf(&view, light, d) * std::sin(theta);
            }
        }
        integral *= (pi / rows) * (2.0 * pi / columns);
        CAPTURE(rotation);
        REQUIRE(integral == Approx(1.0).epsilon(2e-3));
        // Each sample: a unit direction whose looked-up density is the
        // sampled one (but for a sample on a texel's very edge, which the
        // lookup may place in the neighbour).
        std::mt19937 rng(99);
        std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
        int mismatched = 0;
        const int samples = 20000;
        for (int i = 0; i < samples; ++i) {
            const kernel::EnvironmentSample s =
                kernel::environment_sample(&view, light, glm::vec2(uniform(rng), uniform(rng)));
            REQUIRE(s.pdf > 0.0f);
            REQUIRE(glm::length(s.direction) == Approx(1.0f).epsilon(1e-5));
            const float looked_up = kernel::environment_pdf(&view, light, s.direction);
            mismatched += std::fabs(looked_up - s.pdf) > 1e-3f * s.pdf;
        }
        REQUIRE(mismatched <= samples / 1000);
    }
}

TEST_CASE("the map's samples follow its density (chi-square over solid-angle cells)",
          "[environment][sampling]") {
    Scene scene = sphere_scene(8, 8, glm::vec3(0.5f));
    scene.environment = random_map(16, 8, 20.0f);
    const PackedScene packed = pack_scene(scene);
    const kernel::SceneView view = packed.view();
    const kernel::LightRecord* light = &packed.lights[0];
    // Cells of equal solid angle, 24 in phi by 12 in cos(theta): not the
    // map's texels (rotated 20 degrees, and of equal angle, not area). Each
    // cell's probability from the density, by the midpoint rule on 64 x 64
    // points in it.
    const int cells_phi = 24, cells_z = 12, n = 64;
    std::vector<double> expected(cells_phi * cells_z, 0.0);
    for (int cz = 0; cz < cells_z; ++cz) {
        for (int cp = 0; cp < cells_phi; ++cp) {
            double sum = 0.0;
            for (int i = 0; i < n; ++i) {
                const double z = 1.0 - 2.0 * (cz + (i + 0.5) / n) / cells_z;
                for (int j = 0; j < n; ++j) {
                    const double phi = 2.0 * pi * (cp + (j + 0.5) / n) / cells_phi;
                    const glm::vec3 d(direction_at(std::acos(z), phi));
                    sum += kernel::environment_pdf(&view, light, d);
                }
            }
            expected[static_cast<std::size_t>(cz * cells_phi + cp)] =
                sum / (n * n) * 4.0 * pi / (cells_phi * cells_z);
        }
    }
    const int samples = 200000;
    std::vector<double> observed(expected.size(), 0.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int i = 0; i < samples; ++i) {
        const kernel::EnvironmentSample s =
            kernel::environment_sample(&view, light, glm::vec2(uniform(rng), uniform(rng)));
        const double z = std::fmin(std::fmax(static_cast<double>(s.direction.y), -1.0), 1.0);
        double phi =
            std::atan2(static_cast<double>(s.direction.z), static_cast<double>(s.direction.x));
        phi = phi < 0.0 ? phi + 2.0 * pi : phi;
        const int cz = std::min(cells_z - 1, static_cast<int>((1.0 - z) / 2.0 * cells_z));
        const int cp = std::min(cells_phi - 1, static_cast<int>(phi / (2.0 * pi) * cells_phi));
        observed[static_cast<std::size_t>(cz * cells_phi + cp)] += 1.0;
    }
    double total = 0.0;
    std::vector<double> expected_counts;
    for (double p : expected) {
        total += p;
        expected_counts.push_back(p * samples);
    }
    REQUIRE(total == Approx(1.0).epsilon(5e-3));
    // At 1 - 1e-4 (test_support.h's chi_square), cells expecting fewer
    // than 5 samples pooled.
    const ChiSquare chi2 = chi_square(expected_counts, observed);
    CAPTURE(chi2.value, chi2.cells, chi2.critical);
    REQUIRE(chi2.cells > 200);
    REQUIRE(chi2.value < chi2.critical);
}

TEST_CASE("the map faces as documented: right half towards +x, top up, middle ahead",
          "[environment]") {
    const int width = 32, height = 24;
    Scene scene = sphere_scene(width, height, glm::vec3(0.8f));
    scene.environment = quadrant_map(64, 32, false);
    Renderer r = render(scene, 32, Integrator::nee);
    const Image image = r.image();
    const auto at = [&](int x, int y) {
        return image.pixels[static_cast<std::size_t>(y) * width + x];
    };
    // The background, camera rays alone: the column right of the image's
    // middle sees u >= 0.5 (red), the one left of it u < 0.5; the top rows
    // see the map's top half (green), the bottom rows its bottom half.
    REQUIRE(at(width / 2, 0) == glm::vec3(1.0f, 1.0f, 0.2f));
    REQUIRE(at(width / 2 - 1, 0) == glm::vec3(0.0f, 1.0f, 0.2f));
    REQUIRE(at(width / 2, height - 1) == glm::vec3(1.0f, 0.0f, 0.2f));
    REQUIRE(at(0, height - 1) == glm::vec3(0.0f, 0.0f, 0.2f));
    // The sphere, lit by it: its +x side (image right) red, its -x side
    // not; its top green, its bottom far less.
    const glm::vec3 right = at(width / 2 + 5, height / 2);
    const glm::vec3 left = at(width / 2 - 6, height / 2);
    const glm::vec3 top = at(width / 2, height / 2 - 6);
    const glm::vec3 bottom = at(width / 2, height / 2 + 5);
    CAPTURE(right.x, left.x, top.y, bottom.y);
    REQUIRE(right.x > 4.0f * left.x);
    REQUIRE(top.y > 4.0f * bottom.y);
    // Turned by 90 degrees about +y (counter-clockwise seen from above),
    // the map's middle faces -x, and the view ahead sees u = 0.75 (red);
    // turned by -90 degrees, u = 0.25.
    for (float rotation : {90.0f, -90.0f}) {
        scene.environment.rotation = rotation;
        Renderer turned = render(scene, 1, Integrator::nee);
        const glm::vec3 ahead = turned.image().pixels[static_cast<std::size_t>(width / 2)];
        CAPTURE(rotation);
        REQUIRE(ahead.x == (rotation > 0.0f ? 1.0f : 0.0f));
    }
}

namespace {

// Spheres on a floor under the quadrant map with its bright patch and a
// sun disc of 40 degrees (wide, so that scattered rays find it often and
// its MIS weights matter): diffuse, rough glossy and glass surfaces, where
// light sampling and scattering both find the map and the sun.
Scene outdoor_scene(int width, int height) {
    Scene scene = sphere_scene(width, height, glm::vec3(0.7f, 0.6f, 0.5f));
    scene.camera.position = glm::vec3(0.0f, 0.6f, 2.2f);
    scene.camera.direction = glm::vec3(0.0f, -0.3f, -1.0f);
    scene.materials.push_back(diffuse("floor", glm::vec3(0.5f)));
    Material glossy;
    glossy.name = "glossy";
    glossy.type = MaterialType::glossy;
    glossy.color = glm::vec3(0.9f);
    glossy.roughness = 0.3f;
    scene.materials.push_back(glossy);
    Material glass;
    glass.name = "glass";
    glass.type = MaterialType::glass;
    glass.color = glm::vec3(1.0f);
    scene.materials.push_back(glass);
    scene.shapes.push_back(
        make_plane(glm::vec3(0.0f, -0.5f, 0.0f), glm::vec3(0.0f), glm::vec2(6.0f), 1));
    scene.shapes.push_back(
        make_icosphere(glm::vec3(0.9f, -0.2f, 0.3f), glm::vec3(0.0f), 0.3f, 2, 2));
    scene.shapes.push_back(
        make_icosphere(glm::vec3(-0.9f, -0.2f, 0.3f), glm::vec3(0.0f), 0.3f, 2, 3));
    scene.environment = quadrant_map(64, 32, true);
    scene.environment.rotation = 40.0f;
    scene.environment.strength = 0.7f;
    Lamp sun;
    sun.type = LampType::sun;
    sun.direction = glm::normalize(glm::vec3(-0.4f, 1.0f, 0.6f));
    sun.power = 3.0f;
    sun.angle = 40.0f;
    scene.lamps.push_back(sun);
    scene.render.max_depth = 5;
    return scene;
}

}  // namespace

// As test_nee's comparison of the integrators (require_same_block_means):
// 4 x 4 blocks and the whole image.
TEST_CASE(
    "light sampling with MIS and scattering alone converge to the same image under a "
    "map and a sun disc",
    "[environment][nee]") {
    const int width = 32, height = 24;
    const Scene scene = outdoor_scene(width, height);
    Renderer nee = render(scene, 256, Integrator::nee, 101);
    Renderer naive = render(scene, 1024, Integrator::naive, 202);
    REQUIRE((nee.packed().features & (T0_FEATURE_ENVIRONMENT | T0_FEATURE_LAMPS)) ==
            (T0_FEATURE_ENVIRONMENT | T0_FEATURE_LAMPS));
    // Teeth: over the whole image, a bias of 5 % is outside the tolerance.
    REQUIRE(require_same_block_means(nee.accumulator(), naive.accumulator(), width, height, 4) <
            0.05);
}

TEST_CASE("an environment map renders alike on OpenCL and the CPU", "[environment][opencl]") {
    REQUIRE_FALSE(list_opencl_devices().empty());
    const Scene scene = outdoor_scene(32, 24);
    PackOptions options;
    options.integrator = Integrator::nee;
    options.sampler = SamplerKind::sobol;
    require_warning_free_build(pack_scene(scene, options));
    const Image a = render(scene, 8, Integrator::nee).image();
    const Image b =
        render(scene, 8, Integrator::nee, 5, std::make_unique<OpenClBackend>(0)).image();
    const int close = close_pixel_count(a, b);
    CAPTURE(close, a.pixels.size());
    REQUIRE(close >= static_cast<int>(0.95 * a.pixels.size()));
}

namespace {

// A Radiance .hdr file of width x height texels of one colour (flat RGBE
// scanlines, which readers take where a scanline does not start 2, 2).
void write_hdr(const std::string& path, int width, int height, glm::vec3 color) {
    std::ofstream out(path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << height << " +X " << width << "\n";
    int exponent = 0;
    const float peak = std::fmax(color.x, std::fmax(color.y, color.z));
    const float mantissa = std::frexp(peak, &exponent) * 256.0f / peak;
    const unsigned char rgbe[4] = {static_cast<unsigned char>(color.x * mantissa),
                                   static_cast<unsigned char>(color.y * mantissa),
                                   static_cast<unsigned char>(color.z * mantissa),
                                   static_cast<unsigned char>(exponent + 128)};
    for (int i = 0; i < width * height; ++i) {
        out.write(reinterpret_cast<const char*>(rgbe), 4);
    }
}

std::string scene_with(const std::string& extra) {
    return R"({"materials": {"m": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
               "shapes": [{"type": "plane", "size": [1, 1], "material": "m"}],)" +
           extra + "}";
}

}  // namespace

TEST_CASE("environment maps load from .exr and .hdr files, as the scene names them",
          "[environment][scene_loader]") {
    TempDir dir;
    Image image;
    image.width = 8;
    image.height = 4;
    image.pixels.assign(32, glm::vec3(0.25f, 0.5f, 2.0f));
    dir.write("sky.exr", "");  // removed with the directory; written next
    write_exr(dir.path() + "/sky.exr", image);
    const Scene exr = parse_scene(scene_with(R"("environment": {"map": "sky.exr", "strength": 2,
                                                                  "rotation": 45})"),
                                  "scene.json", dir.path());
    REQUIRE(exr.environment.present);
    REQUIRE(exr.environment.width == 8);
    REQUIRE(exr.environment.height == 4);
    REQUIRE(exr.environment.texels.at(5) == glm::vec3(0.25f, 0.5f, 2.0f));
    REQUIRE(exr.environment.strength == 2.0f);
    REQUIRE(exr.environment.rotation == 45.0f);
    dir.write("sky.hdr", "");
    write_hdr(dir.path() + "/sky.hdr", 16, 8, glm::vec3(0.5f, 1.0f, 0.25f));
    const Scene hdr =
        parse_scene(scene_with(R"("environment": {"map": "sky.hdr"})"), "scene.json", dir.path());
    REQUIRE(hdr.environment.width == 16);
    REQUIRE(hdr.environment.texels.at(3) == glm::vec3(0.5f, 1.0f, 0.25f));
    // What cannot be a map: one message naming the file and the texel or
    // the reason.
    image.at(3, 2) = glm::vec3(0.5f, -0.25f, 1.0f);
    dir.write("negative.exr", "");
    write_exr(dir.path() + "/negative.exr", image);
    CHECK_THROWS_WITH(read_environment_map(dir.path() + "/negative.exr"),
                      Contains("negative.exr: environment map texel (3, 2) has a negative value "
                               "in channel G"));
    std::string truncated;
    {
        std::ifstream in(dir.path() + "/sky.hdr", std::ios::binary);
        truncated.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    dir.write("cut.hdr", truncated.substr(0, truncated.size() / 2));
    CHECK_THROWS_WITH(read_environment_map(dir.path() + "/cut.hdr"),
                      Contains("cut.hdr: cannot read environment map"));
    dir.write("text.exr", "not an image at all");
    CHECK_THROWS_WITH(read_environment_map(dir.path() + "/text.exr"),
                      Contains("text.exr: cannot read environment map: not an OpenEXR file"));
}

TEST_CASE("bad environments and lights get one message naming the key", "[environment][lamps]") {
    const auto message = [](const std::string& extra) {
        try {
            parse_scene(scene_with(extra), "s.json", "/nonexistent");
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    CHECK_THAT(message(R"("environment": {"color": [1, 1, 1], "strength": -1})"),
               Contains("s.json: /environment/strength: expected a finite number >= 0, got -1"));
    CHECK_THAT(message(R"("environment": {"color": [1, 1, 1], "map": "a.exr"})"),
               Contains("/environment: an environment has a \"color\" or a \"map\", not both"));
    CHECK_THAT(message(R"("environment": {"strength": 1})"),
               Contains("/environment: required key is missing"));
    CHECK_THAT(message(R"("environment": {"map": "sky.exr"})"),
               Contains("/environment/map: /nonexistent/sky.exr: cannot open environment map"));
    CHECK_THAT(message(R"("environment": {"map": "sky.png"})"),
               Contains("expected an .exr or .hdr file"));
    CHECK_THAT(message(R"("environment": {"color": [1, 1, 1], "rotation": 10})"),
               Contains("/environment/rotation: a constant environment has no rotation"));
    CHECK_THAT(message(R"("lights": [{"type": "lamp"}])"),
               Contains("/lights/0/type: expected one of \"point\", \"spot\", \"sun\""));
    CHECK_THAT(message(R"("lights": [{"type": "point", "position": [0, 1, 0]}])"),
               Contains("/lights/0/intensity: required key is missing"));
    CHECK_THAT(message(R"("lights": [{"type": "spot", "position": [0, 1, 0], "intensity": 1,
                                      "direction": [0, -1, 0], "angle": 200}])"),
               Contains("/lights/0/angle: expected a number of degrees in (0, 180]"));
    CHECK_THAT(message(R"("lights": [{"type": "spot", "position": [0, 1, 0], "intensity": 1,
                                      "direction": [0, 0, 0]}])"),
               Contains("/lights/0/direction: expected a direction"));
    CHECK_THAT(message(R"("lights": [{"type": "sun", "direction": [0, 1, 0], "irradiance": 1,
                                      "angle": -1}])"),
               Contains("/lights/0/angle: expected a number of degrees in [0, 90]"));
    CHECK_THAT(message(R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1,
                                      "cone": 3}])"),
               Contains("/lights/0/cone: unknown key in a point light"));
    CHECK_THAT(message(R"("lights": {"type": "point"})"),
               Contains("/lights: expected an array of lights"));
}

TEST_CASE("light sampling alone and cosine sampling alone estimate the same irradiance from a map",
          "[environment][nee]") {
    // The irradiance integral of the quadrant map (with its bright patch)
    // at a surface, estimated from each sampler alone: the map's own
    // (environment_sample, its radiance over its density times the cosine)
    // and the cosine-weighted hemisphere's (pi times the radiance looked
    // up); the two means within 5 standard errors of their difference, and
    // the tolerance under 3 %.
    Scene scene = sphere_scene(8, 8, glm::vec3(0.5f));
    scene.environment = quadrant_map(64, 32, true);
    scene.environment.rotation = 25.0f;
    const PackedScene packed = pack_scene(scene);
    const kernel::SceneView view = packed.view();
    const kernel::LightRecord* light = &packed.lights[0];
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (const glm::vec3 n :
         {glm::vec3(0.0f, 1.0f, 0.0f), glm::normalize(glm::vec3(1.0f, 0.2f, -0.5f)),
          glm::vec3(0.0f, -1.0f, 0.0f)}) {
        const int samples = 1000000;
        double sum_light = 0.0, sum2_light = 0.0, sum_cos = 0.0, sum2_cos = 0.0;
        for (int i = 0; i < samples; ++i) {
            const kernel::EnvironmentSample s =
                kernel::environment_sample(&view, light, glm::vec2(uniform(rng), uniform(rng)));
            const float c = glm::dot(s.direction, n);
            const double a = s.pdf > 0.0f && c > 0.0f
                                 ? static_cast<double>(kernel::luminance(s.radiance)) * c / s.pdf
                                 : 0.0;
            sum_light += a;
            sum2_light += a * a;
            const kernel::DirectionSample d =
                kernel::sample_cosine_hemisphere(n, uniform(rng), uniform(rng));
            const double b = pi * kernel::luminance(kernel::environment_radiance(
                                      &view, light, glm::normalize(d.direction)));
            sum_cos += b;
            sum2_cos += b * b;
        }
        const double mean_light = sum_light / samples;
        const double mean_cos = sum_cos / samples;
        const double var = (sum2_light / samples - mean_light * mean_light) / samples +
                           (sum2_cos / samples - mean_cos * mean_cos) / samples;
        CAPTURE(n.x, n.y, n.z, mean_light, mean_cos, std::sqrt(var));
        REQUIRE(std::fabs(mean_light - mean_cos) <= 5.0 * std::sqrt(var));
        REQUIRE(5.0 * std::sqrt(var) < 0.03 * mean_cos);
    }
}
