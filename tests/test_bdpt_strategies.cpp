// Bidirectional path tracing's strategies one at a time (pbrt-v4's way of
// checking them): strategy (s, t), unweighted, is an unbiased estimator of
// the light of the paths of s + t vertices that it can make, so every
// strategy that can make all of them must give the same image. Each is
// the image's mean luminance over many frames of independent samples
// (the random sampler), compared with a tolerance of five standard errors
// of the difference, the standard errors from the spread of the frames'
// means; the seeds are fixed, so the test is deterministic. And the
// strategies of one path length together, weighted, against one alone:
// the weights of the strategies that make a path must add up to one.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/bdpt.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace trac0r;

namespace {

struct Estimate {
    double mean = 0.0;
    double standard_error = 0.0;
};

// The image's mean luminance in each of `frames` frames of the
// strategies `which`.
std::vector<double> frame_means(const Renderer& r, kernel::BdptStrategies which, int frames) {
    const PackedScene& packed = r.packed();
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord cam = scaled_camera(r.camera_record(), packed.scale);
    const std::uint32_t pixels = cam.size.x * cam.size.y;
    std::vector<glm::vec4> radiance(pixels);
    std::vector<kernel::t0_i64> splats(4 * pixels);
    std::vector<double> means;
    for (int f = 0; f < frames; ++f) {
        std::fill(splats.begin(), splats.end(), 0);
        std::fill(radiance.begin(), radiance.end(), glm::vec4(0.0f));
        for (std::uint32_t p = 0; p < pixels; ++p) {
            kernel::bdpt_sample(&view, cam, p, 11, static_cast<std::uint32_t>(f), 5, which,
                                radiance.data(), splats.data());
        }
        double frame = 0.0;
        for (std::uint32_t p = 0; p < pixels; ++p) {
            frame +=
                kernel::luminance(glm::vec3(radiance[p]) + kernel::splat_value(splats.data(), p));
        }
        means.push_back(frame / pixels);
    }
    return means;
}

// The mean of the values and its standard error, from their spread.
Estimate estimate_of(const std::vector<double>& values) {
    double sum = 0.0;
    double sum2 = 0.0;
    for (double v : values) {
        sum += v;
        sum2 += v * v;
    }
    const double n = static_cast<double>(values.size());
    Estimate e;
    e.mean = sum / n;
    const double variance = (sum2 / n - e.mean * e.mean) * n / (n - 1.0);
    e.standard_error = std::sqrt(std::max(variance, 0.0) / n);
    return e;
}

// The image's mean luminance from `frames` frames of strategy (s, t) alone.
Estimate strategy_estimate(const Renderer& r, int s, int t, int frames) {
    kernel::BdptStrategies which = kernel::bdpt_all_strategies();
    which.only_s = s;
    which.only_t = t;
    return estimate_of(frame_means(r, which, frames));
}

Renderer bdpt_renderer(const std::string& json, const std::string& base_dir = "",
                       LightSampler light_sampler = LightSampler::automatic) {
    PackOptions options;
    options.integrator = Integrator::bdpt;
    options.sampler = SamplerKind::random;
    options.light_sampler = light_sampler;
    LoadOptions load;
    load.isolate_readers = false;
    return Renderer(parse_scene(json, "strategies.json", base_dir, load),
                    std::make_unique<CpuBackend>(1), 11, options);
}

// Every strategy of `strategies` (pairs s, t of the same s + t) against
// the first.
void check_strategies_agree(const Renderer& r, const std::vector<std::pair<int, int>>& strategies,
                            int frames) {
    const Estimate first = strategy_estimate(r, strategies[0].first, strategies[0].second, frames);
    CAPTURE(strategies[0].first, strategies[0].second, first.mean, first.standard_error);
    REQUIRE(first.mean > 0.0);
    for (std::size_t i = 1; i < strategies.size(); ++i) {
        const Estimate other =
            strategy_estimate(r, strategies[i].first, strategies[i].second, frames);
        const double tolerance = 5.0 * std::sqrt(first.standard_error * first.standard_error +
                                                 other.standard_error * other.standard_error);
        CAPTURE(strategies[i].first, strategies[i].second, other.mean, other.standard_error,
                tolerance);
        CHECK(std::fabs(other.mean - first.mean) <= tolerance);
        // A tolerance that says something: a bias of 15 % would show.
        CHECK(tolerance < 0.15 * first.mean);
    }
}

// The strategies of paths of `length` vertices, weighted, against
// strategy (1, length - 1) alone, which makes all of them where no
// surface is a mirror or smooth glass: if the weights of a path's
// strategies add up to anything but one, the two differ. Both runs draw
// the same numbers for (1, length - 1) (the random sampler, drawn in
// order, and no other strategy draws before it), so the tolerance is five
// standard errors of the frames' differences.
void check_weights_add_up(const Renderer& r, int length, int frames) {
    kernel::BdptStrategies which = kernel::bdpt_all_strategies();
    which.length = length;
    const std::vector<double> weighted = frame_means(r, which, frames);
    which.only_s = 1;
    which.only_t = length - 1;
    const std::vector<double> alone = frame_means(r, which, frames);
    std::vector<double> differences;
    for (int f = 0; f < frames; ++f) {
        differences.push_back(weighted[f] - alone[f]);
    }
    const Estimate difference = estimate_of(differences);
    const double mean = estimate_of(alone).mean;
    const double tolerance = 5.0 * difference.standard_error;
    CAPTURE(length, mean, difference.mean, difference.standard_error, tolerance);
    REQUIRE(mean > 0.0);
    CHECK(std::fabs(difference.mean) <= tolerance);
    CHECK(tolerance < 0.05 * mean);
}

// Paths of three vertices, then of four: every strategy that makes them
// (with s = 0 where lights can be hit), `frames` and `frames_four`
// frames.
void check_three_and_four(const Renderer& r, int frames, int frames_four, bool lights_hit) {
    SECTION("paths of three vertices") {
        std::vector<std::pair<int, int>> three = {{1, 2}, {2, 1}};
        if (lights_hit) {
            three.push_back({0, 3});
        }
        check_strategies_agree(r, three, frames);
    }
    SECTION("paths of four vertices") {
        std::vector<std::pair<int, int>> four = {{1, 3}, {2, 2}, {3, 1}};
        if (lights_hit) {
            four.push_back({0, 4});
        }
        check_strategies_agree(r, four, frames_four);
    }
}

// A closed room lit by a two-sided and a one-sided lamp, with diffuse
// walls and a rough glossy, plastic, conductor and principled object each.
const char* const room = R"({
  "camera": {"position": [0, 0, 0.9], "direction": [0, -0.2, -1], "vertical_fov": 70},
  "render": {"width": 16, "height": 12, "max_depth": 5},
  "materials": {
    "lamp": {"type": "emissive", "color": [1, 0.9, 0.8], "emittance": 6},
    "spot": {"type": "emissive", "color": [0.6, 0.8, 1], "emittance": 8, "two_sided": false},
    "white": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
    "red": {"type": "diffuse", "color": [0.7, 0.2, 0.2]},
    "glossy": {"type": "glossy", "color": [0.9, 0.9, 0.6], "roughness": 0.4},
    "plastic": {"type": "plastic", "color": [0.2, 0.5, 0.8], "roughness": 0.3},
    "metal": {"type": "conductor", "color": [0.9, 0.7, 0.4], "roughness": 0.35},
    "principled": {"type": "principled", "color": [0.8, 0.3, 0.3], "roughness": 0.5,
                   "metallic": 0.4}
  },
  "shapes": [
    {"type": "box", "material": "white", "position": [0, 0, 0], "size": [2.2, 2, 2.2]},
    {"type": "plane", "material": "red", "position": [0, -0.99, 0], "size": [1.5, 1.5]},
    {"type": "plane", "material": "lamp", "position": [-0.4, 0.9, -0.2], "size": [0.4, 0.4]},
    {"type": "plane", "material": "spot", "position": [0.5, 0.95, 0.3],
     "orientation": [3.1415927, 0, 0], "size": [0.3, 0.3]},
    {"type": "box", "material": "glossy", "position": [-0.5, -0.7, -0.4], "size": [0.4, 0.6, 0.4]},
    {"type": "icosphere", "material": "plastic", "position": [0.4, -0.7, -0.3], "radius": 0.3},
    {"type": "icosphere", "material": "metal", "position": [0.0, -0.8, 0.2], "radius": 0.2},
    {"type": "icosphere", "material": "principled", "position": [-0.3, -0.3, -0.8],
     "radius": 0.2}
  ]
})";

