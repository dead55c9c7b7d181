// Lamps against their closed forms: a diffuse plane of albedo rho lit by a
// point lamp of intensity I at distance r and angle theta has radiance
// rho/pi I cos(theta) / r^2; by a spot, the same times the documented
// falloff; by the sun, rho/pi E cos(theta), whether the sun is a direction
// or a disc. One-sided emitters are black from behind and, from the front,
// the two-sided emitter exactly. The OpenCL backend agrees with the CPU.
#include <catch2/catch.hpp>

#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/trace.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/scene_loader.h"
#include "trac0r/shape.h"
#include "test_support.h"

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

using namespace trac0r;

namespace {

const double pi = 3.14159265358979323846;
const float albedo = 0.5f;
const int side = 24;
const double camera_height = 3.0;

// A diffuse floor (y = 0, 40 m square) seen from straight above by a
// camera at height 3 with a 60 degree view: image right is +x, image up
// is -z. Nothing else, so what a path finds after its first bounce is
// black: the floor's radiance is its direct light alone. Every length
// times `unit` (a power of two: the same floats, scaled).
Scene floor_scene(float unit = 1.0f) {
    Scene scene;
    Material floor;
    floor.name = "floor";
    floor.type = MaterialType::diffuse;
    floor.color = glm::vec3(albedo);
    scene.materials = {floor};
    scene.shapes.push_back(
        make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(40.0f * unit), 0));
    scene.camera.position = glm::vec3(0.0f, static_cast<float>(camera_height) * unit, 0.0f);
    scene.camera.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    scene.camera.world_up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = side;
    scene.render.height = side;
    scene.render.max_depth = 2;
    return scene;
}

Renderer render(const Scene& scene, int frames, Integrator integrator = Integrator::nee,
                std::unique_ptr<Backend> backend = nullptr) {
    PackOptions options;
    options.integrator = integrator;
    options.sampler = SamplerKind::sobol;
    Renderer r(scene, backend ? std::move(backend) : std::make_unique<CpuBackend>(), 7, options);
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    REQUIRE(r.stats().samples_dropped == 0);
    return r;
}

// The closed form `radiance` of a floor point, averaged over each pixel
// (a 16 x 16 grid of the camera's own rays), as the pixel's samples see it.
std::vector<double> expected_image(const Scene& scene,
                                   const std::function<double(glm::dvec3)>& radiance) {
    const kernel::CameraRecord cam = make_camera_record(scene.camera, side, side);
    std::vector<double> image(side * side, 0.0);
    const int grid = 16;
    for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) {
            double sum = 0.0;
            for (int j = 0; j < grid * grid; ++j) {
                const kernel::Ray ray =
                    kernel::camera_ray(cam, static_cast<float>(x), static_cast<float>(y),
                                       (j % grid + 0.5f) / grid, (j / grid + 0.5f) / grid);
                const glm::dvec3 o(ray.origin);
                const glm::dvec3 d(ray.direction);
                sum += radiance(o + d * (-o.y / d.y));
            }
            image[static_cast<std::size_t>(y) * side + x] = sum / (grid * grid);
        }
    }
    return image;
}

// Each pixel's red channel within `tolerance` of the closed form,
// relative, plus `floor` of the image's peak (where it is near zero).
void require_closed_form(const Image& image, const std::vector<double>& expected, double tolerance,
                         double floor = 1e-4) {
    double peak = 0.0;
    for (double e : expected) {
        peak = std::fmax(peak, e);
    }
    REQUIRE(peak > 0.0);
    for (int i = 0; i < side * side; ++i) {
        const double got = image.pixels[static_cast<std::size_t>(i)].x;
        CAPTURE(i % side, i / side, got, expected[static_cast<std::size_t>(i)]);
        REQUIRE(std::fabs(got - expected[static_cast<std::size_t>(i)]) <=
                tolerance * expected[static_cast<std::size_t>(i)] + floor * peak);
    }
}

Lamp point_lamp(glm::vec3 position, float intensity) {
    Lamp lamp;
    lamp.type = LampType::point;
    lamp.position = position;
    lamp.power = intensity;
    return lamp;
}

// The documented spot falloff (docs/lights.md): smoothstep from the cone's
// half-angle inwards over `blend` of it, in the cosine.
double spot_falloff(double cos_angle, double angle_degrees, double blend) {
    const double outer = std::cos(0.5 * angle_degrees * pi / 180.0);
    const double inner = std::cos(0.5 * angle_degrees * pi / 180.0 * (1.0 - blend));
    const double t = std::fmin(std::fmax((cos_angle - outer) / (inner - outer), 0.0), 1.0);
    return t * t * (3.0 - 2.0 * t);
}

}  // namespace

