// Temporal reuse (kernel/temporal.h, trac0r/temporal.h): a pixel keeps the
// previous frame's colour where the previous view saw the same surface,
// and starts again where it did not.
#include "test_support.h"

#include "trac0r/camera.h"
#include "trac0r/fly_camera.h"
#include "trac0r/guides.h"
#include "trac0r/temporal.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace trac0r;

namespace {

const float half_pi = 1.5707963f;

// A wall facing the camera at z = 2 that fills every view below, and a
// box 0.2 across at z 0.9 to 1.1 in front of its middle. The camera looks
// along +z from (x, 0, 0).
Scene wall_and_box() {
    Scene scene;
    Material white;
    white.name = "white";
    white.color = glm::vec3(0.7f);
    scene.materials = {white};
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(-half_pi, 0.0f, 0.0f),
                                      glm::vec2(100.0f), 0));
    scene.shapes.push_back(
        make_box(glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f), glm::vec3(0.2f), 0));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.direction = glm::vec3(0.0f, 0.0f, 1.0f);
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = 64;
    scene.render.height = 48;
    return scene;
}

struct View {
    kernel::CameraRecord camera;
    GuideImages guides;
};

View view_of(const PackedScene& packed, const Camera& camera, int width, int height) {
    View v;
    v.camera = make_camera_record(camera, width, height);
    v.guides = render_surface_guides(packed, v.camera);  // as the window's
    return v;
}

Image flat_image(int width, int height, glm::vec3 colour) {
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height, colour);
    return image;
}

// The world point a pixel's guide depth puts its first hit at.
glm::vec3 first_hit(const View& v, int x, int y) {
    const glm::vec3 forward(v.camera.forward);
    const float sx = (2.0f * (x + 0.5f) / v.camera.size.x - 1.0f) * v.camera.extent.x;
    const float sy = (1.0f - 2.0f * (y + 0.5f) / v.camera.size.y) * v.camera.extent.y;
    const glm::vec3 d =
        glm::normalize(forward + glm::vec3(v.camera.right) * sx + glm::vec3(v.camera.up) * sy);
    const float depth = v.guides.depth[static_cast<std::size_t>(y) * v.guides.width + x];
    return glm::vec3(v.camera.position) + d * (depth / glm::dot(d, forward));
}

const glm::vec3 red(1.0f, 0.0f, 0.0f);
const glm::vec3 green(0.0f, 1.0f, 0.0f);

}  // namespace

TEST_CASE("a static view keeps its whole history", "[temporal]") {
    const Scene scene = builtin_scene();
    const PackedScene packed = pack_scene(scene);
    const View v = view_of(packed, scene.camera, 40, 30);
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(40, 30, red), 10.0f, v.camera, v.guides);
    TemporalStats stats;
    const TemporalFrame next = temporal_blend(history, flat_image(40, 30, green), 1.0f, v.camera,
                                              v.guides, TemporalSettings(), &stats);
    CHECK(stats.reused == 40 * 30);
    CHECK(stats.dropped == 0);
    for (const kernel::TemporalPixel& p : next.pixels) {
        REQUIRE(p.value.w == Approx(11.0f));
        REQUIRE(p.value.x == Approx(10.0f / 11.0f));
        REQUIRE(p.value.y == Approx(1.0f / 11.0f));
    }
}

TEST_CASE("history counts for at most max_history samples", "[temporal]") {
    const Scene scene = builtin_scene();
    const PackedScene packed = pack_scene(scene);
    const View v = view_of(packed, scene.camera, 20, 15);
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(20, 15, red), 1000.0f, v.camera, v.guides);
    TemporalSettings settings;
    settings.max_history = 3.0f;
    const TemporalFrame next =
        temporal_blend(history, flat_image(20, 15, green), 1.0f, v.camera, v.guides, settings);
    for (const kernel::TemporalPixel& p : next.pixels) {
        REQUIRE(p.value.w == Approx(4.0f));
        REQUIRE(p.value.x == Approx(0.75f));
        REQUIRE(p.value.y == Approx(0.25f));
    }
}

