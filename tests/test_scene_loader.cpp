// The scene loader: the shipped scenes load with the expected contents,
// defaults are the documented ones, and every kind of mistake gives one
// SceneError that names the file and the JSON path of the mistake.
#include <catch2/catch.hpp>

#include "trac0r/image_io.h"
#include "trac0r/input_checks.h"
#include "trac0r/kernel/types.h"
#include "trac0r/packed_scene.h"
#include "trac0r/scene_loader.h"
#include "scene_test_support.h"
#include "test_support.h"

#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace trac0r;
using namespace trac0r_scene_test;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

namespace {

const std::string scenes_dir = std::string(TRAC0R_SOURCE_DIR) + "/scenes";

std::string with_material(const std::string& material) {
    return scene_json(white_material + ", " + material, plane_shape);
}

std::string with_extra(const std::string& extra) {
    return scene_json(white_material, plane_shape, extra);
}

Scene parse(const std::string& text) { return parse_scene(text, "test.json", ""); }

// The message of the SceneError that parsing throws; a test fails if it
// throws nothing or something else.
std::string scene_error(const std::string& text) {
    try {
        parse(text);
    } catch (const SceneError& e) {
        const std::string message = e.what();
        CHECK(message.find('\n') == std::string::npos);  // one line, for a terminal
        return message;
    }
    FAIL("no SceneError for: " << text);
    return "";
}

const Material& material_named(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials) {
        if (m.name == name) {
            return m;
        }
    }
    FAIL("no material named " << name);
    return scene.materials.front();
}

std::vector<std::string> scene_files() {
    std::vector<std::string> names;
    DIR* dir = opendir(scenes_dir.c_str());
    REQUIRE(dir != nullptr);
    while (const dirent* entry = readdir(dir)) {
        const std::string name = entry->d_name;
        if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0) {
            names.push_back(name);
        }
    }
    closedir(dir);
    std::sort(names.begin(), names.end());
    return names;
}

const char* const tetrahedron_obj =
    "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";

// The error of a camera block read as cam.json, or "(no error)".
std::string camera_block_error(const std::string& text) {
    try {
        parse_camera_block(text, "cam.json", glm::dvec3(0.0));
    } catch (const SceneError& e) {
        return std::string(e.what());
    }
    return std::string("(no error)");
}

}  // namespace

TEST_CASE("every scene in scenes/ loads", "[scene_loader]") {
    const std::vector<std::string> names = scene_files();
    CHECK(names.size() >= 4);
    for (const std::string& name : names) {
        INFO("scene " << name);
        CHECK_NOTHROW(load_scene_file(scenes_dir + "/" + name));
    }
}

TEST_CASE("the Cornell scene has the thesis' contents", "[scene_loader]") {
    const Scene scene = load_scene_file(scenes_dir + "/cornell.json");
    CHECK(scene.materials.size() == 6);
    REQUIRE(scene.shapes.size() == 10);
    // 6 planes x 2 + 2 boxes x 12 + 2 icospheres x 20 * 4^2.
    CHECK(scene.triangle_count() == 6 * 2 + 2 * 12 + 2 * 320);
    CHECK(scene.render.width == 800);
    CHECK(scene.render.height == 600);
    CHECK(scene.render.max_depth == 5);
    CHECK(same_vec3(scene.camera.position, glm::vec3(0.0f, 0.31f, 1.2f)));
    CHECK(scene.camera.vertical_fov == 53.13f);

    const Material& lamp = material_named(scene, "lamp");
    CHECK(lamp.type == MaterialType::emissive);
    CHECK(lamp.emittance == 15.0f);
    CHECK(material_named(scene, "glass").ior == 1.51714f);
    CHECK(material_named(scene, "glossy").roughness == 0.09f);
    CHECK(material_named(scene, "red").color.x == 0.366046f);
    // The lamp plane is shape 5 and uses the lamp material.
    CHECK(scene.materials[static_cast<std::size_t>(scene.shapes[5].material)].name == "lamp");
}

