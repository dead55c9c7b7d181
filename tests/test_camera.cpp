// The cameras: make_camera_record's frame and extents, and the kernel's
// camera_ray (true vertical field of view, orientation, aspect; an
// orthographic camera's parallel rays).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "trac0r/camera.h"
#include "trac0r/kernel/trace.h"

using namespace trac0r;
using kernel::camera_ray;
using kernel::CameraRecord;
using kernel::Ray;

namespace {

const double pi = 3.14159265358979323846;

// Angles from float directions: each component carries ~1e-7 relative
// rounding, which moves an angle by ~1e-7 rad; 1e-5 rad (0.0006 degrees) is
// far below any real mistake (half a pixel at 800 x 600 is ~1e-3 rad).
const double angle_tolerance = 1e-5;

double dot_d(glm::vec3 a, glm::vec3 b) {
    return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y +
           static_cast<double>(a.z) * b.z;
}

glm::vec3 v3(glm::vec4 v) { return glm::vec3(v); }

// The ray's angle above the forward axis in the forward/up plane, and to the
// right of it in the forward/right plane.
double vertical_angle(const CameraRecord& cam, glm::vec3 d) {
    return std::atan2(dot_d(d, v3(cam.up)), dot_d(d, v3(cam.forward)));
}
double horizontal_angle(const CameraRecord& cam, glm::vec3 d) {
    return std::atan2(dot_d(d, v3(cam.right)), dot_d(d, v3(cam.forward)));
}

Camera tilted_camera() {
    Camera c;
    c.position = glm::vec3(1.0f, -2.0f, 3.0f);
    c.direction = glm::vec3(0.3f, -0.2f, 1.0f);
    c.world_up = glm::vec3(0.0f, 1.0f, 0.0f);
    c.vertical_fov = 60.0f;
    return c;
}

}  // namespace

TEST_CASE("make_camera_record builds an orthonormal frame from the camera", "[kernel][camera]") {
    const Camera c = tilted_camera();
    const CameraRecord cam = make_camera_record(c, 800, 600);
    const glm::vec3 forward = glm::normalize(c.direction);
    const glm::vec3 right = glm::normalize(glm::cross(c.direction, c.world_up));
    CHECK(glm::length(v3(cam.forward) - forward) < 1e-6f);
    CHECK(glm::length(v3(cam.right) - right) < 1e-6f);
    CHECK(std::fabs(glm::dot(v3(cam.up), v3(cam.forward))) < 1e-6f);
    CHECK(std::fabs(glm::dot(v3(cam.up), v3(cam.right))) < 1e-6f);
    CHECK(std::fabs(glm::length(v3(cam.up)) - 1.0f) < 1e-6f);
    CHECK(glm::dot(v3(cam.up), c.world_up) > 0.0f);  // not upside down
    CHECK(v3(cam.position) == c.position);
    CHECK(cam.size.x == 800u);
    CHECK(cam.size.y == 600u);
}

TEST_CASE("camera_ray: the centre ray is the view direction", "[kernel][camera]") {
    const Camera cameras[] = {Camera(), tilted_camera()};
    for (const Camera& c : cameras) {
        const CameraRecord cam = make_camera_record(c, 800, 600);
        const Ray centre = camera_ray(cam, 400.0f, 300.0f, 0.0f, 0.0f);
        CHECK(glm::length(centre.direction - glm::normalize(c.direction)) < 1e-6f);
        CHECK(centre.origin == c.position);
        // The same point reached as pixel (399, 299) with jitter (1, 1).
        const Ray jittered = camera_ray(cam, 399.0f, 299.0f, 1.0f, 1.0f);
        CHECK(glm::length(jittered.direction - centre.direction) < 1e-6f);
    }
}