TEST_CASE("a history of another resolution reprojects into the view", "[temporal]") {
    const Scene scene = builtin_scene();
    const PackedScene packed = pack_scene(scene);
    const View small = view_of(packed, scene.camera, 20, 15);
    const View large = view_of(packed, scene.camera, 80, 60);
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(20, 15, red), 4.0f, small.camera, small.guides);
    TemporalStats stats;
    temporal_blend(history, flat_image(80, 60, green), 1.0f, large.camera, large.guides,
                   TemporalSettings(), &stats);
    // Only pixels at a silhouette (the boxes', the room's corners) may find
    // no tap of the coarse history on their surface.
    CHECK(stats.reused > 80 * 60 * 9 / 10);
}

TEST_CASE("a camera step keeps the wall seen before and drops what the box hid", "[temporal]") {
    const Scene scene = wall_and_box();
    const PackedScene packed = pack_scene(scene);
    const int w = scene.render.width;
    const int h = scene.render.height;
    const View before = view_of(packed, scene.camera, w, h);
    Camera moved = scene.camera;
    moved.position.x = 0.15f;
    const View after = view_of(packed, moved, w, h);
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(w, h, red), 8.0f, before.camera, before.guides);
    TemporalStats stats;
    const TemporalFrame next = temporal_blend(history, flat_image(w, h, green), 1.0f, after.camera,
                                              after.guides, TemporalSettings(), &stats);
    // From the old camera at the origin, a wall point P (z = 2) lies behind
    // the box when the segment to it crosses the box's front face, z = 0.9:
    // max(|P.x|, |P.y|) * 0.9 / 2 <= 0.1. The old view covers |x| < 2 tan(40 deg) at z = 2.
    int kept = 0;
    int dropped = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            if (std::fabs(after.guides.depth[i] - 2.0f) > 1e-3f) {
                continue;  // the box
            }
            const glm::vec3 p = first_hit(after, x, y);
            const float reach = std::max(std::fabs(p.x), std::fabs(p.y)) * 0.9f / 2.0f;
            const float old_edge = 2.0f * before.camera.extent.x;
            const kernel::TemporalPixel& out = next.pixels[i];
            CAPTURE(x, y, p.x, p.y, out.value.w);
            if (reach < 0.1f - 0.02f) {
                REQUIRE(out.value.w == 1.0f);  // hidden before: the new sample alone
                REQUIRE(out.value.y == 1.0f);
                ++dropped;
            } else if (reach > 0.1f + 0.02f && std::fabs(p.x) < old_edge - 0.05f) {
                REQUIRE(out.value.w == Approx(9.0f));
                REQUIRE(out.value.x == Approx(8.0f / 9.0f));
                ++kept;
            }
        }
    }
    // The step must have uncovered some of the wall and kept most of it.
    CHECK(dropped >= 10);
    CHECK(kept > w * h / 2);
    CHECK(stats.reused + stats.dropped == w * h);
    CHECK(stats.background == 0);
    // The frame keeps each pixel's depth slope for the next frame's taps;
    // beside the box's edges they are not zero.
    REQUIRE(next.depth_slopes.size() == static_cast<std::size_t>(w) * h);
    int sloped = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float slope = next.depth_slopes[static_cast<std::size_t>(y) * w + x];
            CAPTURE(x, y);
            REQUIRE(slope == kernel::temporal_depth_slope(next.guides.data(), w, h, x, y));
            sloped += slope > 0.0f ? 1 : 0;
        }
    }
    CHECK(sloped > 0);
    // And the taps read them: with every slope huge, any depth matches, and
    // the wall the box hid takes the box's history.
    TemporalFrame loose = history;
    std::fill(loose.depth_slopes.begin(), loose.depth_slopes.end(), 1e6f);
    TemporalStats loose_stats;
    temporal_blend(loose, flat_image(w, h, green), 1.0f, after.camera, after.guides,
                   TemporalSettings(), &loose_stats);
    CAPTURE(stats.reused, loose_stats.reused);
    CHECK(loose_stats.reused >= stats.reused + dropped / 2);
}