// Pixel jitter with 64 Sobol points over a smooth function is exact to far
// below 0.5 %; what remains is float rounding.
TEST_CASE("a point lamp lights a diffuse plane as rho/pi I cos / r^2", "[lamps]") {
    // Also a scene 2^-50 the size (packed at another scale, PackedScene::
    // scale), with the intensity times 2^-100: the same image.
    for (const float unit : {1.0f, std::ldexp(1.0f, -50)}) {
        Scene scene = floor_scene(unit);
        const glm::dvec3 light(0.3, 1.0, -0.2);
        const double intensity = 2.0;
        scene.lamps.push_back(point_lamp(glm::vec3(light) * unit,
                                         static_cast<float>(intensity) * unit * unit));
        Renderer r = render(scene, 64);
        REQUIRE((r.packed().features & T0_FEATURE_LAMPS) != 0u);
        CAPTURE(unit, r.packed().scale);
        REQUIRE((unit == 1.0f) == (r.packed().scale == 1.0f));
        const auto radiance = [&](glm::dvec3 p) {
            const glm::dvec3 to = light - p;
            const double r2 = glm::dot(to, to);
            const double cos_theta = to.y / std::sqrt(r2);
            return albedo / pi * intensity * cos_theta / r2;
        };
        require_closed_form(r.image(), expected_image(floor_scene(), radiance), 0.005);
    }
}

TEST_CASE("a spot lamp is a point lamp times its falloff, dark outside its cone", "[lamps]") {
    Scene scene = floor_scene();
    const glm::dvec3 light(0.0, 1.0, 0.0);
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -1.0, 0.1));
    Lamp spot = point_lamp(glm::vec3(light), 3.0f);
    spot.type = LampType::spot;
    spot.direction = glm::vec3(axis);
    spot.angle = 70.0f;
    spot.blend = 0.4f;
    scene.lamps.push_back(spot);
    Renderer r = render(scene, 256);
    // The falloff's ends are kinks (its slope jumps to zero) that cross
    // pixels: there a pixel's mean is the grid's and the 256 samples' to
    // about 1e-3 of the peak (and 2 % of its value).
    const std::vector<double> expected = expected_image(scene, [&](glm::dvec3 p) {
        const glm::dvec3 to = light - p;
        const double r2 = glm::dot(to, to);
        const double cos_theta = to.y / std::sqrt(r2);
        const double falloff = spot_falloff(glm::dot(-to / std::sqrt(r2), axis), 70.0, 0.4);
        return albedo / pi * 3.0 * falloff * cos_theta / r2;
    });
    require_closed_form(r.image(), expected, 0.02, 1e-3);
    int dark = 0, lit = 0;
    for (double e : expected) {
        dark += e == 0.0;
        lit += e > 0.0;
    }
    REQUIRE(dark > 50);  // the test sees the outside of the cone and its inside
    REQUIRE(lit > 50);
}

TEST_CASE("the sun lights a diffuse plane as rho/pi E cos, as a direction or a disc", "[lamps]") {
    const double irradiance = 4.0;
    const glm::dvec3 towards = glm::normalize(glm::dvec3(0.5, 1.0, 0.2));
    for (float angle : {0.0f, 0.53f, 5.0f}) {
        Scene scene = floor_scene();
        Lamp sun;
        sun.type = LampType::sun;
        sun.direction = glm::vec3(towards);
        sun.power = static_cast<float>(irradiance);
        sun.angle = angle;
        scene.lamps.push_back(sun);
        Renderer r = render(scene, 64);
        // A disc of angular radius a and radiance E / (pi sin^2 a) brings
        // its solid angle 2 pi (1 - cos a) times the mean cosine over it,
        // cos(theta) (1 + cos a) / 2 (the mean direction of a uniform cap
        // is its axis times that), which is E cos(theta) exactly while the
        // disc is above the horizon: as the delta sun.
        const double expected = albedo / pi * irradiance * towards.y;
        CAPTURE(angle);
        require_closed_form(r.image(), std::vector<double>(side * side, expected),
                            angle > 1.0f ? 0.01 : 0.005);
    }
}

TEST_CASE("the naive integrator cannot find a delta lamp: its light is NEE's alone", "[lamps]") {
    Scene scene = floor_scene();
    scene.lamps.push_back(point_lamp(glm::vec3(0.0f, 1.0f, 0.0f), 2.0f));
    Renderer r = render(scene, 4, Integrator::naive);
    for (const glm::vec3& p : r.image().pixels) {
        REQUIRE(p == glm::vec3(0.0f));
    }
}

namespace {

// A lamp quad 0.6 m square at height 1 over the floor, facing down (its
// front: the plane's +y turned by pi about x), two-sided or not.
Scene lamp_over_floor(bool two_sided, bool facing_down) {
    Scene scene = floor_scene();
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = glm::vec3(1.0f);
    lamp.emittance = 4.0f;
    lamp.two_sided = two_sided;
    scene.materials.push_back(lamp);
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 1.0f, 0.0f),
                                      glm::vec3(facing_down ? 3.14159265f : 0.0f, 0.0f, 0.0f),
                                      glm::vec2(0.6f), 1));
    return scene;
}

// Whether pixel i sees the floor alone: the lamp, 0.3 m from the centre
// at 2 m from the camera, covers 3.1 pixels either side of the image's
// centre (a pixel is 2 tan 30 degrees / 24 at distance one).
bool floor_only(std::size_t i) {
    const double x = static_cast<double>(i % side) + 0.5 - 0.5 * side;
    const double y = static_cast<double>(i / side) + 0.5 - 0.5 * side;
    return std::fabs(x) > 4.0 || std::fabs(y) > 4.0;
}

}  // namespace

