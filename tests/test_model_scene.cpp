// A model file opened on its own (trac0r/model_scene.h): a scene around it
// that frames it and lights it, and that --print-scene writes as JSON
// that loads back to the same scene and image.
#include "test_support.h"
#include "viewer_process.h"

#include "trac0r/model_scene.h"

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