TEST_CASE("camera_ray: vertical_fov is the true angle between top and bottom edges",
          "[kernel][camera]") {
    const float fovs[] = {30.0f, 53.13f, 90.0f, 120.0f};
    for (float fov : fovs) {
        INFO("vertical_fov " << fov);
        Camera c = tilted_camera();
        c.vertical_fov = fov;
        const int w = 640;
        const int h = 480;
        const CameraRecord cam = make_camera_record(c, w, h);
        const double half = 0.5 * fov * pi / 180.0;
        // Middle of the top and bottom edges: exactly vfov/2 off the axis.
        const glm::vec3 top = camera_ray(cam, w / 2.0f, 0.0f, 0.0f, 0.0f).direction;
        const glm::vec3 bottom =
            camera_ray(cam, w / 2.0f, static_cast<float>(h), 0.0f, 0.0f).direction;
        CHECK(std::acos(dot_d(top, v3(cam.forward))) == Approx(half).margin(angle_tolerance));
        CHECK(std::acos(dot_d(bottom, v3(cam.forward))) == Approx(half).margin(angle_tolerance));
        CHECK(vertical_angle(cam, top) == Approx(half).margin(angle_tolerance));
        CHECK(vertical_angle(cam, bottom) == Approx(-half).margin(angle_tolerance));
        // The corners: (0, 0) with zero jitter is the top-left corner,
        // (W, H) the bottom-right. Their vertical angle is also +-vfov/2,
        // their horizontal one +-hfov/2 with tan(hfov/2) = aspect tan(vfov/2).
        const double half_horizontal = std::atan(std::tan(half) * w / h);
        const glm::vec3 top_left = camera_ray(cam, 0.0f, 0.0f, 0.0f, 0.0f).direction;
        const glm::vec3 bottom_right =
            camera_ray(cam, static_cast<float>(w), static_cast<float>(h), 0.0f, 0.0f).direction;
        CHECK(vertical_angle(cam, top_left) == Approx(half).margin(angle_tolerance));
        CHECK(horizontal_angle(cam, top_left) == Approx(-half_horizontal).margin(angle_tolerance));
        CHECK(vertical_angle(cam, bottom_right) == Approx(-half).margin(angle_tolerance));
        CHECK(horizontal_angle(cam, bottom_right) ==
              Approx(half_horizontal).margin(angle_tolerance));
    }
}

TEST_CASE("camera_ray: image right is normalize(cross(direction, world_up)), row 0 on top",
          "[kernel][camera]") {
    // Right-handed, as glTF and Blender: the default camera looks along -z
    // with y up, and right is cross(-z, y) = +x.
    CHECK(Camera().direction == glm::vec3(0.0f, 0.0f, -1.0f));
    const CameraRecord cam = make_camera_record(Camera(), 800, 600);
    CHECK(glm::length(v3(cam.right) - glm::vec3(1, 0, 0)) < 1e-6f);
    const glm::vec3 right_edge = camera_ray(cam, 800.0f, 300.0f, 0.0f, 0.0f).direction;
    const glm::vec3 left_edge = camera_ray(cam, 0.0f, 300.0f, 0.0f, 0.0f).direction;
    CHECK(right_edge.x > 0.4f);
    CHECK(left_edge.x < -0.4f);
    CHECK(std::fabs(right_edge.y) < 1e-6f);
    // Row 0 is the top of the image: world up.
    const glm::vec3 first_row = camera_ray(cam, 400.0f, 0.5f, 0.0f, 0.0f).direction;
    const glm::vec3 last_row = camera_ray(cam, 400.0f, 599.5f, 0.0f, 0.0f).direction;
    CHECK(first_row.y > 0.4f);
    CHECK(last_row.y < -0.4f);
    // A general camera: the right edge leans towards cross(direction, world_up).
    const Camera c = tilted_camera();
    const CameraRecord tilted = make_camera_record(c, 800, 600);
    const glm::vec3 expected_right = glm::normalize(glm::cross(c.direction, c.world_up));
    const glm::vec3 r = camera_ray(tilted, 800.0f, 300.0f, 0.0f, 0.0f).direction;
    const glm::vec3 l = camera_ray(tilted, 0.0f, 300.0f, 0.0f, 0.0f).direction;
    CHECK(glm::dot(r - l, expected_right) > 0.5f);
    CHECK(std::fabs(glm::dot(r - l, v3(tilted.up))) < 1e-6f);
}