TEST_CASE("the other shipped scenes have their expected contents", "[scene_loader]") {
    SECTION("cornell_diffuse: every surface but the lamp is diffuse") {
        const Scene scene = load_scene_file(scenes_dir + "/cornell_diffuse.json");
        CHECK(scene.materials.size() == 4);
        CHECK(scene.shapes.size() == 10);
        for (const Material& m : scene.materials) {
            INFO(m.name);
            CHECK((m.type == MaterialType::diffuse || m.name == "lamp"));
        }
        CHECK(scene.camera.vertical_fov == 90.0f);
        CHECK(scene.render.max_depth == 64);
    }
    SECTION("furnace: one emitting diffuse box around the camera") {
        const Scene scene = load_scene_file(scenes_dir + "/furnace.json");
        REQUIRE(scene.materials.size() == 1);
        REQUIRE(scene.shapes.size() == 1);
        CHECK(scene.triangle_count() == 12);
        CHECK(scene.materials[0].emittance == 1.0f);
        CHECK(same_vec3(scene.shapes[0].aabb.min, glm::vec3(-1.0f)));
        CHECK(same_vec3(scene.shapes[0].aabb.max, glm::vec3(1.0f)));
        CHECK(same_vec3(scene.camera.position, glm::vec3(0.0f)));
        CHECK(scene.render.width == 64);
        CHECK(scene.render.height == 48);
        CHECK(scene.render.max_depth == 8);
    }
    SECTION("mesh_demo: the tetrahedron OBJ, relative to the scene's directory") {
        const Scene scene = load_scene_file(scenes_dir + "/mesh_demo.json");
        REQUIRE(scene.shapes.size() == 7);
        CHECK(scene.shapes.back().triangles.size() == 4);
    }
    SECTION("mtl_demo: the cube's faces in three shapes, by their MTL materials") {
        const Scene scene = load_scene_file(scenes_dir + "/mtl_demo.json");
        REQUIRE(scene.shapes.size() == 9);
        const char* const names[3] = {"brick", "gold", "glow"};
        const MaterialType types[3] = {MaterialType::diffuse, MaterialType::conductor,
                                       MaterialType::emissive};
        const std::size_t triangles[3] = {4, 6, 2};
        for (std::size_t k = 0; k < 3; ++k) {
            const Shape& part = scene.shapes[6 + k];
            const Material& m = scene.materials[static_cast<std::size_t>(part.material)];
            CHECK(m.name == names[k]);
            CHECK(m.type == types[k]);
            CHECK(part.triangles.size() == triangles[k]);
        }
    }
    SECTION("smooth_demo: one OBJ sphere flat, then smooth") {
        const Scene scene = load_scene_file(scenes_dir + "/smooth_demo.json");
        REQUIRE(scene.shapes.size() == 8);
        const Shape& flat = scene.shapes[6];
        const Shape& smooth = scene.shapes[7];
        CHECK(flat.triangles.size() == 80);
        CHECK(flat.normals.empty());
        REQUIRE(smooth.normals.size() == 80);
        // The sphere's normals point away from its centre.
        const glm::vec3 centre = 0.5f * (smooth.aabb.min + smooth.aabb.max);
        for (std::size_t i = 0; i < smooth.triangles.size(); ++i) {
            const glm::vec3 out = glm::normalize(smooth.triangles[i].v0 - centre);
            CHECK(glm::dot(smooth.normals[i][0], out) > 0.999f);
        }
        CHECK((pack_scene(scene).features & T0_FEATURE_SMOOTH) != 0u);
    }
}

TEST_CASE("the built-in scene is scenes/cornell.json", "[scene_loader]") {
    const Scene builtin = builtin_scene();
    const Scene file = load_scene_file(scenes_dir + "/cornell.json");
    CHECK(builtin.triangle_count() == file.triangle_count());
    REQUIRE(builtin.shapes.size() == file.shapes.size());
    for (std::size_t i = 0; i < file.shapes.size(); ++i) {
        CHECK(builtin.shapes[i].material == file.shapes[i].material);
        CHECK(same_vec3(builtin.shapes[i].aabb.min, file.shapes[i].aabb.min));
        CHECK(same_vec3(builtin.shapes[i].aabb.max, file.shapes[i].aabb.max));
    }
    REQUIRE(builtin.materials.size() == file.materials.size());
    for (std::size_t i = 0; i < file.materials.size(); ++i) {
        CHECK(builtin.materials[i].name == file.materials[i].name);
    }
    CHECK(same_vec3(builtin.camera.position, file.camera.position));
    CHECK(same_vec3(builtin.camera.direction, file.camera.direction));
    CHECK(same_vec3(builtin.camera.world_up, file.camera.world_up));
    CHECK(builtin.camera.vertical_fov == file.camera.vertical_fov);
    CHECK(builtin.render.max_depth == file.render.max_depth);

    // The text itself is the file's, without the build's header line.
    std::ifstream in(scenes_dir + "/cornell.json");
    std::stringstream text;
    text << in.rdbuf();
    CHECK_THAT(builtin_scene_json(), StartsWith(text.str()));
}