TEST_CASE("a one-sided emitter is black from behind and the two-sided one from the front",
          "[lamps]") {
    // The camera above looks at the lamp's back (it faces down): the lamp's
    // pixels are black, and the floor, lit by its front, is the two-sided
    // lamp's floor bit for bit (the lamp is the only light, so the same
    // samples; no floor ray meets its back).
    Renderer one = render(lamp_over_floor(false, true), 16);
    Renderer two = render(lamp_over_floor(true, true), 16);
    REQUIRE((one.packed().features & T0_FEATURE_ONE_SIDED) != 0u);
    REQUIRE((two.packed().features & T0_FEATURE_ONE_SIDED) == 0u);
    const Image a = one.image();
    const Image b = two.image();
    const std::size_t centre = static_cast<std::size_t>(side / 2) * side + side / 2;
    REQUIRE(a.pixels[centre] == glm::vec3(0.0f));
    REQUIRE(b.pixels[centre].x == Approx(4.0f));
    int floor_pixels = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (floor_only(i)) {
            REQUIRE(a.pixels[i] == b.pixels[i]);
            floor_pixels += a.pixels[i].x > 0.0f;
        }
    }
    REQUIRE(floor_pixels == side * side - 64);
    // Turned to face up, the one-sided lamp sends the floor nothing: black
    // everywhere but the lamp, which the camera now sees from the front.
    const Image up = render(lamp_over_floor(false, false), 16).image();
    REQUIRE(up.pixels[centre].x == Approx(4.0f));
    for (std::size_t i = 0; i < up.pixels.size(); ++i) {
        if (floor_only(i)) {
            REQUIRE(up.pixels[i] == glm::vec3(0.0f));
        }
    }
}

TEST_CASE("lamps and a one-sided emitter render alike on OpenCL and the CPU", "[lamps][opencl]") {
    REQUIRE_FALSE(list_opencl_devices().empty());
    Scene scene = lamp_over_floor(false, true);
    scene.lamps.push_back(point_lamp(glm::vec3(-1.0f, 1.5f, 0.5f), 2.0f));
    Lamp spot = point_lamp(glm::vec3(1.0f, 1.0f, 0.0f), 3.0f);
    spot.type = LampType::spot;
    spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    spot.angle = 50.0f;
    spot.blend = 0.2f;
    scene.lamps.push_back(spot);
    Lamp sun;
    sun.type = LampType::sun;
    sun.direction = glm::normalize(glm::vec3(0.3f, 1.0f, -0.4f));
    sun.power = 2.0f;
    sun.angle = 2.0f;
    scene.lamps.push_back(sun);
    scene.render.max_depth = 4;
    PackOptions options;
    options.integrator = Integrator::nee;
    options.sampler = SamplerKind::sobol;
    const PackedScene packed = pack_scene(scene, options);
    require_warning_free_build(packed);
    const Image a = render(scene, 8).image();
    const Image b = render(scene, 8, Integrator::nee, std::make_unique<OpenClBackend>(0)).image();
    // The same random numbers: equal to float rounding, but for the rare
    // path a last-bit difference turns.
    const int close = close_pixel_count(a, b);
    CAPTURE(close, a.pixels.size());
    REQUIRE(close >= static_cast<int>(0.95 * a.pixels.size()));
}

TEST_CASE("scene files set two_sided on emitting materials only, and lamps by type",
          "[lamps][scene_loader]") {
    const Scene scene = parse_scene(
        R"({"materials": {"lamp": {"type": "emissive", "color": [1, 1, 1], "emittance": 2,
                                   "two_sided": false},
                          "wall": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
            "shapes": [{"type": "plane", "size": [1, 1], "material": "lamp"}],
            "lights": [{"type": "spot", "position": [0, 2, 0], "direction": [0, -2, 0],
                        "intensity": 5, "color": [1, 0.5, 0.5]},
                       {"type": "sun", "direction": [0, 1, 1], "irradiance": 3}]})",
        "s.json", "");
    CHECK_FALSE(scene.materials[0].two_sided);
    CHECK(scene.materials[1].two_sided);
    REQUIRE(scene.lamps.size() == 2);
    CHECK(scene.lamps[0].type == LampType::spot);
    CHECK(scene.lamps[0].direction == glm::vec3(0.0f, -1.0f, 0.0f));
    CHECK(scene.lamps[0].angle == 45.0f);  // the documented defaults
    CHECK(scene.lamps[0].blend == 0.15f);
    CHECK(scene.lamps[1].angle == default_sun_angle);
    CHECK(scene.lamps[1].direction.y == Approx(std::sqrt(0.5f)));
    CHECK_THROWS_WITH(
        parse_scene(R"({"materials": {"g": {"type": "glass", "color": [1, 1, 1],
                                            "two_sided": false}},
                        "shapes": [{"type": "plane", "size": [1, 1], "material": "g"}]})",
                    "s.json", ""),
        Catch::Matchers::Contains("/materials/g/two_sided: unknown key in a glass material"));
}
