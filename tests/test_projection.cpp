// Projecting points and AABB wireframes onto the image (the viewer's F1
// overlay): the inverse of the kernel's camera_ray, near-plane clipping of
// boxes partly behind the camera, and clipping to the image rectangle.
#include <catch2/catch.hpp>

#include "trac0r/camera.h"
#include "trac0r/fly_camera.h"
#include "trac0r/kernel/trace.h"
#include "trac0r/projection.h"

#include <cmath>

using namespace trac0r;

namespace {

// Image positions of float computations that pass through a division by
// depth and a scale by ~400 pixels: 1e-3 pixel is ~100 float ulps there,
// and far below anything visible (a mistake moves lines by whole pixels).
const float pixel_tolerance = 1e-3f;

kernel::CameraRecord record_at(glm::vec3 position, glm::vec3 direction, int width = 800,
                               int height = 600) {
    Camera c;
    c.position = position;
    c.direction = direction;
    c.vertical_fov = 60.0f;
    return make_camera_record(c, width, height);
}

AABB box(glm::vec3 min, glm::vec3 max) {
    AABB b;
    b.min = min;
    b.max = max;
    return b;
}

bool inside_image(glm::vec2 p, float width, float height) {
    const float slack = pixel_tolerance;
    return p.x >= -slack && p.x <= width + slack && p.y >= -slack && p.y <= height + slack;
}

}  // namespace

TEST_CASE("project_point inverts camera_ray", "[projection]") {
    const kernel::CameraRecord cam =
        record_at(glm::vec3(0.3f, 0.2f, -1.0f), glm::vec3(0.2f, -0.1f, 1.0f));
    // Pixel (x + jitter) of a ray, 2.5 units along it, projects back to it.
    const float xs[] = {0.0f, 17.25f, 400.0f, 799.5f};
    const float ys[] = {0.0f, 123.75f, 300.0f, 599.5f};
    for (float x : xs) {
        for (float y : ys) {
            const kernel::Ray ray = kernel::camera_ray(cam, x, y, 0.25f, 0.5f);
            const glm::vec3 point = glm::vec3(ray.origin) + 2.5f * glm::vec3(ray.direction);
            glm::vec2 image;
            REQUIRE(project_point(cam, point, 1e-3f, &image));
            CHECK(image.x == Approx(x + 0.25f).margin(pixel_tolerance));
            CHECK(image.y == Approx(y + 0.5f).margin(pixel_tolerance));
        }
    }
}

TEST_CASE("project_point inverts an orthographic camera_ray", "[projection]") {
    Camera c;
    c.position = glm::vec3(0.3f, 0.2f, -1.0f);
    c.direction = glm::vec3(0.2f, -0.1f, 1.0f);
    c.projection = Projection::orthographic;
    c.view_height = 1.5f;
    const kernel::CameraRecord cam = make_camera_record(c, 800, 600);
    const float xs[] = {0.0f, 17.25f, 400.0f, 799.5f};
    const float ys[] = {0.0f, 123.75f, 300.0f, 599.5f};
    for (float x : xs) {
        for (float y : ys) {
            const kernel::Ray ray = kernel::camera_ray(cam, x, y, 0.25f, 0.5f);
            // Near and far along the ray: the same place in the image.
            for (float t : {0.5f, 4.0f}) {
                const glm::vec3 point = glm::vec3(ray.origin) + t * glm::vec3(ray.direction);
                glm::vec2 image;
                REQUIRE(project_point(cam, point, 1e-3f, &image));
                CHECK(image.x == Approx(x + 0.25f).margin(pixel_tolerance));
                CHECK(image.y == Approx(y + 0.5f).margin(pixel_tolerance));
            }
        }
    }
}