TEST_CASE("optional keys take their documented defaults", "[scene_loader]") {
    const Scene scene = parse(
        scene_json(white_material + R"(, "mirror": {"type": "glossy", "color": [1, 1, 1]},
                              "clear": {"type": "glass", "color": [1, 1, 1]})",
                   plane_shape + R"(, {"type": "icosphere", "radius": 1, "material": "white"})"));
    const Camera default_camera;
    CHECK(same_vec3(scene.camera.position, default_camera.position));
    CHECK(same_vec3(scene.camera.direction, default_camera.direction));
    CHECK(same_vec3(scene.camera.world_up, default_camera.world_up));
    CHECK(scene.camera.vertical_fov == default_camera.vertical_fov);
    CHECK(scene.render.width == 800);
    CHECK(scene.render.height == 600);
    CHECK(scene.render.max_depth == 5);
    CHECK(material_named(scene, "white").emittance == 0.0f);
    CHECK(material_named(scene, "mirror").roughness == 0.0f);
    CHECK(material_named(scene, "clear").ior == 1.5f);
    // Position and orientation 0: the unit plane centred on the origin.
    CHECK(same_vec3(scene.shapes[0].aabb.min, glm::vec3(-0.5f, 0.0f, -0.5f)));
    CHECK(same_vec3(scene.shapes[0].aabb.max, glm::vec3(0.5f, 0.0f, 0.5f)));
    CHECK(scene.shapes[1].triangles.size() == 320);  // 2 subdivisions
}

TEST_CASE("integers may be written with a zero fraction", "[scene_loader]") {
    const Scene scene = parse(with_extra(R"("render": {"width": 640.0, "height": 480})"));
    CHECK(scene.render.width == 640);
}

TEST_CASE("scene errors: JSON syntax, with line and column", "[scene_loader]") {
    const std::string text = "{\n  \"materials\": {\n    \"white\": {\"type\": \"diffuse\",}\n";
    CHECK_THAT(scene_error(text), StartsWith("test.json:3:33: JSON syntax error: "));
    CHECK_THAT(scene_error(""), StartsWith("test.json:1:1: JSON syntax error: "));
    CHECK_THAT(scene_error("{\"render\": {\"height\": \"1e999\",\n  \"width\": 1e400}}"),
               Equals("test.json:2:12: JSON number is not finite: number overflow parsing "
                      "'1e400'"));
}

TEST_CASE("scene errors: a missing required key", "[scene_loader]") {
    CHECK_THAT(scene_error(R"({"shapes": [)" + plane_shape + "]}"),
               StartsWith("test.json: /materials: required key is missing"));
    CHECK_THAT(scene_error(R"({"materials": {)" + white_material + "}}"),
               StartsWith("test.json: /shapes: required key is missing"));
    CHECK_THAT(scene_error(with_shape(R"({"type": "plane", "material": "white"})")),
               StartsWith("test.json: /shapes/0/size: required key is missing") &&
                   Contains("an array of 2 finite positive numbers"));
    CHECK_THAT(scene_error(with_shape(R"({"type": "plane", "size": [1, 1]})")),
               StartsWith("test.json: /shapes/0/material: required key is missing"));
    CHECK_THAT(scene_error(with_shape(R"({"size": [1, 1], "material": "white"})")),
               StartsWith("test.json: /shapes/0/type: required key is missing"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "diffuse"})")),
               StartsWith("test.json: /materials/m/color: required key is missing"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "emissive", "color": [1, 1, 1]})")),
               StartsWith("test.json: /materials/m/emittance: required key is missing"));
    CHECK_THAT(scene_error(with_shape(R"({"type": "mesh", "material": "white"})")),
               StartsWith("test.json: /shapes/0/file: required key is missing"));
}

