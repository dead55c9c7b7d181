// A model file opened on its own (trac0r/model_scene.h): a scene around it
// that frames it and lights it, and that --print-scene writes as JSON
// that loads back to the same scene and image.
#include "test_support.h"
#include "viewer_process.h"

#include "trac0r/model_scene.h"

#include <cstring>

using namespace trac0r;
using Catch::Matchers::Contains;

namespace {

// A unit cube's 12 triangles, centred on `c`, as an OBJ.
std::string cube_obj(const glm::dvec3& c) {
    std::string text;
    for (int i = 0; i < 8; ++i) {
        char line[128];
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", c.x + ((i & 1) ? 0.5 : -0.5),
                      c.y + ((i & 2) ? 0.5 : -0.5), c.z + ((i & 4) ? 0.5 : -0.5));
        text += line;
    }
    return text + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

}  // namespace

TEST_CASE("model files are told from scene files by their extension", "[model_scene]") {
    for (const char* path : {"a.obj", "b.PLY", "c/d.gltf", "e.Glb"}) {
        CHECK(is_model_path(path));
    }
    for (const char* path : {"a.json", "obj", "a.obj.json", ""}) {
        CHECK_FALSE(is_model_path(path));
    }
}

TEST_CASE("a model's scene frames it, lights it, and prints as JSON that loads back to it",
          "[model_scene]") {
    TempDir dir;
    // Near the origin (the scene keeps its first load) and far from it
    // (loaded again about the camera's local origin).
    for (const glm::dvec3& centre :
         {glm::dvec3(0.2, 0.5, -0.3), glm::dvec3(5000.0, 20.0, -3000.0)}) {
        CAPTURE(centre.x);
        const std::string obj = dir.write("cube.obj", cube_obj(centre));
        std::string json;
        const Scene scene = model_scene(obj, LoadOptions(), &json);
        CAPTURE(json);
        REQUIRE(scene.shapes.size() == 1);
        CHECK(scene.materials[static_cast<std::size_t>(scene.shapes[0].material)].name ==
              "default");
        CHECK(scene.environment.present);
        // Looking at the cube's centre, from in front (+z), to the right
        // and above, far enough that its bounding sphere (radius sqrt(3)/2)
        // fits the 45-degree view.
        const glm::dvec3 position = glm::dvec3(scene.camera.position) + scene.origin;
        const glm::dvec3 to_centre = centre - position;
        CHECK(glm::dot(glm::normalize(to_centre),
                       glm::normalize(glm::dvec3(scene.camera.direction))) ==
              Approx(1.0).epsilon(1e-6));
        CHECK(position.z > centre.z);
        CHECK(position.x > centre.x);
        CHECK(position.y > centre.y);
        CHECK(scene.camera.vertical_fov == 45.0f);
        const double fits = std::sqrt(3.0) / 2.0 / std::sin(22.5 * 3.14159265358979323846 / 180.0);
        CHECK(glm::length(to_centre) >= fits);
        CHECK(glm::length(to_centre) <= 1.1 * fits);
        // The JSON, loaded as a scene file: the same scene, field by field.
        const std::string printed = dir.write("printed.json", json);
        CHECK(scene_digest(load_scene_file(printed)) == scene_digest(scene));
    }
}

TEST_CASE("trac0r_viewer opens a model on its own; --print-scene's scene renders the same",
          "[model_scene][cli]") {
    TempDir dir;
    const std::string obj = dir.write("cube.obj", cube_obj(glm::dvec3(1.0, 2.0, 3.0)));
    const std::string direct = dir.path() + "/direct.pfm";
    const auto run = trac0r_test::run_viewer_process(
        obj + " --headless --width 32 --height 24 --spp 2 --output " + direct);
    CAPTURE(run.err);
    REQUIRE(run.exit_code == 0);
    const auto print = trac0r_test::run_viewer_process(obj + " --print-scene");
    REQUIRE(print.exit_code == 0);
    CHECK_THAT(print.out, Contains("\"environment\": {\"color\":[1,1,1]}"));
    const std::string scene = dir.write("printed.json", print.out);
    const std::string again = dir.path() + "/again.pfm";
    REQUIRE(trac0r_test::run_viewer_process(scene +
                                            " --headless --width 32 --height 24 --spp 2 "
                                            "--output " +
                                            again)
                .exit_code == 0);
    CHECK(trac0r_test::read_text_file(direct) == trac0r_test::read_text_file(again));
    const Image image = read_pfm(direct);
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels) {
        sum += p.x;
    }
    CHECK(sum > 0.0);
    // --print-scene wants a model.
    const auto wrong = trac0r_test::run_viewer_process(scene + " --print-scene");
    CHECK(wrong.exit_code != 0);
    CHECK_THAT(wrong.err, Contains("--print-scene: expected a model file (.obj, .ply, .gltf, "
                                   ".glb) to make a scene around, got '"));
}