TEST_CASE("camera_ray: pixels are square for any aspect ratio", "[kernel][camera]") {
    const int sizes[][2] = {{800, 600}, {800, 400}, {300, 900}, {1, 1}};
    for (const auto& size : sizes) {
        const int w = size[0];
        const int h = size[1];
        INFO(w << " x " << h);
        Camera c;
        c.vertical_fov = 70.0f;
        const CameraRecord cam = make_camera_record(c, w, h);
        CHECK(cam.extent.x / cam.extent.y == Approx(static_cast<double>(w) / h).epsilon(1e-6));
        // One pixel step right and one step down, from the centre, move the
        // image-plane point (at distance one) by the same length.
        auto plane_point = [&](float x, float y) {
            const glm::vec3 d = camera_ray(cam, x, y, 0.0f, 0.0f).direction;
            return d / static_cast<float>(dot_d(d, v3(cam.forward)));
        };
        const glm::vec3 centre = plane_point(w / 2.0f, h / 2.0f);
        const float step_right = glm::length(plane_point(w / 2.0f + 1.0f, h / 2.0f) - centre);
        const float step_down = glm::length(plane_point(w / 2.0f, h / 2.0f + 1.0f) - centre);
        // Differences of nearby float points: relative error ~1e-7 / step.
        CHECK(step_right == Approx(step_down).epsilon(1e-4));
        const double half_horizontal = std::atan(std::tan(35.0 * pi / 180.0) * w / h);
        const glm::vec3 right_edge =
            camera_ray(cam, static_cast<float>(w), h / 2.0f, 0.0f, 0.0f).direction;
        CHECK(horizontal_angle(cam, right_edge) == Approx(half_horizontal).margin(angle_tolerance));
    }
}

TEST_CASE("camera_problem names the mistakes; make_camera_record refuses them",
          "[kernel][camera]") {
    CHECK(camera_problem(Camera()) == nullptr);
    CHECK(camera_problem(tilted_camera()) == nullptr);

    auto problem = [](Camera c) {
        const char* p = camera_problem(c);
        return std::string(p ? p : "");
    };
    Camera parallel;
    parallel.direction = glm::vec3(0.0f, 2.0f, 0.0f);
    CHECK(problem(parallel).find("parallel") != std::string::npos);
    Camera antiparallel;
    antiparallel.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    CHECK(problem(antiparallel).find("parallel") != std::string::npos);

    const float bad_fovs[] = {0.0f,
                              -10.0f,
                              180.0f,
                              200.0f,
                              std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::infinity()};
    for (float fov : bad_fovs) {
        INFO("vertical_fov " << fov);
        Camera c;
        c.vertical_fov = fov;
        CHECK(problem(c).find("vertical_fov") != std::string::npos);
        CHECK_THROWS_AS(make_camera_record(c, 800, 600), std::invalid_argument);
    }
    Camera narrow;
    narrow.vertical_fov = 0.5f;
    CHECK(camera_problem(narrow) == nullptr);
    Camera wide;
    wide.vertical_fov = 179.0f;
    CHECK(camera_problem(wide) == nullptr);

    Camera zero_direction;
    zero_direction.direction = glm::vec3(0.0f);
    CHECK_FALSE(problem(zero_direction).empty());
    Camera nan_position;
    nan_position.position.x = std::numeric_limits<float>::quiet_NaN();
    CHECK_FALSE(problem(nan_position).empty());

    CHECK_THROWS_AS(make_camera_record(parallel, 800, 600), std::invalid_argument);
    CHECK_THROWS_AS(make_camera_record(Camera(), 0, 600), std::invalid_argument);
    CHECK_THROWS_AS(make_camera_record(Camera(), 800, -1), std::invalid_argument);
}

// Issue 33, point 7: a camera vector near float's largest was reported as
// "parallel to world_up" (its length overflowed), and one that passed would
// normalise to NaN. Only the direction of these vectors counts.
TEST_CASE("huge camera vectors are directions like any other", "[kernel][camera]") {
    Camera huge;
    huge.direction = glm::vec3(3e38f, 3e38f, 3e38f);
    huge.world_up = glm::vec3(0.0f, 3e38f, 0.0f);
    CHECK(camera_problem(huge) == nullptr);
    Camera unit = huge;
    unit.direction = glm::vec3(1.0f, 1.0f, 1.0f);
    unit.world_up = glm::vec3(0.0f, 1.0f, 0.0f);
    const kernel::CameraRecord a = make_camera_record(huge, 80, 60);
    const kernel::CameraRecord b = make_camera_record(unit, 80, 60);
    for (int i = 0; i < 3; ++i) {
        CHECK(a.forward[i] == Approx(b.forward[i]).margin(1e-6));
        CHECK(a.right[i] == Approx(b.right[i]).margin(1e-6));
        CHECK(a.up[i] == Approx(b.up[i]).margin(1e-6));
    }
    Camera huge_parallel = huge;
    huge_parallel.direction = glm::vec3(0.0f, -3e38f, 0.0f);
    CHECK(std::string(camera_problem(huge_parallel)).find("parallel") != std::string::npos);
}