TEST_CASE("scene errors: an emission beyond what a pixel's float sum can hold", "[scene_loader]") {
    // Each number is a finite float, but colour x emittance is 1e39 (or
    // above 1e30, where a pixel's sum of up to 2^24 samples could overflow).
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "emissive", "color": [10, 1, 1], "emittance": 1e38})")),
               StartsWith("test.json: /materials/m/emittance: the colour times the emittance "
                          "is 1e+39 in a channel, above 1e30"));
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "diffuse", "color": [0.5, 1, 1], "emittance": 2e30})")),
               StartsWith("test.json: /materials/m/emittance: the colour times the emittance "
                          "is 2e+30"));
    // 1e30 itself is accepted.
    const Scene scene =
        parse(with_material(R"("m": {"type": "emissive", "color": [1, 1, 1], "emittance": 1e30})"));
    CHECK(material_named(scene, "m").emittance == 1e30f);
}

TEST_CASE("scene errors: a value of the wrong JSON type", "[scene_loader]") {
    CHECK_THAT(scene_error("[1, 2]"), StartsWith("test.json: (top level): expected a JSON object"));
    CHECK_THAT(scene_error(with_shape(R"({"type": "plane", "size": "big", "material": "white"})")),
               Equals("test.json: /shapes/0/size: expected an array of 2 finite positive "
                      "numbers, got \"big\""));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "diffuse", "color": [1, "1", 1]})")),
               StartsWith("test.json: /materials/m/color: expected an array of 3 numbers in "
                          "[0, 1], got [1, \"1\", 1]"));
    CHECK_THAT(scene_error(with_extra(R"("render": {"width": "800"})")),
               Equals("test.json: /render/width: expected an integer in [1, 16384], got \"800\""));
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "glossy", "color": [1, 1, 1], "roughness": true})")),
               StartsWith("test.json: /materials/m/roughness: expected a number in [0, 1], got "
                          "true"));
    CHECK_THAT(scene_error(with_shape(R"({"type": "plane", "size": [1, 1], "material": 3})")),
               StartsWith("test.json: /shapes/0/material: expected the name of a material"));
    CHECK_THAT(scene_error(R"({"materials": [], "shapes": [)" + plane_shape + "]}"),
               StartsWith("test.json: /materials: expected a non-empty object"));
    CHECK_THAT(scene_error(R"({"materials": {}, "shapes": [)" + plane_shape + "]}"),
               StartsWith("test.json: /materials: expected a non-empty object"));
    CHECK_THAT(scene_error(scene_json(white_material, "")),
               StartsWith("test.json: /shapes: expected a non-empty array of shapes, got []"));
    CHECK_THAT(scene_error(with_extra(R"("camera": [0, 0, 1])")),
               StartsWith("test.json: /camera: expected a camera object"));
    CHECK_THAT(
        scene_error(with_shape(R"({"type": "mesh", "file": 7, "material": "white"})")),
        StartsWith("test.json: /shapes/0/file: expected the path of a mesh file (.obj, .ply, "
                   ".gltf or .glb), got 7"));
}

TEST_CASE("scene errors: a deeply nested or huge value is described in short", "[scene_loader]") {
    // The description stops at 80 characters without building (or recursing
    // through) the rest: nested 100,000 deep, it once overflowed the stack.
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    const std::string message = scene_error(deep);
    CHECK_THAT(message,
               StartsWith("test.json: (top level): expected a JSON object") && EndsWith("[[[..."));
    CHECK(message.size() < 200);
    CHECK_THAT(scene_error(R"({"materials": )" + deep + R"(, "shapes": [)" + plane_shape + "]}"),
               StartsWith("test.json: /materials: expected a non-empty object"));
    std::string wide = "[0";
    for (int i = 0; i < 100000; ++i) {
        wide += ", 0";
    }
    CHECK(
        scene_error(scene_json(white_material, plane_shape, R"("camera": )" + wide + "]")).size() <
        200);
}