TEST_CASE("a glTF's own camera and KHR_lights_punctual lights make its scene", "[model_scene]") {
    // One triangle; a camera at (0, 1, 5) turned 90 degrees about y (so
    // it looks along -x) with yfov 0.5 and aspect 2; a point light of 683
    // cd (1 W/sr) at (1, 2, 3); a red spot of 1366 cd under a parent node
    // moved by (0, 10, 0), turned to point down (-90 degrees about x), its
    // cone 0.2 to 0.4 rad; a directional light of 6830 lux pointing down.
    const double h = std::sqrt(0.5);
    char rotations[256];
    std::snprintf(rotations, sizeof rotations, "[0, %.17g, 0, %.17g]|[%.17g, 0, 0, %.17g]", h, h,
                  -h, h);
    const std::string turn_y(rotations, std::strchr(rotations, '|'));
    const std::string turn_down(std::strchr(rotations, '|') + 1);
    TempDir dir;
    const std::string path =
        dir.write("lit.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0, 1, 2, 3, 5]}],
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "point", "intensity": 683},
    {"type": "spot", "intensity": 1366, "color": [1, 0, 0],
     "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}},
    {"type": "directional", "intensity": 6830}]}},
  "nodes": [{"mesh": 0},
            {"camera": 0, "translation": [0, 1, 5], "rotation": )" +
                                  turn_y + R"(},
            {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"translation": [0, 10, 0], "children": [4]},
            {"rotation": )" + turn_down +
                                  R"(, "extensions": {"KHR_lights_punctual": {"light": 1}}},
            {"rotation": )" + turn_down +
                                  R"(, "extensions": {"KHR_lights_punctual": {"light": 2}}}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 2.0,
                                                       "znear": 0.1}}],
  )" + gltf_one_triangle_tail());
    std::string json;
    const Scene scene = model_scene(path, LoadOptions(), &json);
    CAPTURE(json);
    const glm::dvec3 eye = glm::dvec3(scene.camera.position) + scene.origin;
    CHECK(eye.x == Approx(0.0).margin(1e-6));
    CHECK(eye.y == Approx(1.0));
    CHECK(eye.z == Approx(5.0));
    // -z turned 90 degrees about y: -x.
    CHECK(scene.camera.direction.x == Approx(-1.0f));
    CHECK(scene.camera.direction.z == Approx(0.0f).margin(1e-6));
    CHECK(scene.camera.vertical_fov == Approx(0.5 * 180.0 / 3.14159265358979323846));
    CHECK(scene.render.width == 1200);
    CHECK(scene.render.height == 600);
    CHECK_FALSE(scene.environment.present);  // the file's lights instead
    REQUIRE(scene.lamps.size() == 3);
    const Lamp& point = scene.lamps[0];
    CHECK(point.type == LampType::point);
    CHECK(point.power == Approx(1.0f));
    CHECK(glm::dvec3(point.position) + scene.origin == glm::dvec3(1, 2, 3));
    const Lamp& spot = scene.lamps[1];
    CHECK(spot.type == LampType::spot);
    CHECK(spot.power == Approx(2.0f));
    CHECK(spot.color == glm::vec3(1, 0, 0));
    CHECK((glm::dvec3(spot.position) + scene.origin).y == Approx(10.0));
    CHECK(spot.direction.y == Approx(-1.0f));
    CHECK(spot.angle == Approx(2.0 * 0.4 * 180.0 / 3.14159265358979323846));
    CHECK(spot.blend == Approx(0.5f));
    const Lamp& sun = scene.lamps[2];
    CHECK(sun.type == LampType::sun);
    CHECK(sun.power == Approx(10.0f));
    CHECK(sun.direction.y == Approx(1.0f));  // towards the sun: up
    CHECK(sun.angle == 0.0f);
    // The printed scene loads back to it.
    const std::string printed = dir.write("printed.json", json);
    CHECK(scene_digest(load_scene_file(printed)) == scene_digest(scene));
}

TEST_CASE("a glTF's orthographic camera makes an orthographic scene camera", "[model_scene]") {
    // One triangle seen by an orthographic camera at (0, 0, 4) looking
    // along -z: xmag 3 and ymag 1.5 (half the view's width and height).
    const auto gltf = [&](const std::string& magnification) {
        return R"({"asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 4]}],
  "cameras": [{"type": "orthographic", "orthographic": {)" +
               magnification + R"(, "znear": 0.1, "zfar": 100}}],
  )" + gltf_one_triangle_tail();
    };
    TempDir dir;
    // A negative magnification (which glTF says should not be) is its size.
    const std::string path = dir.write("ortho.gltf", gltf(R"("xmag": 3, "ymag": -1.5)"));
    std::string json;
    const Scene scene = model_scene(path, LoadOptions(), &json);
    CAPTURE(json);
    CHECK(scene.camera.projection == Projection::orthographic);
    CHECK(scene.camera.view_height == 3.0f);
    CHECK(scene.camera.direction.z == Approx(-1.0f));
    CHECK(scene.render.width == 1200);  // the view's aspect, 600 rows
    CHECK(scene.render.height == 600);
    const std::string printed = dir.write("printed.json", json);
    CHECK(scene_digest(load_scene_file(printed)) == scene_digest(scene));
    // A magnification that is not a positive number is named.
    const std::string bad = dir.write("bad.gltf", gltf(R"("xmag": 3, "ymag": 0)"));
    try {
        model_scene(bad, LoadOptions(), nullptr);
        FAIL("no error");
    } catch (const std::exception& e) {
        CHECK_THAT(std::string(e.what()),
                   Contains("node 1: camera: xmag, ymag: expected numbers not zero and at most "
                            "5e29 (half the view's width and height), got 3.0, 0.0"));
    }
}