TEST_CASE("an orthographic camera's rays are parallel, from a view_height-high rectangle",
          "[kernel][camera]") {
    Camera c = tilted_camera();
    c.projection = Projection::orthographic;
    c.view_height = 3.0f;
    const int w = 640;
    const int h = 480;
    const CameraRecord cam = make_camera_record(c, w, h);
    const glm::vec3 forward = glm::normalize(c.direction);
    // Where a ray starts, in the camera's frame: right, up, forward.
    auto start = [&](const Ray& r) {
        const glm::vec3 o = r.origin - c.position;
        return glm::vec3(dot_d(o, v3(cam.right)), dot_d(o, v3(cam.up)), dot_d(o, v3(cam.forward)));
    };
    // Float positions of a few metres: 1e-5 m is ~100 ulps, far below a
    // pixel (3 / 480 m).
    const float length_tolerance = 1e-5f;
    const float xs[] = {0.0f, 17.25f, 320.0f, 639.5f, 640.0f};
    const float ys[] = {0.0f, 123.75f, 240.0f, 479.5f, 480.0f};
    for (float x : xs) {
        for (float y : ys) {
            CAPTURE(x, y);
            const Ray r = camera_ray(cam, x, y, 0.0f, 0.0f);
            CHECK(glm::length(r.direction - forward) < 1e-6f);
            // Square pixels 3 / 480 m on a side, (0, 0) the top-left
            // corner, the view centred on the camera's position.
            const glm::vec3 s = start(r);
            CHECK(s.x == Approx((x - w / 2.0f) * 3.0f / h).margin(length_tolerance));
            CHECK(s.y == Approx((h / 2.0f - y) * 3.0f / h).margin(length_tolerance));
            CHECK(s.z == Approx(0.0f).margin(length_tolerance));
        }
    }
    // A thin lens focuses each parallel ray: the lens ray from any point of
    // the aperture meets the pinhole ray at the focus distance.
    c.aperture_radius = 0.1f;
    c.focus_distance = 2.5f;
    const CameraRecord lens = make_camera_record(c, w, h);
    const Ray axis = camera_ray(lens, 100.0f, 50.0f, 0.5f, 0.5f);
    for (float u : {0.0f, 0.3f, 0.9f}) {
        const Ray r = kernel::camera_lens_ray(lens, 100.0f, 50.0f, 0.5f, 0.5f, glm::vec2(u, 0.7f));
        const glm::vec3 focus = axis.origin + 2.5f * axis.direction;
        const float t = dot_d(focus - r.origin, r.direction);
        CHECK(glm::length(r.origin + t * r.direction - focus) < length_tolerance);
        CHECK(glm::length(r.origin - axis.origin) <= 0.1f + length_tolerance);
    }
}

TEST_CASE("camera_problem refuses an orthographic view_height that is not a length",
          "[kernel][camera]") {
    const float bad[] = {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(),
                         std::numeric_limits<float>::infinity()};
    for (float height : bad) {
        INFO("view_height " << height);
        Camera c;
        c.projection = Projection::orthographic;
        c.view_height = height;
        CHECK(std::string(camera_problem(c) ? camera_problem(c) : "").find("view_height") !=
              std::string::npos);
        CHECK_THROWS_AS(make_camera_record(c, 80, 60), std::invalid_argument);
    }
    Camera ortho;
    ortho.projection = Projection::orthographic;
    ortho.view_height = 1e-4f;
    CHECK(camera_problem(ortho) == nullptr);
    // camera_block_json writes the projection's own keys.
    ortho.view_height = 0.75f;
    const std::string block = camera_block_json(ortho, glm::dvec3(0.0));
    CHECK(block.find("\"projection\": \"orthographic\", \"view_height\": 0.75") !=
          std::string::npos);
    CHECK(block.find("vertical_fov") == std::string::npos);
    CHECK(camera_block_json(Camera(), glm::dvec3(0.0)).find("projection") == std::string::npos);
}