TEST_CASE("scene errors: an unknown key", "[scene_loader]") {
    CHECK_THAT(scene_error(with_extra(R"("camra": {})")),
               StartsWith("test.json: /camra: unknown key in the top level"));
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "diffuse", "color": [1, 1, 1], "roughness": 0.5})")),
               StartsWith("test.json: /materials/m/roughness: unknown key in a diffuse material") &&
                   Contains("allowed keys: type, color, emittance"));
    CHECK_THAT(
        scene_error(with_material(R"("m": {"type": "glass", "color": [1, 1, 1], "emittance": 1})")),
        StartsWith("test.json: /materials/m/emittance: unknown key in a glass material"));
    CHECK_THAT(scene_error(with_shape(
                   R"({"type": "plane", "size": [1, 1], "radius": 1, "material": "white"})")),
               StartsWith("test.json: /shapes/0/radius: unknown key in a plane shape"));
    CHECK_THAT(
        scene_error(with_shape(
            R"({"type": "icosphere", "radius": 1, "scale": [1, 1, 1], "material": "white"})")),
        StartsWith("test.json: /shapes/0/scale: unknown key in an icosphere shape"));
    CHECK_THAT(scene_error(with_extra(R"("camera": {"fov": 40})")),
               StartsWith("test.json: /camera/fov: unknown key in the camera"));
    CHECK_THAT(scene_error(with_extra(R"("render": {"depth": 4})")),
               StartsWith("test.json: /render/depth: unknown key in the render settings"));
}

TEST_CASE("scene errors: a key given twice", "[scene_loader]") {
    CHECK_THAT(scene_error(scene_json(white_material + ", " + white_material)),
               StartsWith("test.json: /materials/white: duplicate key"));
    CHECK_THAT(scene_error(with_shape(
                   R"({"type": "plane", "size": [1, 1], "size": [2, 2], "material": "white"})")),
               StartsWith("test.json: /shapes/0/size: duplicate key"));
    const std::string box_with_two_types =
        R"({"type": "box", "size": [1, 1, 1], "material": "white", "type": "box"})";
    CHECK_THAT(scene_error(scene_json(white_material, plane_shape + ", " + box_with_two_types)),
               StartsWith("test.json: /shapes/1/type: duplicate key"));
}

TEST_CASE("scene errors: long names and lists are cut short", "[scene_loader]") {
    std::string materials = white_material;
    for (int i = 0; i < 30; ++i) {
        materials += ", \"m" + std::to_string(i) + R"(": {"type": "diffuse", "color": [1, 1, 1]})";
    }
    const std::string unknown =
        scene_error(scene_json(materials, R"({"type": "plane", "size": [1, 1], "material": "x"})"));
    CHECK_THAT(unknown, StartsWith("test.json: /shapes/0/material: unknown material \"x\" (known "
                                   "materials: \"m0\", \"m1\", ") &&
                            EndsWith(" and 11 more)"));
    const std::string key(100000, 'k');
    const std::string long_key = scene_error(with_extra("\"" + key + "\": 1"));
    CHECK_THAT(long_key, StartsWith("test.json: /kkk") && Contains("...: unknown key"));
    CHECK(long_key.size() < 300);
    // A long key is cut, but the path keeps the field after it.
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "diffuse", "color": [1, 1, 1], ")" +
                                         std::string(200, 'k') + R"(": {"a": 1}})")),
               StartsWith("test.json: /materials/m/kkkk") && Contains("k...: unknown key"));
    // A key with a newline and a terminal's escape: one line, escaped.
    CHECK_THAT(scene_error(with_extra(R"("x\ny\u001b[31m": 1)")),
               StartsWith("test.json: /x\\x0ay\\x1b[31m: unknown key"));
}

TEST_CASE("scene errors: unknown names and types", "[scene_loader]") {
    CHECK_THAT(scene_error(with_shape(R"({"type": "plane", "size": [1, 1], "material": "whte"})")),
               Equals("test.json: /shapes/0/material: unknown material \"whte\" (known "
                      "materials: \"white\")"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "metal", "color": [1, 1, 1]})")),
               Equals("test.json: /materials/m/type: expected one of \"emissive\", \"diffuse\", "
                      "\"glass\", \"glossy\", \"conductor\", \"plastic\", "
                      "\"principled\", got \"metal\""));
    CHECK_THAT(scene_error(with_shape(R"({"type": "sphere", "radius": 1, "material": "white"})")),
               StartsWith("test.json: /shapes/0/type: expected one of \"plane\", \"box\", "
                          "\"icosphere\", \"mesh\", got \"sphere\""));
}