// The room's walls and lamp around a rough glass sphere (light through
// it both ways) and a smooth-shaded metal sphere (its vertex normals).
const char* const glass_room = R"({
  "camera": {"position": [0, 0, 0.9], "direction": [0, -0.3, -1], "vertical_fov": 70},
  "render": {"width": 16, "height": 12, "max_depth": 5},
  "materials": {
    "lamp": {"type": "emissive", "color": [1, 0.9, 0.8], "emittance": 6},
    "white": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
    "glass": {"type": "glass", "color": [0.9, 0.95, 1], "roughness": 0.3, "ior": 1.5},
    "metal": {"type": "glossy", "color": [0.8, 0.8, 0.8], "roughness": 0.5}
  },
  "shapes": [
    {"type": "box", "material": "white", "position": [0, 0, 0], "size": [2.2, 2, 2.2]},
    {"type": "plane", "material": "lamp", "position": [0, 0.9, -0.2], "size": [0.5, 0.5]},
    {"type": "icosphere", "material": "glass", "position": [-0.3, -0.6, -0.4], "radius": 0.35},
    {"type": "mesh", "material": "metal", "file": "meshes/sphere80.obj",
     "position": [0.45, -0.7, -0.2], "scale": [0.25, 0.25, 0.25]}
  ]
})";

