// Extreme cameras (issue 5, docs/stability.md): inside a closed emissive
// mesh or a closed box, looking straight along world up, and fields of view
// at and beyond (0, 180).
#include <catch2/catch.hpp>

#include "stability_support.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

using namespace trac0r;
using namespace trac0r::stability;

TEST_CASE("a camera inside a closed emissive mesh sees it in every pixel, flat and BVH",
          "[stability][camera]") {
    // Max depth 1: a pixel is the lamp's radiance where its ray hits and
    // black where it leaks through a crack. Every pixel must be exactly le.
    Scene scene;
    scene.materials.push_back(make_material(MaterialType::emissive, glm::vec3(1.0f), 3.0f));
    scene.shapes.push_back(
        make_icosphere(glm::vec3(0.3f, -0.1f, 0.2f), glm::vec3(0.5f, -0.3f, 1.2f), 2.0f, 3, 0));
    set_view(scene, glm::vec3(0.45f, 0.2f, -0.3f), glm::vec3(0.3f, 0.5f, 1.0f), 150.0f, 32, 1);
    for (Accel accel : {Accel::flat, Accel::bvh}) {
        CAPTURE(to_string(accel));
        std::unique_ptr<Renderer> r = render(scene, 4, 1, accel);
        for (const glm::vec3& p : r->image().pixels) {
            REQUIRE(p == glm::vec3(3.0f));
        }
    }
}

TEST_CASE("a camera inside a closed box without a lamp sees black, at the origin and at 1e5",
          "[stability][camera]") {
    // The room's block, lifted 1/8 off the floor, is closed; from inside
    // it, light could only arrive through a crack or by a continuation ray
    // offset out through a wall or an edge (at 1e5 a hit point's rounding
    // can put it on the neighbouring face's plane: hit_position moves it
    // into its triangle). Not resting on the floor: there the block's
    // bottom and the floor share a plane, and within a float of their
    // common edge no renderer can tell which of the two a ray hit.
    for (float offset : {0.0f, 1e5f}) {
        CAPTURE(offset);
        Scene scene = room(1.0f, glm::vec3(offset));
        const glm::vec3 block_centre = glm::vec3(offset) + glm::vec3(0.25f, -0.5f, 0.25f);
        scene.shapes[2] = make_box(block_centre, glm::vec3(0.0f), glm::vec3(0.75f), 2);
        scene.camera.position = block_centre;
        scene.camera.vertical_fov = 120.0f;
        std::unique_ptr<Renderer> r = render(scene, 8);
        for (const glm::vec3& p : r->image().pixels) {
            REQUIRE(p == glm::vec3(0.0f));
        }
        CHECK(r->stats().samples_dropped == 0);
    }
}

TEST_CASE("looking straight along world up is refused; the renderer keeps its camera",
          "[stability][camera]") {
    // camera_problem's message is tested in test_camera.cpp and the scene
    // loader's in test_scene_loader.cpp; here what a viewer that turns the
    // camera straight up gets: an exception, and a renderer that goes on
    // with the camera it had.
    Scene scene = room(1.0f, glm::vec3(0.0f));
    Renderer r(scene, cpu(), 1);
    r.render_frame();
    const Image before = r.image();
    Camera up = scene.camera;
    for (const glm::vec3& d : {glm::vec3(0, 1, 0), glm::vec3(0, -3, 0), glm::vec3(1e-7f, 1, 0)}) {
        up.direction = d;
        CHECK_THROWS_AS(r.set_camera(up), std::invalid_argument);
    }
    CHECK(r.scene().camera.direction == scene.camera.direction);
    CHECK(r.frames() == 1);
    CHECK(r.image().pixels == before.pixels);
    SECTION("just off world up the frame is well defined and the image finite") {
        for (float angle : {1e-2f, 1e-4f, 2e-6f}) {
            CAPTURE(angle);
            up.direction = glm::vec3(std::sin(angle), std::cos(angle), 0.0f);
            const kernel::CameraRecord cam = make_camera_record(up, 16, 16);
            const glm::vec3 f(cam.forward), x(cam.right), y(cam.up);
            CHECK(std::fabs(glm::length(x) - 1.0f) < 1e-6f);
            CHECK(std::fabs(glm::length(y) - 1.0f) < 1e-6f);
            CHECK(std::fabs(glm::dot(f, x)) < 1e-6f);
            CHECK(std::fabs(glm::dot(f, y)) < 1e-6f);
            CHECK(std::fabs(glm::dot(x, y)) < 1e-6f);
            r.set_camera(up);
            r.render_frame();
            CHECK(non_finite_pixels(r.image()) == 0);
            CHECK(r.stats().samples_dropped == 0);
        }
    }
}

TEST_CASE(
    "fields of view: outside (0, 180) is an error naming the file and field; the "
    "extremes inside render finite images",
    "[stability][camera]") {
    auto scene_text = [](const std::string& fov) {
        return R"({"camera": {"position": [0, 0, -0.5], "vertical_fov": )" + fov +
               R"(}, "render": {"width": 16, "height": 16, "max_depth": 4},
               "materials": {"white": {"type": "diffuse", "color": [0.7, 0.7, 0.7],
                                       "emittance": 1}},
               "shapes": [{"type": "box", "size": [2, 2, 2], "material": "white"}]})";
    };
    // 1e-50 and 179.9999999 round to 0 and 180 as floats.
    for (const char* bad : {"0", "-1", "180", "1000", "1e-50", "179.9999999"}) {
        CAPTURE(bad);
        REQUIRE_THROWS_WITH(parse_scene(scene_text(bad), "fov.json", ""),
                            Catch::StartsWith("fov.json: /camera/vertical_fov: expected a number "
                                              "of degrees in (0, 180), got "));
    }
    // The smallest accepted values make every ray the view direction; the
    // largest make rays graze the image plane. A furnace-like box whose
    // walls emit colour x emittance = 0.7 and reflect 0.7, the camera inside:
    // every path's first vertex emits 0.7, and no path carries more than
    // one that survives all 4 vertices, each dividing its throughput by
    // the roulette's continuation probability. Every pixel lies in between.
    const float emitted = 0.7f;
    const float albedo = 0.7f;
    const int max_depth = 4;
    double largest = 0.0;
    glm::vec3 throughput(1.0f);
    for (int depth = 0; depth < max_depth; ++depth) {
        largest += emitted * throughput.x;
        throughput *= albedo / kernel::continuation_probability(depth, max_depth, throughput);
    }
    for (const char* fov : {"1e-30", "1e-3", "179.99", "179.9999"}) {
        CAPTURE(fov);
        const Scene scene = parse_scene(scene_text(fov), "fov.json", "");
        std::unique_ptr<Renderer> r = render(scene, 2);
        for (const glm::vec3& p : r->image().pixels) {
            REQUIRE(finite(p));
            REQUIRE(p.x >= emitted);
            REQUIRE(p.x <= largest * (1.0 + 1e-6));  // float rounding of the path's sum
        }
        CHECK(r->stats().samples_dropped == 0);
    }
}