TEST_CASE("scene errors: a mesh file that cannot be read", "[scene_loader]") {
    CHECK_THAT(
        scene_error(with_shape(R"({"type": "mesh", "file": "no/such.obj", "material": "white"})")),
        StartsWith("test.json: /shapes/0/file: ") && Contains("no/such.obj"));
}

TEST_CASE("scene errors: numbers out of range", "[scene_loader]") {
    CHECK_THAT(
        scene_error(with_shape(R"({"type": "plane", "size": [1, -2], "material": "white"})")),
        Equals("test.json: /shapes/0/size: expected an array of 2 finite positive "
               "numbers, got [1, -2]"));
    CHECK_THAT(
        scene_error(with_shape(R"({"type": "plane", "size": [1e39, 1], "material": "white"})")),
        StartsWith("test.json: /shapes/0/size: ") && Contains("not finite"));
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "emissive", "color": [1, 1, 1], "emittance": 1e39})")),
               StartsWith("test.json: /materials/m/emittance: ") && Contains("not finite"));
    CHECK_THAT(
        scene_error(with_shape(R"({"type": "icosphere", "radius": 0, "material": "white"})")),
        Equals("test.json: /shapes/0/radius: expected a finite positive number, got 0"));
    CHECK_THAT(
        scene_error(with_shape(
            R"({"type": "icosphere", "radius": 1, "subdivisions": 8, "material": "white"})")),
        StartsWith("test.json: /shapes/0/subdivisions: expected an integer in [0, 7]"));
    CHECK_THAT(
        scene_error(with_shape(
            R"({"type": "mesh", "file": "x.obj", "scale": [1, 0, 1], "material": "white"})")),
        StartsWith("test.json: /shapes/0/scale: expected an array of 3 finite non-zero"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "diffuse", "color": [1.2, 0, 0]})")),
               StartsWith("test.json: /materials/m/color: expected an array of 3 numbers in "
                          "[0, 1], got [1.2, 0, 0]"));
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "emissive", "color": [1, 1, 1], "emittance": 0})")),
               StartsWith("test.json: /materials/m/emittance: expected a finite positive number"));
    CHECK_THAT(scene_error(with_extra(R"("render": {"width": 2.5})")),
               Equals("test.json: /render/width: expected an integer in [1, 16384], got 2.5"));
    CHECK_THAT(scene_error(with_extra(R"("render": {"max_depth": 0})")),
               StartsWith("test.json: /render/max_depth: expected an integer in [1, 100000]"));
    // An emitter's color is radiance, not reflectance: above 1 is fine.
    CHECK_NOTHROW(
        parse(with_material(R"("m": {"type": "emissive", "color": [2, 2, 2], "emittance": 1})")));
}

TEST_CASE("scene errors: a shape none of whose triangles survive in float", "[scene_loader]") {
    // Each number is in range, but the triangles are not: at x = z = 1, a plane
    // 1e-20 wide has its vertices all rounded to the same floats (zero
    // area), and 3e38 plus the radius is above float's largest. The shape
    // would silently vanish.
    const std::string expected =
        "no triangle of the shape can be rendered (of 2, each has in float arithmetic an area of "
        "zero or below float's smallest normal";
    CHECK_THAT(
        scene_error(scene_json(
            white_material,
            plane_shape + R"(, {"type": "plane", "size": [1e-20, 1e-20], "position": [1, 0, 1],
                                         "material": "white"})")),
        StartsWith("test.json: /shapes/1: " + expected));
    CHECK_THAT(
        scene_error(with_shape(R"({"type": "icosphere", "radius": 1e38,
                                         "position": [3e38, 0, 0], "material": "white"})")),
        StartsWith("test.json: /shapes/0: no triangle of the shape can be rendered (of 320,"));
    // At the origin the same plane's area, 1e-40, is a float, but a
    // denormal, which the CPU backend (and any device that flushes them)
    // reads as 0.
    CHECK_THAT(scene_error(
                   with_shape(R"({"type": "plane", "size": [1e-20, 1e-20], "material": "white"})")),
               StartsWith("test.json: /shapes/0: " + expected));
    // Some triangles left: the shape stays (pack_scene counts the others).
    CHECK_NOTHROW(
        parse(with_shape(R"({"type": "plane", "size": [1e-5, 1e-5], "material": "white"})")));
}