// Distant light only: a constant environment and a sun's disc of 30
// degrees (wide, so that camera subpaths find it by themselves) over a
// floor with a diffuse and a plastic sphere above it (no corners, where
// an unweighted join's 1 / distance^2 has a heavy tail).
const char* const outdoors = R"({
  "camera": {"position": [0, 1.2, 2.2], "direction": [0, -0.5, -1], "vertical_fov": 50},
  "render": {"width": 16, "height": 12, "max_depth": 5},
  "environment": {"color": [0.3, 0.4, 0.6], "strength": 1},
  "lights": [{"type": "sun", "direction": [0.5, 1, 0.3], "irradiance": 3, "angle": 30}],
  "materials": {
    "ground": {"type": "diffuse", "color": [0.6, 0.6, 0.55]},
    "clay": {"type": "diffuse", "color": [0.75, 0.32, 0.18]},
    "plastic": {"type": "plastic", "color": [0.2, 0.5, 0.8], "roughness": 0.3}
  },
  "shapes": [
    {"type": "plane", "material": "ground", "position": [0, 0, 0], "size": [4, 4]},
    {"type": "icosphere", "material": "clay", "position": [-0.4, 0.6, 0], "radius": 0.3},
    {"type": "icosphere", "material": "plastic", "position": [0.4, 0.5, 0.2], "radius": 0.3}
  ]
})";

// Delta lights only: a point lamp, a spot and a sun of angle 0 in a room
// with an opening; no strategy s = 0 can find them.
const char* const lamps = R"({
  "camera": {"position": [0, 0, 0.9], "direction": [0, -0.2, -1], "vertical_fov": 70},
  "render": {"width": 16, "height": 12, "max_depth": 5},
  "lights": [{"type": "point", "position": [-0.5, 0.6, -0.3], "intensity": 1.5},
             {"type": "spot", "position": [0.5, 0.8, 0], "direction": [-0.2, -1, -0.3],
              "intensity": 4, "angle": 60, "blend": 0.3},
             {"type": "sun", "direction": [0.2, 1, 0.1], "irradiance": 2, "angle": 0}],
  "materials": {
    "white": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
    "plastic": {"type": "plastic", "color": [0.2, 0.5, 0.8], "roughness": 0.3}
  },
  "shapes": [
    {"type": "plane", "material": "white", "position": [0, -1, 0], "size": [2.2, 2.2]},
    {"type": "plane", "material": "white", "position": [0, 0, -1.1],
     "orientation": [1.5707963, 0, 0], "size": [2.2, 2]},
    {"type": "plane", "material": "white", "position": [-1.1, 0, 0],
     "orientation": [0, 0, -1.5707963], "size": [2, 2.2]},
    {"type": "icosphere", "material": "plastic", "position": [0.3, -0.7, -0.4], "radius": 0.3}
  ]
})";