TEST_CASE("project_point refuses points behind or too near the camera", "[projection]") {
    // Looking along -z with y up: +x is right (right-handed).
    const kernel::CameraRecord cam = record_at(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    glm::vec2 image(-7.0f);
    CHECK_FALSE(project_point(cam, glm::vec3(0.1f, 0.0f, 1.0f), 0.01f, &image));
    CHECK_FALSE(project_point(cam, glm::vec3(0.0f, 0.0f, -0.005f), 0.01f, &image));
    CHECK(image == glm::vec2(-7.0f));  // left alone
    REQUIRE(project_point(cam, glm::vec3(0.0f, 0.0f, -0.02f), 0.01f, &image));
    CHECK(image.x == Approx(400.0f));  // the centre of the image
    CHECK(image.y == Approx(300.0f));
    // Right of the camera is right in the image, up is up (smaller y).
    REQUIRE(project_point(cam, glm::vec3(0.1f, 0.1f, -1.0f), 0.01f, &image));
    CHECK(image.x > 400.0f);
    CHECK(image.y < 300.0f);
}

TEST_CASE("clip_segment_to_image (Liang-Barsky)", "[projection]") {
    Segment2 inside{{10.0f, 20.0f}, {30.0f, 40.0f}};
    REQUIRE(clip_segment_to_image(&inside, 100.0f, 50.0f));
    CHECK(inside.a == glm::vec2(10.0f, 20.0f));
    CHECK(inside.b == glm::vec2(30.0f, 40.0f));

    // Across the whole image, left to right at y = 25: cut at both edges.
    Segment2 across{{-100.0f, 25.0f}, {300.0f, 25.0f}};
    REQUIRE(clip_segment_to_image(&across, 100.0f, 50.0f));
    CHECK(across.a.x == Approx(0.0f));
    CHECK(across.b.x == Approx(100.0f));
    CHECK(across.a.y == Approx(25.0f));

    // A diagonal entering through the top edge.
    Segment2 diagonal{{-10.0f, -10.0f}, {10.0f, 10.0f}};
    REQUIRE(clip_segment_to_image(&diagonal, 100.0f, 50.0f));
    CHECK(diagonal.a.x == Approx(0.0f).margin(1e-6));
    CHECK(diagonal.a.y == Approx(0.0f).margin(1e-6));
    CHECK(diagonal.b == glm::vec2(10.0f, 10.0f));

    Segment2 above{{-10.0f, -5.0f}, {200.0f, -1.0f}};
    CHECK_FALSE(clip_segment_to_image(&above, 100.0f, 50.0f));
    Segment2 past_corner{{90.0f, -20.0f}, {130.0f, 20.0f}};  // misses the top-right corner
    CHECK_FALSE(clip_segment_to_image(&past_corner, 100.0f, 50.0f));
    Segment2 vertical_outside{{-1.0f, 0.0f}, {-1.0f, 50.0f}};
    CHECK_FALSE(clip_segment_to_image(&vertical_outside, 100.0f, 50.0f));
}

TEST_CASE("a box wholly in front of the camera: 12 edges at the corners' projections",
          "[projection]") {
    const kernel::CameraRecord cam = record_at(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    const AABB b = box(glm::vec3(-0.2f, -0.1f, 2.0f), glm::vec3(0.1f, 0.2f, 3.0f));
    const std::vector<Segment2> segments = project_aabb_wireframe(cam, b, 0.01f);
    REQUIRE(segments.size() == 12);
    // Every segment end is a projected corner.
    for (const Segment2& s : segments) {
        for (glm::vec2 end : {s.a, s.b}) {
            bool is_corner = false;
            for (int i = 0; i < 8; ++i) {
                const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                       (i & 4) ? b.max.z : b.min.z);
                glm::vec2 p;
                REQUIRE(project_point(cam, corner, 0.01f, &p));
                is_corner = is_corner || glm::length(p - end) < pixel_tolerance;
            }
            CHECK(is_corner);
        }
    }
}

TEST_CASE("boxes behind the camera or outside the view draw nothing", "[projection]") {
    const kernel::CameraRecord cam = record_at(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    CHECK(project_aabb_wireframe(
              cam, box(glm::vec3(-1.0f, -1.0f, -3.0f), glm::vec3(1.0f, 1.0f, -2.0f)), 0.01f)
              .empty());
    // Far to the right, outside the 60-degree (vertical) view.
    CHECK(project_aabb_wireframe(
              cam, box(glm::vec3(50.0f, -0.1f, 1.0f), glm::vec3(51.0f, 0.1f, 2.0f)), 0.01f)
              .empty());
    CHECK(project_aabb_wireframe(cam, AABB(), 0.01f).empty());  // empty box
}

TEST_CASE(
    "a box partly behind the camera is clipped at the near plane, not drawn across "
    "the screen",
    "[projection]") {
    // A long, thin box along the view axis, from behind the camera to well
    // in front, below and left of the eye: a floor rail the camera stands
    // over. Projecting the corners behind the camera without clipping would
    // flip them (negative depth) to the upper right of the image.
    const kernel::CameraRecord cam = record_at(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    const AABB rail = box(glm::vec3(-0.3f, -0.3f, -5.0f), glm::vec3(-0.2f, -0.2f, 2.0f));
    const float near_distance = 0.01f;
    const std::vector<Segment2> segments = project_aabb_wireframe(cam, rail, near_distance);
    // The 4 edges along z are clipped and visible; the 4 edges of the far
    // end are visible; the 4 of the near end lie behind the camera.
    REQUIRE(segments.size() == 8);
    for (const Segment2& s : segments) {
        CHECK(inside_image(s.a, 800.0f, 600.0f));
        CHECK(inside_image(s.b, 800.0f, 600.0f));
        // Everything of the rail is left of and below the eye: the lower
        // left quadrant of the image, never the upper right.
        CHECK(s.a.x <= 400.0f + pixel_tolerance);
        CHECK(s.b.x <= 400.0f + pixel_tolerance);
        CHECK(s.a.y >= 300.0f - pixel_tolerance);
        CHECK(s.b.y >= 300.0f - pixel_tolerance);
    }
    // The clipped ends run off the image's bottom-left (the near plane is
    // close), so some segment reaches the image border there.
    bool reaches_border = false;
    for (const Segment2& s : segments) {
        for (glm::vec2 end : {s.a, s.b}) {
            reaches_border =
                reaches_border || end.x < pixel_tolerance || end.y > 600.0f - pixel_tolerance;
        }
    }
    CHECK(reaches_border);
}

TEST_CASE("a box around the camera: only the edges in front remain, inside the image",
          "[projection]") {
    // The camera inside a room-sized box, as in the Cornell box's walls.
    const kernel::CameraRecord cam =
        record_at(glm::vec3(0.0f, 0.3f, 0.0f), glm::vec3(0.3f, -0.2f, 1.0f));
    const AABB room = box(glm::vec3(-1.0f), glm::vec3(1.0f));
    const std::vector<Segment2> segments = project_aabb_wireframe(cam, room, 1e-3f);
    REQUIRE(!segments.empty());
    REQUIRE(segments.size() < 12);  // the edges behind are gone
    for (const Segment2& s : segments) {
        CHECK(inside_image(s.a, 800.0f, 600.0f));
        CHECK(inside_image(s.b, 800.0f, 600.0f));
        CHECK(std::isfinite(s.a.x + s.a.y + s.b.x + s.b.y));
    }
}

TEST_CASE(
    "fly camera: moves in the camera's frame, turns without reaching the pole, zooms "
    "within limits",
    "[projection]") {
    Camera c;
    c.position = glm::vec3(1.0f, 2.0f, 3.0f);
    c.direction = glm::vec3(1.0f, 0.0f, 0.0f);  // looking along +x, y up
    const Camera moved = move_camera(c, glm::vec3(0.5f, 0.25f, 2.0f));
    // Right is cross(forward, up) = cross(+x, +y) = +z.
    CHECK(moved.position.x == Approx(3.0f));
    CHECK(moved.position.y == Approx(2.25f));
    CHECK(moved.position.z == Approx(3.5f));
    CHECK(moved.direction == c.direction);

    // Yaw by 90 degrees to the right: now looking along the old right, +z.
    const Camera yawed = turn_camera(c, 0.5f * 3.14159265f, 0.0f);
    CHECK(yawed.direction.z == Approx(1.0f));
    CHECK(std::abs(yawed.direction.x) < 1e-6f);
    // Pitching far up stops short of world_up, so the camera stays valid.
    const Camera up = turn_camera(c, 0.0f, 10.0f);
    CHECK(camera_problem(up) == nullptr);
    CHECK(up.direction.y > 0.99f);
    CHECK(up.direction.y < 1.0f);
    const float angle_to_pole = std::acos(glm::dot(glm::normalize(up.direction), c.world_up));
    CHECK(angle_to_pole == Approx(fly_camera_min_pole_angle).margin(1e-4));
    // Turning further still stays there (no flip past the pole).
    const Camera further = turn_camera(up, 0.3f, 1.0f);
    CHECK(camera_problem(further) == nullptr);
    CHECK(further.direction.y == Approx(up.direction.y).margin(1e-4));

    CHECK(zoom_camera(c, 0.5f).vertical_fov == Approx(c.vertical_fov * 0.5f));
    CHECK(zoom_camera(c, 100.0f).vertical_fov == fly_camera_max_fov);
    CHECK(zoom_camera(c, 1e-4f).vertical_fov == fly_camera_min_fov);
    // An orthographic camera zooms its view's height, while that stays a
    // height camera_problem takes.
    Camera ortho = c;
    ortho.projection = Projection::orthographic;
    ortho.view_height = 2.0f;
    CHECK(zoom_camera(ortho, 0.5f).view_height == 1.0f);
    CHECK(zoom_camera(ortho, 0.5f).vertical_fov == c.vertical_fov);
    ortho.view_height = 1e30f;
    CHECK(zoom_camera(ortho, 10.0f).view_height == 1e30f);
}