TEST_CASE("an orthographic view keeps its history across a sideways step", "[temporal]") {
    // Looking at the wall and box without perspective, 1 m high, pixels
    // 1/48 m; a step of 4 pixels to the right. Each wall point seen
    // before is seen again 4 pixels to the left; the box hides the same
    // wall as before, so what the step uncovers is only the view's new
    // right edge.
    Scene scene = wall_and_box();
    scene.camera.projection = Projection::orthographic;
    scene.camera.view_height = 1.0f;
    const PackedScene packed = pack_scene(scene);
    const int w = scene.render.width;
    const int h = scene.render.height;
    const View before = view_of(packed, scene.camera, w, h);
    Camera moved = scene.camera;
    // The camera looks along +z with y up: image right is -x.
    moved.position.x = -4.0f / h;
    const View after = view_of(packed, moved, w, h);
    // A history that tells its columns apart: red scaled by the column.
    Image previous = flat_image(w, h, red);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            previous.pixels[static_cast<std::size_t>(y) * w + x] *= (x + 1.0f) / w;
        }
    }
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), previous, 8.0f, before.camera, before.guides);
    TemporalStats stats;
    const TemporalFrame next = temporal_blend(history, flat_image(w, h, green), 1.0f, after.camera,
                                              after.guides, TemporalSettings(), &stats);
    const auto depth = [&](int x, int y) {
        return after.guides.depth[static_cast<std::size_t>(y) * w + x];
    };
    int checked = 0;
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 5 < w; ++x) {
            // Left out: the columns new to the view, and the pixels beside
            // the box's outline, whose taps may straddle it.
            const float d = depth(x, y);
            if (std::fabs(depth(x - 1, y) - d) > 1e-3f || std::fabs(depth(x + 1, y) - d) > 1e-3f ||
                std::fabs(depth(x, y - 1) - d) > 1e-3f || std::fabs(depth(x, y + 1) - d) > 1e-3f) {
                continue;
            }
            const kernel::TemporalPixel& out = next.pixels[static_cast<std::size_t>(y) * w + x];
            CAPTURE(x, y, d, out.value.x, out.value.w);
            // Pixel x + 4 of the history, (x + 5) / w red, over 8 + 1 samples.
            REQUIRE(out.value.w == Approx(9.0f));
            REQUIRE(out.value.x == Approx(8.0f / 9.0f * (x + 5.0f) / w).epsilon(1e-4));
            ++checked;
        }
    }
    CHECK(checked > w * h * 7 / 10);
    CHECK(stats.reused > w * h * 8 / 10);
}

TEST_CASE("a half turn leaves nothing to reuse", "[temporal]") {
    // The wall and box, and a second wall behind the camera at z = -3.
    Scene scene = wall_and_box();
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(half_pi, 0.0f, 0.0f),
                                      glm::vec2(100.0f), 0));
    const PackedScene packed = pack_scene(scene);
    const View v = view_of(packed, scene.camera, 20, 15);
    const View back = view_of(packed, turn_camera(scene.camera, 3.1415927f, 0.0f), 20, 15);
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(20, 15, red), 8.0f, v.camera, v.guides);
    TemporalStats stats;
    const TemporalFrame next = temporal_blend(history, flat_image(20, 15, green), 1.0f, back.camera,
                                              back.guides, TemporalSettings(), &stats);
    CHECK(stats.reused == 0);
    CHECK(stats.dropped == 20 * 15);
    for (const kernel::TemporalPixel& p : next.pixels) {
        REQUIRE(p.value.y == 1.0f);
    }
}

TEST_CASE("pixels that see nothing carry nothing over", "[temporal]") {
    // The wall alone, seen from so close to its edge that half the view
    // is background: the wall on the left (x > 0, as the camera looks
    // along +z), the background on the right.
    Scene scene = wall_and_box();
    scene.shapes = {make_plane(glm::vec3(50.0f, 0.0f, 2.0f), glm::vec3(-half_pi, 0.0f, 0.0f),
                               glm::vec2(100.0f), 0)};
    const PackedScene packed = pack_scene(scene);
    const View v = view_of(packed, scene.camera, 20, 15);
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(20, 15, red), 8.0f, v.camera, v.guides);
    TemporalStats stats;
    const TemporalFrame next = temporal_blend(history, flat_image(20, 15, green), 1.0f, v.camera,
                                              v.guides, TemporalSettings(), &stats);
    CHECK(stats.background == 20 * 15 / 2);
    CHECK(stats.reused == 20 * 15 / 2);
    for (int y = 0; y < 15; ++y) {
        for (int x = 10; x < 20; ++x) {
            REQUIRE(next.pixels[static_cast<std::size_t>(y) * 20 + x].value.y == 1.0f);
        }
    }
}