TEST_CASE("scene errors: a camera that cannot form an image", "[scene_loader]") {
    CHECK_THAT(scene_error(with_extra(R"("camera": {"direction": [0, 1, 0]})")),
               StartsWith("test.json: /camera: ") && Contains("parallel"));
    CHECK_THAT(scene_error(with_extra(R"("camera": {"direction": [0, 0, 0]})")),
               StartsWith("test.json: /camera: ") && Contains("direction"));
    CHECK_THAT(scene_error(with_extra(R"("camera": {"vertical_fov": 180})")),
               Equals("test.json: /camera/vertical_fov: expected a number of degrees in "
                      "(0, 180), got 180"));
}

TEST_CASE("scene files: errors name the file; meshes are relative to it", "[scene_loader]") {
    TempDir dir;
    SECTION("a file that does not exist") {
        const std::string path = dir.path() + "/absent.json";
        REQUIRE_THROWS_WITH(load_scene_file(path),
                            Equals(path + ": cannot open scene file: No such file or directory"));
    }
    SECTION("a directory") {
        REQUIRE_THROWS_WITH(load_scene_file(dir.path()), StartsWith(dir.path() + ": cannot"));
    }
    SECTION("a syntax error") {
        const std::string path = dir.write("broken.json", "{\n  \"materials\": {,\n}\n");
        REQUIRE_THROWS_WITH(load_scene_file(path), StartsWith(path + ":2:17: JSON syntax error"));
    }
    SECTION("a relative mesh path resolves against the scene's directory") {
        dir.write("tet.obj", tetrahedron_obj);
        const std::string path = dir.write(
            "mesh.json", with_shape(R"({"type": "mesh", "file": "tet.obj", "material": "white"})"));
        const Scene scene = load_scene_file(path);
        CHECK(scene.shapes[0].triangles.size() == 4);
    }
    SECTION("a missing mesh names the scene file, the JSON path and the OBJ file") {
        const std::string path = dir.write(
            "mesh.json",
            with_shape(R"({"type": "mesh", "file": "missing.obj", "material": "white"})"));
        REQUIRE_THROWS_WITH(load_scene_file(path), StartsWith(path + ": /shapes/0/file: ") &&
                                                       Contains(dir.path() + "/missing.obj"));
    }
}

TEST_CASE("printable: control bytes escaped, cut between characters", "[scene_loader]") {
    CHECK(printable("plain", 40) == "plain");
    CHECK(printable("a\nb\x1b[31m\x7f", 40) == "a\\x0ab\\x1b[31m\\x7f");
    CHECK(printable("caf\xc3\xa9", 40) == "caf\xc3\xa9");  // UTF-8 passes
    CHECK(printable("\xc2\x9b"
                    "2J",
                    40) == "\\xc2\\x9b2J");  // C1 control (CSI)
    // Cut to at most 10 bytes with "...", never inside a character or an
    // escape.
    CHECK(printable("abcdefghijklmnop", 10) == "abcdefg...");
    CHECK(printable(std::string("abcdef") + "\xc3\xa9\xc3\xa9\xc3\xa9", 10) == "abcdef...");
    CHECK(printable("abcde\x1b\x1b\x1b", 10) == "abcde...");
    CHECK(printable("abcdefghij", 10) == "abcdefghij");  // fits exactly: not cut
}