// A room seen from below its ceiling, under most of which a two-sided
// lamp hangs 5 cm: light samples (s = 1) pick their points on it by solid
// angle nearly everywhere, and the camera's own hits (s = 0) and light
// tracing (t = 1) find its light often.
const char* const under_lamp = R"({
  "camera": {"position": [0, -0.2, 0.8], "direction": [0, 0.8, -1], "vertical_fov": 60},
  "render": {"width": 16, "height": 12, "max_depth": 5},
  "materials": {
    "lamp": {"type": "emissive", "color": [1, 0.9, 0.8], "emittance": 4},
    "white": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
    "plastic": {"type": "plastic", "color": [0.2, 0.5, 0.8], "roughness": 0.3}
  },
  "shapes": [
    {"type": "box", "material": "white", "position": [0, 0, 0], "size": [2.2, 2, 2.2]},
    {"type": "plane", "material": "lamp", "position": [0, 0.95, -0.2], "size": [1.6, 1.6]},
    {"type": "icosphere", "material": "plastic", "position": [0.3, -0.6, -0.4], "radius": 0.3}
  ]
})";

}  // namespace

TEST_CASE("each bdpt strategy alone gives the same image in a room of area lights",
          "[bdpt][bdpt_strategies]") {
    check_three_and_four(bdpt_renderer(room), 3000, 3000, true);
}

TEST_CASE("each bdpt strategy alone gives the same image through rough glass and vertex normals",
          "[bdpt][bdpt_strategies]") {
    check_three_and_four(bdpt_renderer(glass_room, std::string(TRAC0R_SOURCE_DIR) + "/scenes"),
                         3000, 3000, true);
}

TEST_CASE("each bdpt strategy alone gives the same image under the sky and the sun",
          "[bdpt][bdpt_strategies]") {
    check_three_and_four(bdpt_renderer(outdoors), 3000, 12000, true);
}

TEST_CASE("each bdpt strategy that can reach a delta light gives the same image",
          "[bdpt][bdpt_strategies]") {
    check_three_and_four(bdpt_renderer(lamps), 3000, 3000, false);
}

// With the light tree, light samples (s = 1) pick lights by the tree's
// probabilities at the vertex, as next-event estimation does, while light
// subpaths start from a light picked by power.
TEST_CASE("each bdpt strategy alone gives the same image with the light tree",
          "[bdpt][bdpt_strategies]") {
    SECTION("area lights") {
        check_three_and_four(bdpt_renderer(room, "", LightSampler::tree), 3000, 3000, true);
    }
    SECTION("a point lamp and a spot in the tree, a sun beside it") {
        check_three_and_four(bdpt_renderer(lamps, "", LightSampler::tree), 3000, 3000, false);
    }
}

TEST_CASE("the weighted strategies of a path length add up to its light",
          "[bdpt][bdpt_strategies]") {
    SECTION("under a large lamp") {
        const Renderer r = bdpt_renderer(under_lamp);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 3000);
    }
    SECTION("in a room of area lights and glossy materials") {
        const Renderer r = bdpt_renderer(room);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 6000);
    }
    SECTION("under the sky and the sun") {
        const Renderer r = bdpt_renderer(outdoors);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 12000);
    }
    SECTION("in the room of area lights, with the light tree") {
        const Renderer r = bdpt_renderer(room, "", LightSampler::tree);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 6000);
    }
    SECTION("under a large lamp, with the light tree") {
        const Renderer r = bdpt_renderer(under_lamp, "", LightSampler::tree);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 3000);
    }
    SECTION("through rough glass and vertex normals, with the light tree") {
        const Renderer r = bdpt_renderer(glass_room, std::string(TRAC0R_SOURCE_DIR) + "/scenes",
                                         LightSampler::tree);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 3000);
    }
    SECTION("with delta lights, with the light tree") {
        const Renderer r = bdpt_renderer(lamps, "", LightSampler::tree);
        check_weights_add_up(r, 3, 3000);
        check_weights_add_up(r, 4, 3000);
    }
}