TEST_CASE("temporal_blend refuses an image of another size", "[temporal]") {
    const Scene scene = builtin_scene();
    const PackedScene packed = pack_scene(scene);
    const View v = view_of(packed, scene.camera, 20, 15);
    CHECK_THROWS_AS(
        temporal_blend(TemporalFrame(), flat_image(10, 15, red), 1.0f, v.camera, v.guides),
        std::invalid_argument);
    // So does a history whose depth slopes are missing.
    TemporalFrame history =
        temporal_blend(TemporalFrame(), flat_image(20, 15, red), 1.0f, v.camera, v.guides);
    history.depth_slopes.clear();
    CHECK_THROWS_WITH(temporal_blend(history, flat_image(20, 15, red), 1.0f, v.camera, v.guides),
                      Catch::Contains("depth slopes"));
}

TEST_CASE("a frame blended into kept storage is the frame made anew", "[temporal]") {
    // As the window blends: into the frame before last, of this size or of
    // another (a resized window), whose old values must all be overwritten.
    const Scene scene = wall_and_box();
    const PackedScene packed = pack_scene(scene);
    const View before = view_of(packed, scene.camera, 64, 48);
    Camera moved = scene.camera;
    moved.position.x = -0.05f;
    const View after = view_of(packed, moved, 64, 48);
    Image previous = flat_image(64, 48, red);
    for (std::size_t i = 0; i < previous.pixels.size(); ++i) {
        previous.pixels[i] *= static_cast<float>(i % 7 + 1);
    }
    const TemporalFrame history =
        temporal_blend(TemporalFrame(), previous, 4.0f, before.camera, before.guides);
    TemporalStats fresh_stats;
    const TemporalFrame fresh =
        temporal_blend(history, flat_image(64, 48, green), 1.0f, after.camera, after.guides,
                       TemporalSettings(), &fresh_stats);
    // Kept frames of other views, turned: their guides differ from the
    // new ones everywhere (the wall's depth across the view).
    const Camera turned = turn_camera(scene.camera, 0.4f, 0.2f);
    const View other = view_of(packed, turned, 64, 48);
    const View small = view_of(packed, turned, 20, 15);
    const TemporalFrame same_size = temporal_blend(
        TemporalFrame(), flat_image(64, 48, green * 9.0f), 2.0f, other.camera, other.guides);
    const TemporalFrame other_size =
        temporal_blend(TemporalFrame(), flat_image(20, 15, red), 2.0f, small.camera, small.guides);
    for (TemporalFrame kept : {same_size, other_size}) {
        TemporalStats stats;
        temporal_blend(history, flat_image(64, 48, green), 1.0f, after.camera, after.guides, &kept,
                       TemporalSettings(), &stats);
        CHECK(std::memcmp(&kept.camera, &fresh.camera, sizeof fresh.camera) == 0);
        REQUIRE(kept.pixels.size() == fresh.pixels.size());
        REQUIRE(kept.guides.size() == fresh.guides.size());
        REQUIRE(kept.depth_slopes.size() == fresh.depth_slopes.size());
        CHECK(std::memcmp(kept.pixels.data(), fresh.pixels.data(),
                          fresh.pixels.size() * sizeof fresh.pixels[0]) == 0);
        CHECK(std::memcmp(kept.guides.data(), fresh.guides.data(),
                          fresh.guides.size() * sizeof fresh.guides[0]) == 0);
        CHECK(std::memcmp(kept.depth_slopes.data(), fresh.depth_slopes.data(),
                          fresh.depth_slopes.size() * sizeof fresh.depth_slopes[0]) == 0);
        CHECK(stats.reused == fresh_stats.reused);
        CHECK(stats.dropped == fresh_stats.dropped);
        CHECK(stats.background == fresh_stats.background);
    }
    // The history reused and dropped some pixels: the comparison above
    // covers both kinds.
    CHECK(fresh_stats.reused > 0);
    CHECK(fresh_stats.dropped > 0);
    // The result cannot be written over the history it reads.
    TemporalFrame self = history;
    CHECK_THROWS_WITH(
        temporal_blend(self, flat_image(64, 48, green), 1.0f, after.camera, after.guides, &self),
        Catch::Contains("other than the history"));
    CHECK_THROWS_WITH(temporal_blend(history, flat_image(64, 48, green), 1.0f, after.camera,
                                     after.guides, nullptr),
                      Catch::Contains("other than the history"));
}