TEST_CASE("a camera block loads over a scene's; bad ones are one message",
          "[scene_loader][camera]") {
    const glm::dvec3 origin(0.0);
    const Camera c = parse_camera_block(
        R"({"camera": {"position": [1, 2, 3], "direction": [0, 0, -1], "aperture_radius": 0.02,
            "focus_distance": 2.5}})",
        "cam.json", origin);
    CHECK(c.position == glm::vec3(1.0f, 2.0f, 3.0f));
    CHECK(c.aperture_radius == 0.02f);
    CHECK(c.focus_distance == 2.5f);
    // The block alone is a camera too.
    CHECK(parse_camera_block(R"({"vertical_fov": 40})", "cam.json", origin).vertical_fov == 40.0f);
    // Printed and read back: the same floats.
    Camera odd;
    odd.position = glm::vec3(0.1f, -1234.5677f, 3e-7f);
    odd.direction = glm::vec3(0.3f, -0.2f, -0.9f);
    odd.vertical_fov = 33.333f;
    odd.aperture_radius = 0.0123f;
    odd.focus_distance = 7.77f;
    const glm::dvec3 far(4096.0, 0.0, -1024.0);
    const Camera read = parse_camera_block(camera_block_json(odd, far), "printed", far);
    CHECK(read.position == odd.position);
    CHECK(read.direction == odd.direction);
    CHECK(read.vertical_fov == odd.vertical_fov);
    CHECK(read.aperture_radius == odd.aperture_radius);
    CHECK(read.focus_distance == odd.focus_distance);

    const auto message = camera_block_error;
    CHECK(message(R"({"camera": {"aperture_radius": -0.1}})") ==
          "cam.json: /camera/aperture_radius: expected a finite number >= 0, got -0.1");
    CHECK(message(R"({"camera": {"focus_distance": 0}})") ==
          "cam.json: /camera/focus_distance: expected a finite positive number, got 0");
    CHECK(message(R"({"camera": {"positon": [0, 0, 0]}})").find("positon") != std::string::npos);
    CHECK(message(R"({"render": {"width": 8}})").find("render") != std::string::npos);
    CHECK(message("[1, 2]").find("cam.json") == 0);
}

TEST_CASE("an orthographic camera block: its keys, printed and read back, and its mistakes",
          "[scene_loader][camera]") {
    const glm::dvec3 origin(0.0);
    const Camera c = parse_camera_block(
        R"({"camera": {"projection": "orthographic", "view_height": 3.5}})", "cam.json", origin);
    CHECK(c.projection == Projection::orthographic);
    CHECK(c.view_height == 3.5f);
    CHECK(camera_block_error(R"({"projection": "perspective", "view_height": 2})") ==
          "cam.json: /view_height: view_height is an orthographic camera's: give "
          "\"projection\": \"orthographic\", or a vertical_fov");
    Camera odd;
    odd.projection = Projection::orthographic;
    odd.view_height = 0.123457f;
    odd.aperture_radius = 0.01f;
    const Camera read = parse_camera_block(camera_block_json(odd, origin), "printed", origin);
    CHECK(read.projection == Projection::orthographic);
    CHECK(read.view_height == odd.view_height);
    CHECK(read.aperture_radius == odd.aperture_radius);

    const auto message = camera_block_error;
    CHECK(message(R"({"camera": {"projection": "fisheye"}})") ==
          "cam.json: /camera/projection: expected one of \"perspective\", \"orthographic\", "
          "got \"fisheye\"");
    CHECK(message(R"({"camera": {"projection": "orthographic", "view_height": 0}})") ==
          "cam.json: /camera/view_height: expected a finite positive number, got 0");
    CHECK(message(R"({"camera": {"projection": "orthographic", "vertical_fov": 40}})") ==
          "cam.json: /camera/vertical_fov: an orthographic camera has no field of view: give "
          "its view_height (metres)");
    CHECK(message(R"({"camera": {"view_height": 2}})") ==
          "cam.json: /camera/view_height: view_height is an orthographic camera's: give "
          "\"projection\": \"orthographic\", or a vertical_fov");
}

TEST_CASE("scene errors: the microfacet materials' keys", "[scene_loader][microfacet]") {
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "conductor", "color": [1, 1, 1], "roughness": 1.5})")),
               StartsWith("test.json: /materials/m/roughness: expected a number in [0, 1]"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "conductor", "metal": "brass"})")),
               Equals("test.json: /materials/m/metal: expected one of \"gold\", \"silver\", "
                      "\"copper\", \"aluminium\", \"chromium\", \"tungsten\", got \"brass\""));
    CHECK_THAT(scene_error(with_material(
                   R"("m": {"type": "plastic", "color": [1, 1, 1], "metal": "gold"})")),
               StartsWith("test.json: /materials/m/metal: unknown key in a plastic material"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "principled", "color": [1, 1, 1],
                                                 "metallic": -0.5})")),
               StartsWith("test.json: /materials/m/metallic: expected a number in [0, 1]"));
    CHECK_THAT(scene_error(with_material(R"("m": {"type": "conductor"})")),
               StartsWith("test.json: /materials/m/color: required key is missing"));
}
