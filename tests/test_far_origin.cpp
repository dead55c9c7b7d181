// A scene far from the file's origin (issue 33, point 6): the loader makes
// every position relative to a local origin near the camera, in double
// (Scene::origin, local_origin), so a room moved 1e5, 1e6 or 1e7 away
// renders as at the origin on both backends. Before, moved 1e5,
// cornell_diffuse.json rendered 16 % darker with its lamp visibly smaller:
// its floats snapped to spacings of 2^-7.
#include "stability_support.h"

#include "trac0r/opencl_backend.h"
#include "trac0r/scene_loader.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace trac0r;
using trac0r::stability::require_same_image;

const std::string scenes_dir = std::string(TRAC0R_SOURCE_DIR) + "/scenes";

// cornell_diffuse.json with the camera and every shape moved by `offset`
// in the file, as doubles, at 32 x 32.
Scene moved_cornell(double offset) {
    std::ifstream in(scenes_dir + "/cornell_diffuse.json");
    nlohmann::json scene = nlohmann::json::parse(in);
    auto move = [offset](nlohmann::json& position) {
        for (auto& x : position) {
            x = x.get<double>() + offset;
        }
    };
    move(scene["camera"]["position"]);
    for (auto& shape : scene["shapes"]) {
        if (!shape.contains("position")) {
            shape["position"] = {0.0, 0.0, 0.0};
        }
        move(shape["position"]);
    }
    scene["render"]["width"] = 32;
    scene["render"]["height"] = 32;
    return parse_scene(scene.dump(), "moved.json", scenes_dir);
}

enum class Device { cpu, opencl };

// 96 frames: each image's standard error is then about 1.3 % of its mean
// (stability_support.h), well within require_same_image's 10 %.
std::unique_ptr<Renderer> render_on(Device backend, const Scene& scene, std::uint64_t seed) {
    std::unique_ptr<trac0r::Backend> b;
    if (backend == Device::cpu) {
        b = stability::cpu();
    } else {
        b = std::make_unique<OpenClBackend>();
    }
    std::unique_ptr<Renderer> r(new Renderer(scene, std::move(b), seed, PackOptions()));
    for (int i = 0; i < stability::room_frames; ++i) {
        r->render_frame();
    }
    return r;
}

}  // namespace

TEST_CASE("the local origin is near the camera, in double", "[far]") {
    const Scene at_origin = moved_cornell(0.0);
    CHECK(at_origin.origin == glm::dvec3(0.0));  // ordinary scenes keep their coordinates
    CHECK(at_origin.camera.position == glm::vec3(0.0f, 0.31f, 1.2f));
    for (double offset : {1e5, 1e6, 1e7, 1e9}) {
        INFO(offset);
        const Scene far = moved_cornell(offset);
        for (int i = 0; i < 3; ++i) {
            CHECK(std::fabs(far.origin[i] - offset) <= 513.0);
            CHECK(std::fabs(far.camera.position[i]) <= 513.0f);
        }
        // The room's own size is kept: its first wall is 1 wide, at the same
        // place relative to the camera.
        const glm::vec3 near_camera = far.shapes[0].aabb.min - far.camera.position;
        const glm::vec3 at_home = at_origin.shapes[0].aabb.min - at_origin.camera.position;
        for (int i = 0; i < 3; ++i) {
            CHECK(near_camera[i] == Approx(at_home[i]).margin(1e-4));
        }
    }
}

TEST_CASE("a room 1e5, 1e6 and 1e7 from the origin renders as at the origin", "[far][opencl]") {
    for (Device backend : {Device::cpu, Device::opencl}) {
        INFO((backend == Device::cpu ? "cpu" : "opencl"));
        const std::unique_ptr<Renderer> home = render_on(backend, moved_cornell(0.0), 5);
        for (double offset : {1e5, 1e6, 1e7}) {
            INFO(offset);
            const std::unique_ptr<Renderer> far = render_on(backend, moved_cornell(offset), 6);
            require_same_image(*home, *far, 0.1);
        }
    }
}
