// The scene loader: the shipped scenes load with the expected contents,
// defaults are the documented ones, and every kind of mistake gives one
// SceneError that names the file and the JSON path of the mistake.
#include <catch2/catch.hpp>

#include "trac0r/image_io.h"
#include "trac0r/input_checks.h"
#include "trac0r/kernel/types.h"
#include "trac0r/packed_scene.h"
#include "trac0r/scene_loader.h"
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
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

namespace {

const std::string scenes_dir = std::string(TRAC0R_SOURCE_DIR) + "/scenes";

// A minimal valid scene: one diffuse material, one plane. Tests swap one
// part for a broken one.
const std::string white_material = R"("white": {"type": "diffuse", "color": [0.5, 0.5, 0.5]})";
const std::string plane_shape = R"({"type": "plane", "size": [1, 1], "material": "white"})";

std::string scene_json(const std::string& materials = white_material,
                       const std::string& shapes = plane_shape, const std::string& extra = "") {
    return "{" + extra + (extra.empty() ? "" : ", ") + R"("materials": {)" + materials +
           R"(}, "shapes": [)" + shapes + "]}";
}

std::string with_shape(const std::string& shape) { return scene_json(white_material, shape); }

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

// Strict loading: a model file's defects are errors, with the messages
// these tests check (lenient loading's warnings: test_model_defects.cpp).
LoadOptions strict() {
    LoadOptions options;
    options.strict = true;
    return options;
}

// The message of the SceneError that loading the scene file `path` throws
// (strictly).
std::string scene_file_error(const std::string& path) {
    try {
        load_scene_file(path, strict());
    } catch (const SceneError& e) {
        return e.what();
    }
    FAIL("no SceneError for " << path);
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

bool same_vec3(const glm::vec3& a, const glm::vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

const char* const tetrahedron_obj =
    "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";

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

TEST_CASE("OBJ meshes: '+' before a coordinate, continued lines and large faces load",
          "[scene_loader]") {
    TempDir dir;
    const std::string scene = dir.write(
        "mesh.json", with_shape(R"({"type": "mesh", "file": "m.obj", "material": "white"})"));
    // What exporters write: a '+' sign, a statement continued after '\'
    // (also with \r\n), and a hexagon (4 triangles).
    dir.write("m.obj",
              "v +0 0 +0\nv 1 0 0\nv 1 \\\n 1 0\nv 0 1 0\r\nv -1 \\\r\n 0.5 +2e+0\nv 0.5 2 0\n"
              "f 1 2 3 \\\n 6 4 5\n");
    const Scene loaded = load_scene_file(scene);
    REQUIRE(loaded.shapes[0].triangles.size() == 4);
    // The vertices as written: the fifth is (-1, 0.5, 2).
    const AABB box = loaded.shapes[0].aabb;
    CHECK(box.min == glm::vec3(-1.0f, 0.0f, 0.0f));
    CHECK(box.max == glm::vec3(1.0f, 2.0f, 2.0f));
    // A mistake after a continued line is named by its own line: 3 lines
    // in, the continued statement counting as 2.
    dir.write("m.obj", "v 0 \\\n 0 0\nv 1 0 0\nv 0 1 x\nf 1 2 3\n");
    REQUIRE_THROWS_WITH(load_scene_file(scene),
                        EndsWith("m.obj:4: expected a vertex coordinate as a "
                                 "decimal number, got 'x'"));
    // One inside a continued statement: the line its word is on.
    dir.write("m.obj", "v 0 0 0\nv 1 \\\n 0 \\\r\n x\nv 0 1 0\nf 1 2 3\n");
    REQUIRE_THROWS_WITH(load_scene_file(scene),
                        EndsWith("m.obj:4: expected a vertex coordinate as a "
                                 "decimal number, got 'x'"));
    // A '+' is one sign, not two.
    dir.write("m.obj", "v 0 0 0\nv 1 0 +-1\nv 0 1 0\nf 1 2 3\n");
    REQUIRE_THROWS_WITH(load_scene_file(scene),
                        EndsWith("m.obj:2: expected a vertex coordinate as a "
                                 "decimal number, got '+-1'"));
    // A comment ends with its line, '\' or not: the vertex after it stays.
    dir.write("m.obj", "# exported to C:\\out\\\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK(load_scene_file(scene).shapes[0].triangles.size() == 1);
}

TEST_CASE("OBJ meshes: mistakes are named by file and line", "[scene_loader]") {
    TempDir dir;
    const std::string scene = dir.write(
        "mesh.json", with_shape(R"({"type": "mesh", "file": "m.obj", "material": "white"})"));
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    // The message after the scene's "/shapes/0/file: ", for an OBJ file.
    const auto obj_error = [&](const std::string& obj) {
        dir.write("m.obj", obj);
        try {
            load_scene_file(scene, strict());
        } catch (const SceneError& e) {
            const std::string prefix = scene + ": /shapes/0/file: ";
            const std::string message = e.what();
            REQUIRE_THAT(message, StartsWith(prefix));
            return message.substr(prefix.size());
        }
        FAIL("no SceneError for OBJ: " << obj);
        return std::string();
    };
    const std::string obj = dir.path() + "/m.obj";
    // tinyobjloader alone read each of these as something else, silently.
    CHECK(obj_error("v 0 0 x\nv 1 0 0\nv 0 1 0\nf 1 2 3\n") ==
          obj + ":1: expected a vertex coordinate as a decimal number, got 'x'");
    CHECK_THAT(obj_error("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n"),
               StartsWith(obj + ":2: ") && EndsWith("got 'nan'"));
    CHECK_THAT(obj_error(triangle + "v 0 0 1e39\nf 1 2 4\n"),
               StartsWith(obj + ":4: ") && EndsWith("got '1e39'"));
    CHECK(
        obj_error("v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n") ==
        obj +
            ":1: expected a vertex as 'v x y z' (with an optional w, r g b, or both), got 2 values");
    CHECK_THAT(obj_error(triangle + "f 1 2 3.5\n"),
               StartsWith(obj + ":4: expected a face vertex") && EndsWith("got '3.5'"));
    CHECK_THAT(obj_error(triangle + "f 1 2 4294967299\n"),
               StartsWith(obj + ":4: expected a face vertex"));
    CHECK_THAT(obj_error("v 0x1p0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
               StartsWith(obj + ":1: ") && EndsWith("got '0x1p0'"));  // tinyobjloader: 0
    // Finite as floats, but tinyobjloader's mantissa times 10^exponent
    // made them NaN (0 times infinity) and infinity.
    CHECK_THAT(obj_error("v 0e500 0 0\n" + triangle + "f 2 3 4\n"),
               StartsWith(obj + ":1: ") && EndsWith("got '0e500'"));
    CHECK_THAT(obj_error("v 1" + std::string(400, '0') + "e-400 0 0\n" + triangle + "f 2 3 4\n"),
               StartsWith(obj + ":1: ") && EndsWith("...'"));
    CHECK_THAT(obj_error("v 0 0 1e301\n" + triangle), EndsWith("within +-300), got '1e301'"));
    // Vertex normals (vn), which faces may name after a second '/'.
    CHECK_THAT(obj_error(triangle + "vn 0 0\nf 1//1 2//1 3//1\n"),
               EndsWith(obj + ":4: expected a normal as 'vn x y z', got 2 values"));
    CHECK_THAT(obj_error(triangle + "vn 0 x 1\nf 1//1 2//1 3//1\n"),
               EndsWith(obj + ":4: expected a normal component as a decimal number, got 'x'"));
    CHECK_THAT(obj_error(triangle + "vn 0 0 1e39\nf 1//1 2//1 3//1\n"),
               EndsWith(obj + ":4: expected a normal component finite in "
                              "float (below 3.4e38, an exponent within "
                              "+-300), got '1e39'"));
    CHECK_THAT(obj_error(triangle + "vn 0 0 1\nf 1//1 2//1 3//2\n"),
               EndsWith(obj + ":5: face refers to normal 2, but the file has 1 normals"));
    CHECK_THAT(obj_error(triangle + "f 1//-1 2//-1 3//-1\nvn 0 0 1\n"),
               EndsWith(obj + ":4: face refers to normal -1 (counted back from the 0 normals "
                              "before it), before the first"));

    // A face too large for tinyobjloader's triangulation (quadratic).
    std::string huge_face = "f";
    for (int k = 0; k < 10001; ++k) {
        huge_face += " " + std::to_string(k % 3 + 1);
    }
    CHECK(obj_error(triangle + huge_face + "\n") ==
          obj + ":4: expected a face of 3 to 10000 vertices, got 10001");
    // A word is quoted cut short, its control bytes escaped.
    CHECK(obj_error("v 0 0 " + std::string(100000, 'x') + "\n").size() < 250);
    CHECK_THAT(obj_error("v 0 0 \x1b[31m\n" + triangle), EndsWith("got '\\x1b[31m'"));
    // The texture and normal indices of a face, which tinyobjloader
    // refused as "zero value for face index".
    for (const char* face : {"f 1/x/1 2/x/1 3/x/1", "f 1// 2// 3//", "f 1/0/1 2/0/1 3/0/1",
                             "f 1/1/1/1 2 3", "f 1/ 2/ 3/"}) {
        CAPTURE(face);
        CHECK_THAT(obj_error(triangle + "vt 0 0\nvn 0 0 1\n" + face + "\n"),
                   StartsWith(obj + ":6: expected a face vertex as v, v/vt, v//vn or v/vt/vn"));
    }
    CHECK(obj_error(triangle + "f 1 2 3\nf 1 2\n") ==
          obj + ":5: expected a face of 3 to 10000 vertices, got 2");
    CHECK(
        obj_error(triangle + "f -1 -2 -4\n") ==
        obj +
            ":4: face refers to vertex -4 (counted back from the 3 vertices before it), before the first");
    CHECK(obj_error(triangle + "f 1 2 3\n\nf 1 2 7\n") ==
          obj + ":6: face refers to vertex 7, but the file has 3 vertices");
    REQUIRE(system(("mkdir " + obj + ".d").c_str()) == 0);
    const std::string dir_scene = dir.write(
        "dir.json", with_shape(R"({"type": "mesh", "file": "m.obj.d", "material": "white"})"));
    CHECK_THROWS_WITH(load_scene_file(dir_scene),
                      EndsWith("m.obj.d: cannot read OBJ mesh: it is a directory"));
    REQUIRE(system(("rmdir " + obj + ".d").c_str()) == 0);

    // What OBJ files hold besides: comments (also after a face, which
    // tinyobjloader refused), texture and normal indices, vertex colours,
    // relative and forward references, polygons, other statements.
    dir.write("m.obj",
              "# a comment\nf 1/1 2/1/1 3//1 # late\nv 0 0 0 # first\nv 1 0 0 1 0 0\n"
              "v 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ng part\nusemtl x\ns off\n"
              "f -4 -3 -2 -1\n");
    const std::vector<Triangle> triangles = load_scene_file(scene).shapes[0].triangles;
    REQUIRE(triangles.size() == 3);
    // The face before the vertices: 1, 2, 3; the quad, counted back from
    // the four before it: 1, 2, 3, 4, which tinyobjloader splits along
    // 2-4 (1 2 4, 2 3 4).
    const glm::vec3 v[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    CHECK((same_vec3(triangles[0].v0, v[0]) && same_vec3(triangles[0].v1, v[1]) &&
           same_vec3(triangles[0].v2, v[2])));
    CHECK((same_vec3(triangles[1].v0, v[0]) && same_vec3(triangles[1].v1, v[1]) &&
           same_vec3(triangles[1].v2, v[3])));
    CHECK((same_vec3(triangles[2].v0, v[1]) && same_vec3(triangles[2].v1, v[2]) &&
           same_vec3(triangles[2].v2, v[3])));

    // Lines, points and other statements the mesh does not use are not
    // read at all (tinyobjloader refused "l x y").
    dir.write("m.obj", triangle + "l x y\np 0\ncstype bezier\nf 1 2 3\n");
    CHECK(load_scene_file(scene).shapes[0].triangles.size() == 1);

    // Line ends \r\n and \r (old Mac exporters), tabs, trailing spaces, a
    // vertex with w and a colour (7 values), numbers as exporters write
    // them: the same triangle each time.
    const char* const same_triangle[] = {
        "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nf 1 2 3\r\n",
        "v 0 0 0\rv 1 0 0\rv 1 1 0\rf 1 2 3\r",
        "v\t0 0 0  \nv 1\t0 0\nv 1 1 0 \t\nf\t1 2 3",
        "v 0 0 0 1 0.5 0.5 0.5\nv 1 0 0 1 0.5 0.5 0.5\nv 1 1 0 1 0.5 0.5 0.5\nf 1 2 3\n",
        "v 0.0 -0 0e0\nv 1. 0.000000 .0\nv 1E+0 10e-1 0\nf 1 2 3\n",
        "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n",  // a UTF-8 byte-order mark
        // A form feed between words, which tinyobjloader does not take
        // for a blank (it read "v\f0" as an unknown statement).
        "v\f0 0 0\nv 1\v0 0\nv 1 1 0\nf\f1 2 3\n",
        // Exponents of three digits (old MSVC printf), leading zeros.
        "v 0.000000e+000 0 0\nv 1.000000e+000 0 0.0e-005\nv 0001 1 0\nf 1 2 3\n",
    };
    for (const char* text : same_triangle) {
        CAPTURE(text);
        dir.write("m.obj", text);
        const std::vector<Triangle> t = load_scene_file(scene).shapes[0].triangles;
        REQUIRE(t.size() == 1);
        CHECK((same_vec3(t[0].v0, v[0]) && same_vec3(t[0].v1, v[1]) && same_vec3(t[0].v2, v[2])));
    }
}

TEST_CASE("OBJ meshes: vertex normals shade a face smooth", "[scene_loader][smooth]") {
    TempDir dir;
    const auto mesh_scene = [&](const std::string& keys) {
        return dir.write("mesh.json", with_shape(R"({"type": "mesh", "file": "m.obj", )"
                                                 R"("material": "white")" +
                                                 keys + "}"));
    };
    const auto near = [](const glm::vec3& a, const glm::vec3& b) {
        return glm::length(a - b) < 1e-6f;
    };
    // Two faces: the first without normals, the second with three.
    dir.write("m.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 1\nvn +1 0 1\n"
              "f 1 2 3\nf 1//1 2//2 3//3\n");
    SECTION("unit normals by face, zero where a face has none") {
        const Shape mesh = load_scene_file(mesh_scene("")).shapes[0];
        REQUIRE(mesh.normals.size() == 2);
        CHECK(mesh.normals[0][0] == glm::vec3(0.0f));
        CHECK(near(mesh.normals[1][0], glm::vec3(0, 0, 1)));
        CHECK(near(mesh.normals[1][1], glm::normalize(glm::vec3(0, 1, 1))));
        CHECK(near(mesh.normals[1][2], glm::normalize(glm::vec3(1, 0, 1))));
    }
    SECTION("transformed by the inverse transpose; a mirror keeps them with their vertices") {
        const Shape scaled = load_scene_file(mesh_scene(R"(, "scale": [2, 1, 1])")).shapes[0];
        CHECK(near(scaled.normals[1][2], glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f))));
        const Shape mirrored = load_scene_file(mesh_scene(R"(, "scale": [-1, 1, 1])")).shapes[0];
        // The mirror swaps v1 and v2 (the winding stays outward), and the
        // normals with them.
        CHECK(near(mirrored.triangles[1].v1, glm::vec3(0, 1, 0)));
        CHECK(near(mirrored.normals[1][1], glm::normalize(glm::vec3(-1, 0, 1))));
        CHECK(near(mirrored.normals[1][2], glm::normalize(glm::vec3(0, 1, 1))));
    }
    SECTION("\"smooth\": false, or no normals in the file: flat") {
        CHECK(load_scene_file(mesh_scene(R"(, "smooth": false)")).shapes[0].normals.empty());
        dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\n");
        CHECK(load_scene_file(mesh_scene("")).shapes[0].normals.empty());
        // A zero normal, which some exporters write: that face is flat.
        dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
        CHECK(load_scene_file(mesh_scene("")).shapes[0].normals.empty());
    }
    SECTION("\"smooth\" must be true or false") {
        REQUIRE_THROWS_WITH(load_scene_file(mesh_scene(R"(, "smooth": 1)")),
                            Contains("/shapes/0/smooth: expected true or false"));
    }
}

TEST_CASE("OBJ meshes: materials from the MTL files, split by usemtl", "[scene_loader][mtl]") {
    TempDir dir;
    const auto mesh_scene = [&](const std::string& keys, const std::string& materials = "") {
        return dir.write(
            "mesh.json",
            scene_json(white_material + materials,
                       R"({"type": "mesh", "file": "m.obj", "material": "white")" + keys + "}"));
    };
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    dir.write("m.mtl",
              "# four materials\nnewmtl red\nKd 0.8 0.1 0.1\nillum 2\n"
              "newmtl lamp\nKe 5 4 2\n"
              "newmtl glass\nillum 7\nNi 1.45\nTf 0.9 0.9 1\n"
              "newmtl chrome\nillum 3\nKs 0.9 0.9 0.9\nNs 1000\n");
    dir.write("m.obj", "mtllib m.mtl\n" + quad +
                           "f 1 2 3\nusemtl red\nf 1 3 4\nusemtl lamp\nf 1 2 4\n"
                           "usemtl glass\nf 2 3 4\nusemtl chrome\nf 1 2 3\nusemtl red\nf 3 4 1\n");
    SECTION("one shape a material, in the order first used; each MTL material mapped") {
        const Scene scene = load_scene_file(mesh_scene(""));
        REQUIRE(scene.shapes.size() == 5);
        const auto material_of = [&](std::size_t shape) -> const Material& {
            return scene.materials[static_cast<std::size_t>(scene.shapes[shape].material)];
        };
        CHECK(material_of(0).name == "white");  // the face before any usemtl
        CHECK(scene.shapes[0].triangles.size() == 1);
        const Material& red = material_of(1);
        CHECK(red.name == "red");
        CHECK(red.type == MaterialType::diffuse);
        CHECK(red.color == glm::vec3(0.8f, 0.1f, 0.1f));
        CHECK(scene.shapes[1].triangles.size() == 2);  // both of its faces
        const Material& lamp = material_of(2);
        CHECK(lamp.type == MaterialType::emissive);
        CHECK(lamp.emittance == 5.0f);
        CHECK(lamp.color == glm::vec3(1.0f, 0.8f, 0.4f));
        const Material& glass = material_of(3);
        CHECK(glass.type == MaterialType::glass);
        CHECK(glass.ior == 1.45f);
        CHECK(glass.color == glm::vec3(0.9f, 0.9f, 1.0f));
        const Material& chrome = material_of(4);
        CHECK(chrome.type == MaterialType::conductor);
        CHECK(chrome.color == glm::vec3(0.9f));
        CHECK(chrome.roughness == 0.0f);  // Ns 1000: 1 - sqrt(1000 / 1000)
        CHECK(scene.materials.size() == 5);
        for (const Shape& shape : scene.shapes) {
            CHECK(shape.source == dir.path() + "/m.obj");
        }
    }
    SECTION("MTL highlights become plastic, the PBR extension principled") {
        dir.write("p.mtl", "newmtl shiny\nKd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nNs 250\nNi 1.4\nillum 2\n"
                           "newmtl pbr\nKd 0.6 0.5 0.4\nPr 0.35\nPm 0.8\n"
                           "newmtl bad\nKd 0.6 0.5 0.4\nPr 1.5\n");
        dir.write("m.obj", "mtllib p.mtl\n" + quad + "usemtl shiny\nf 1 2 3\nusemtl pbr\nf 1 3 4\n");
        const Scene scene = load_scene_file(mesh_scene(""));
        REQUIRE(scene.shapes.size() == 2);
        const Material& shiny = scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
        CHECK(shiny.type == MaterialType::plastic);
        CHECK(shiny.color == glm::vec3(0.2f, 0.3f, 0.4f));
        CHECK(shiny.roughness == Approx(0.5).epsilon(1e-6));  // 1 - sqrt(250 / 1000)
        CHECK(shiny.ior == 1.4f);
        const Material& pbr = scene.materials[static_cast<std::size_t>(scene.shapes[1].material)];
        CHECK(pbr.type == MaterialType::principled);
        CHECK(pbr.roughness == 0.35f);
        CHECK(pbr.metallic == 0.8f);
        dir.write("m.obj", "mtllib p.mtl\n" + quad + "usemtl bad\nf 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   Contains("material 'bad': Pr 1.5: expected it in [0, 1]"));
    }
    SECTION("every file of an mtllib line is read") {
        dir.write("a.mtl", "newmtl one\nKd 0.1 0.2 0.3\n");
        dir.write("b.mtl", "newmtl two\nKd 0.3 0.2 0.1\n");
        dir.write("m.obj", "mtllib a.mtl b.mtl\n" + quad + "usemtl two\nf 1 2 3\n");
        const Scene scene = load_scene_file(mesh_scene(""));
        REQUIRE(scene.shapes.size() == 1);
        CHECK(scene.materials[static_cast<std::size_t>(scene.shapes[0].material)].color ==
              glm::vec3(0.3f, 0.2f, 0.1f));
    }
    SECTION("a scene material of the same name takes the MTL one's place") {
        const Scene scene = load_scene_file(mesh_scene(
            "", R"(, "red": {"type": "glossy", "color": [0.5, 0.5, 0.5], "roughness": 0.1})"));
        REQUIRE(scene.shapes.size() == 5);
        const Material& red = scene.materials[static_cast<std::size_t>(scene.shapes[1].material)];
        CHECK(red.type == MaterialType::glossy);
        CHECK(red.roughness == 0.1f);
    }
    SECTION("\"file_materials\": false: one shape, the scene's material") {
        const Scene scene = load_scene_file(mesh_scene(R"(, "file_materials": false)"));
        REQUIRE(scene.shapes.size() == 1);
        CHECK(scene.shapes[0].triangles.size() == 6);
        CHECK(scene.materials.size() == 1);
    }
    SECTION("mistakes name the file, the line and the material") {
        const std::string obj = dir.path() + "/m.obj";
        const std::string mtl = dir.path() + "/m.mtl";
        dir.write("m.obj", "mtllib missing.mtl\n" + quad + "f 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   Contains(obj + ":1: mtllib 'missing.mtl': " + dir.path() + "/missing.mtl"));
        dir.write("m.obj", "mtllib m.mtl\n" + quad + "usemtl blue\nf 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   EndsWith(obj + ":6: usemtl 'blue': no material of that name in its mtllib "
                                  "files (m.mtl)"));
        // Without mtllib, usemtl names nothing to read: the scene's material.
        dir.write("m.obj", quad + "usemtl red\nf 1 2 3\n");
        const Scene plain = load_scene_file(mesh_scene(""));
        REQUIRE(plain.shapes.size() == 1);
        CHECK(plain.shapes[0].material == 0);
        dir.write("m.obj", "mtllib m.mtl\n" + quad + "usemtl red\nf 1 2 3\n");
        dir.write("m.mtl", "newmtl red\nKd 0.8 x 0.1\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   EndsWith(mtl + ":2: expected a Kd value as a decimal number, got 'x'"));
        dir.write("m.mtl", "newmtl red\nKd 0.8 0.1\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   EndsWith(mtl + ":2: expected 'Kd r g b', three numbers, got 2 values"));
        // One number is grey, as the MTL format says (tinyobjloader alone
        // would read (0.8, 0, 0)): test_mtl_names.cpp.
        dir.write("m.mtl", "newmtl red\nKd 0.8 0.1 0.1 0.1\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   EndsWith(mtl + ":2: expected 'Kd r g b', three numbers, got 4 values"));

        dir.write("m.mtl", "newmtl red\nKd 1.5 0 0\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   EndsWith(mtl + ":2: Kd 1.5: expected a number in [0, 1]"));
        dir.write("m.obj", "mtllib m.mtl\n" + quad + "usemtl\nf 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("")),
                   EndsWith(obj + ":6: expected 'usemtl NAME', got no name"));
    }
}

namespace {

// A glTF 2.0 of two triangles with normals (+z), the second moved to
// z = 3 by its node: "copper" (metal, roughness 0.3) and "glow" (emissive).
std::string two_triangle_gltf(const std::string& buffer_uri) {
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"mesh": 1, "translation": [0, 0, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 2}, "material": 0}]},
             {"primitives": [{"attributes": {"POSITION": 1, "NORMAL": 3}, "material": 1}]}],
  "materials": [{"name": "copper", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.5, 0.2, 1],
                 "metallicFactor": 1.0, "roughnessFactor": 0.3}},
                {"name": "glow", "emissiveFactor": [1, 0.5, 0.25]}],
  "buffers": [{"byteLength": 144, "uri": ")" +
           buffer_uri + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                  {"buffer": 0, "byteOffset": 72, "byteLength": 72}],
  "accessors": [
    {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 1], "max": [1, 1, 1]},
    {"bufferView": 1, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 1, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"}]})";
}

// The 144 bytes of two_triangle_gltf's buffer: the six positions, then the
// six normals.
std::string two_triangle_buffer() {
    const float values[36] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1,
                              0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    return std::string(reinterpret_cast<const char*>(values), sizeof values);
}

// A GLB: the 12-byte header, the JSON chunk (padded with blanks) and the
// binary chunk.
std::string glb_of(std::string json, const std::string& bin) {
    while (json.size() % 4 != 0) {
        json += ' ';
    }
    const auto word = [](std::uint32_t v) {
        return std::string(reinterpret_cast<const char*>(&v), 4);
    };
    const std::uint32_t total = static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size());
    return "glTF" + word(2) + word(total) + word(static_cast<std::uint32_t>(json.size())) + "JSON" +
           json + word(static_cast<std::uint32_t>(bin.size())) + std::string("BIN\0", 4) + bin;
}

}  // namespace

TEST_CASE("PLY and glTF 2.0 meshes, with their normals and materials", "[scene_loader][mesh]") {
    TempDir dir;
    const auto mesh_scene = [&](const std::string& file, const std::string& keys = "") {
        return dir.write("mesh.json", with_shape(R"({"type": "mesh", "file": ")" + file +
                                                 R"(", "material": "white")" + keys + "}"));
    };
    SECTION("PLY: faces triangulated, vertex normals smooth, the scene's material") {
        dir.write("q.ply",
                  "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                  "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                  "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0.6 0 0.8\n0 1 0 0 0 1\n4 0 1 2 3\n");
        const Scene scene = load_scene_file(mesh_scene("q.ply"));
        REQUIRE(scene.shapes.size() == 1);
        const Shape& quad = scene.shapes[0];
        CHECK(quad.triangles.size() == 2);
        CHECK(quad.source == dir.path() + "/q.ply");
        REQUIRE(quad.normals.size() == 2);
        CHECK(quad.material == 0);
        bool tilted = false;
        for (const VertexNormalTriple& n : quad.normals) {
            for (const glm::vec3& v : n) {
                tilted = tilted || glm::length(v - glm::vec3(0.6f, 0.0f, 0.8f)) < 1e-6f;
            }
        }
        CHECK(tilted);
    }
    const auto check_two_triangles = [&](const Scene& scene) {
        REQUIRE(scene.shapes.size() == 2);
        const Material& copper =
            scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
        CHECK(copper.name == "copper");
        CHECK(copper.type == MaterialType::principled);
        CHECK(copper.color == glm::vec3(0.9f, 0.5f, 0.2f));
        CHECK(copper.roughness == 0.3f);
        CHECK(copper.metallic == 1.0f);
        CHECK(copper.ior == 1.5f);
        CHECK(copper.specular == 1.0f);
        const Material& glow = scene.materials[static_cast<std::size_t>(scene.shapes[1].material)];
        // Emissive and reflecting (glTF's default base colour, metallic
        // and roughness), as every glTF material.
        CHECK(glow.type == MaterialType::principled);
        CHECK(glow.emission == glm::vec3(1.0f, 0.5f, 0.25f));
        CHECK(glow.color == glm::vec3(1.0f));
        CHECK(glow.metallic == 1.0f);
        CHECK(glow.roughness == 1.0f);
        // Not doubleSided (glTF's default): it emits from its front alone.
        CHECK_FALSE(glow.two_sided);
        // The node's translation applied: z = 1 + 2.
        CHECK(scene.shapes[1].aabb.min.z == 3.0f);
        CHECK(scene.shapes[0].normals.size() == 1);
    };
    SECTION(".gltf with its buffer beside it, and embedded") {
        dir.write("t.bin", two_triangle_buffer());
        dir.write("t.gltf", two_triangle_gltf("t.bin"));
        check_two_triangles(load_scene_file(mesh_scene("t.gltf")));
        // A mirroring node: the winding is swapped with it, so the
        // triangle's normal still agrees with its vertex normals (+z).
        std::string mirrored = two_triangle_gltf("t.bin");
        const std::string node = R"({"mesh": 0})";
        REQUIRE(mirrored.find(node) != std::string::npos);
        mirrored.replace(mirrored.find(node), node.size(), R"({"mesh": 0, "scale": [-1, 1, 1]})");
        dir.write("m.gltf", mirrored);
        const Scene flipped = load_scene_file(mesh_scene("m.gltf"));
        CHECK(flipped.shapes[0].aabb.min.x == -1.0f);
        CHECK(flipped.shapes[0].triangles[0].normal.z > 0.99f);
        REQUIRE(flipped.shapes[0].normals.size() == 1);
        CHECK(flipped.shapes[0].normals[0][1].z > 0.99f);
        dir.write(
            "e.gltf",
            two_triangle_gltf("data:application/octet-stream;base64,"
                              "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/"
                              "AACAPwAAAAAAAIA/AAAAAAAAgD8AAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"
                              "AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"));
        check_two_triangles(load_scene_file(mesh_scene("e.gltf")));
        // Without the file's materials: one shape of the scene's.
        const Scene plain = load_scene_file(mesh_scene("e.gltf", R"(, "file_materials": false)"));
        REQUIRE(plain.shapes.size() == 1);
        CHECK(plain.shapes[0].triangles.size() == 2);
        CHECK(plain.materials.size() == 1);
    }
    SECTION("a doubleSided glTF emitter emits from both sides") {
        dir.write("t.bin", two_triangle_buffer());
        std::string json = two_triangle_gltf("t.bin");
        const std::string glow = R"("emissiveFactor": [1, 0.5, 0.25])";
        json.replace(json.find(glow), glow.size(), glow + R"(, "doubleSided": true)");
        dir.write("d.gltf", json);
        const Scene scene = load_scene_file(mesh_scene("d.gltf"));
        CHECK(scene.materials[static_cast<std::size_t>(scene.shapes[1].material)].two_sided);
    }
    SECTION("a glTF primitive without a material takes the shape's") {
        dir.write("t.bin", two_triangle_buffer());
        std::string json = two_triangle_gltf("t.bin");
        json.replace(json.find(R"(, "material": 1)"), std::strlen(R"(, "material": 1)"), "");
        dir.write("n.gltf", json);
        const Scene scene = load_scene_file(mesh_scene("n.gltf"));
        REQUIRE(scene.shapes.size() == 2);
        CHECK(scene.shapes[1].material == 0);  // white
    }
    SECTION(".glb") {
        std::string json = two_triangle_gltf("");
        json.replace(json.find(R"(, "uri": "")"), std::strlen(R"(, "uri": "")"), "");
        dir.write("t.glb", glb_of(json, two_triangle_buffer()));
        check_two_triangles(load_scene_file(mesh_scene("t.glb")));
    }
    SECTION("mistakes name the file") {
        const std::string path = dir.path();
        dir.write("empty.ply", "");
        CHECK_THAT(scene_file_error(mesh_scene("empty.ply")),
                   EndsWith(path + "/empty.ply: cannot read mesh: the file is empty"));
        dir.write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n0 0\n");
        CHECK_THAT(scene_file_error(mesh_scene("bad.ply")),
                   Contains(path + "/bad.ply: cannot read mesh: "));
        dir.write("oor.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                  "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
        CHECK_THAT(scene_file_error(mesh_scene("oor.ply")),
                   EndsWith(path + "/oor.ply: mesh '': a face refers to vertex 9, but the mesh "
                                   "has 3"));
        // A polygon is a fan of triangles; one with a corner beyond the
        // vertices is refused (assimp's own triangulation aborted the
        // process on such a face: tests/fuzz/corpus/mesh/broken_face_cube.ply).
        const std::string pentagon_header =
            "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 0\n1.5 1 0\n0.5 2 0\n-0.5 1 0\n";
        dir.write("five.ply", pentagon_header + "5 0 1 2 3 4\n");
        const Scene five = load_scene_file(mesh_scene("five.ply"));
        REQUIRE(five.shapes.size() == 1);
        CHECK(five.shapes[0].triangles.size() == 3);
        dir.write("five.ply", pentagon_header + "5 0 1 2 3 70000\n");
        CHECK_THAT(scene_file_error(mesh_scene("five.ply")),
                   EndsWith(path + "/five.ply: mesh '': a face refers to vertex 70000, but the "
                                   "mesh has 5"));
        // Found by tests/fuzz/fuzz_mesh: a header without end_header hung
        // assimp's PLY reader; an STL or a PLY named .glb or .gltf was read
        // by whichever other reader of assimp's guessed its format.
        dir.write("cut.ply",
                  "ply\nformat ascii 1.0\nelement vertex 8\nproperty float32 x\n"
                  "proper\n1 0 0\n1 0 1\n4 0 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("cut.ply")),
                   EndsWith(path + "/cut.ply: cannot read mesh: the PLY header has no "
                                   "end_header line (a line of its own)"));
        // "end_header" run into the data made it loop.
        dir.write("run_on.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nend_header0\n0 0 0\n0 0 1\n0 1 1\n");
        CHECK_THAT(scene_file_error(mesh_scene("run_on.ply")),
                   EndsWith(path + "/run_on.ply: cannot read mesh: the PLY header has no "
                                   "end_header line (a line of its own)"));
        const std::string stl =
            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
            "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        for (const char* name : {"stl.glb", "stl.gltf"}) {
            dir.write(name, stl);
            CHECK_THAT(scene_file_error(mesh_scene(name)),
                       Contains(path + "/" + name + ": cannot read mesh: GLTF: "));
        }
        dir.write("ply.gltf",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                  "property float y\nproperty float z\nelement face 1\n"
                  "property list uchar int vertex_indices\nend_header\n"
                  "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        CHECK_THAT(scene_file_error(mesh_scene("ply.gltf")),
                   Contains(path + "/ply.gltf: cannot read mesh: GLTF: "));
        dir.write("bad.gltf", "{\"asset\": ");
        CHECK_THAT(scene_file_error(mesh_scene("bad.gltf")),
                   Contains(path + "/bad.gltf: cannot read mesh: "));
        CHECK_THAT(scene_file_error(mesh_scene("missing.glb")),
                   Contains(path + "/missing.glb: cannot open mesh: "));
        std::string json = two_triangle_gltf("t.bin");
        json.replace(json.find("\"metallicFactor\": 1.0"), 21, "\"metallicFactor\": 1.0");
        json.replace(json.find("0.9, 0.5, 0.2, 1"), 16, "1.5, 0.5, 0.2, 1");
        dir.write("t.bin", two_triangle_buffer());
        dir.write("c.gltf", json);
        CHECK_THAT(scene_file_error(mesh_scene("c.gltf")),
                   EndsWith(path + "/c.gltf: material 'copper': base colour (1.5, 0.5, 0.2): "
                                   "expected each in [0, 1]"));
    }
}

namespace {

// A 2 x 2 RGB image written as PNG at path: red, green on the top row,
// blue, white below.
void write_test_png(const std::string& path) {
    Rgb8Image image;
    image.width = 2;
    image.height = 2;
    image.bytes = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    write_png(path, image);
}

// One triangle in the xy plane with texture coordinates (x, y) at its
// vertices and a material with a base-colour texture whose image's URI is
// image_uri; its buffer embedded.
std::string textured_triangle_gltf(const std::string& image_uri) {
    const float values[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    const std::string buffer(reinterpret_cast<const char*>(values), sizeof values);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
  "materials": [{"name": "logo", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                 "baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
  "textures": [{"source": 0}], "images": [{"uri": ")" +
           image_uri + R"("}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]})";
}

}  // namespace

TEST_CASE("base-colour textures from MTL and glTF, with the file's coordinates",
          "[scene_loader][texture]") {
    TempDir dir;
    const auto mesh_scene = [&](const std::string& file, const std::string& keys = "") {
        return dir.write("mesh.json", with_shape(R"({"type": "mesh", "file": ")" + file +
                                                 R"(", "material": "white")" + keys + "}"));
    };
    dir.write("t.png", "");  // removed with the directory
    write_test_png(dir.path() + "/t.png");
    // A quad in the xy plane whose texture coordinates are its (x, y).
    const std::string quad_obj =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl tex\n"
        "f 1/1 2/2 3/3\nusemtl tex2\nf 1/1 3/3 4/4\n";
    const std::string obj = dir.path() + "/m.obj";
    const std::string mtl = dir.path() + "/m.mtl";
    // Each triangle's coordinates those of its vertices: (x_sign x, y), or
    // with flip_v (x, 1 - y).
    const auto check_coordinates_follow_vertices = [](const Shape& s, float x_sign,
                                                      bool flip_v = false) {
        REQUIRE(s.uvs.size() == s.triangles.size());
        for (std::size_t i = 0; i < s.triangles.size(); ++i) {
            const Triangle& t = s.triangles[i];
            const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
            REQUIRE(s.uvs[i].present);
            for (int k = 0; k < 3; ++k) {
                CHECK(s.uvs[i].uv[k] ==
                      glm::vec2(x_sign * v[k].x, flip_v ? 1.0f - v[k].y : v[k].y));
            }
        }
    };
    SECTION("an OBJ's vt and its MTL's map_Kd; one texture for two materials") {
        dir.write("m.obj", quad_obj);
        // A Windows exporter's ".\t.png".
        dir.write("m.mtl",
                  "newmtl tex\nKd 1 1 1\nmap_Kd t.png\nnewmtl tex2\nKd 0.5 0.5 0.5\n"
                  "map_Kd .\\t.png\n");
        const Scene scene = load_scene_file(mesh_scene("m.obj"));
        REQUIRE(scene.textures.size() == 1);
        const Texture& t = scene.textures[0];
        CHECK(t.width == 2);
        CHECK(t.height == 2);
        CHECK(t.source == dir.path() + "/t.png");
        REQUIRE(t.texels.size() == 4);
        CHECK(t.texels[0] == 0xff0000ffu);  // red, alpha 255
        CHECK(t.texels[1] == 0xff00ff00u);
        CHECK(t.texels[2] == 0xffff0000u);
        CHECK(t.texels[3] == 0xffffffffu);
        REQUIRE(scene.shapes.size() == 2);
        for (const Shape& s : scene.shapes) {
            CHECK(scene.materials[static_cast<std::size_t>(s.material)].texture == 0);
            check_coordinates_follow_vertices(s, 1.0f);
        }
        const PackedScene packed = pack_scene(scene);
        CHECK((packed.features & T0_FEATURE_TEXTURE) != 0u);
        CHECK(packed.texels.size() == 4);
        CHECK(packed.uvs.size() == 2);
    }
    SECTION("a mirroring scale keeps each coordinate with its vertex") {
        dir.write("m.obj", quad_obj);
        dir.write("m.mtl", "newmtl tex\nmap_Kd t.png\nnewmtl tex2\nmap_Kd t.png\n");
        const Scene scene = load_scene_file(mesh_scene("m.obj", R"(, "scale": [-1, 1, 1])"));
        for (const Shape& s : scene.shapes) {
            check_coordinates_follow_vertices(s, -1.0f);
        }
    }
    SECTION("faces without vt, or a material without a map: no texture feature") {
        dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl tex\nf 1 2 3\n");
        dir.write("m.mtl", "newmtl tex\nmap_Kd t.png\n");
        const Scene scene = load_scene_file(mesh_scene("m.obj"));
        CHECK(scene.shapes[0].uvs.empty());
        CHECK((pack_scene(scene).features & T0_FEATURE_TEXTURE) == 0u);
        dir.write("m.obj", quad_obj);
        dir.write("m.mtl", "newmtl tex\nKd 0.5 0.5 0.5\nnewmtl tex2\nKd 0.5 0.5 0.5\n");
        const Scene plain = load_scene_file(mesh_scene("m.obj"));
        CHECK(plain.textures.empty());
        const PackedScene packed = pack_scene(plain);
        CHECK((packed.features & T0_FEATURE_TEXTURE) == 0u);
        CHECK(packed.uvs.empty());
    }
    SECTION("a glTF's base colour texture, embedded or beside it") {
        std::ifstream png_file(dir.path() + "/t.png", std::ios::binary);
        const std::string png((std::istreambuf_iterator<char>(png_file)),
                              std::istreambuf_iterator<char>());
        for (const std::string& uri :
             {"data:image/png;base64," + base64(png), std::string("t.png")}) {
            CAPTURE(uri.substr(0, 30));
            dir.write("t.gltf", textured_triangle_gltf(uri));
            const Scene scene = load_scene_file(mesh_scene("t.gltf"));
            REQUIRE(scene.textures.size() == 1);
            CHECK(scene.textures[0].width == 2);
            CHECK(scene.textures[0].texels[1] == 0xff00ff00u);
            const Material& logo =
                scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
            CHECK(logo.name == "logo");
            CHECK(logo.color == glm::vec3(0.5f));
            CHECK(logo.texture == 0);
            // glTF's v runs down from the image's top; assimp gives OBJ's
            // (up from the bottom).
            check_coordinates_follow_vertices(scene.shapes[0], 1.0f, true);
        }
    }
    SECTION("a texture that cannot be read or decoded is named with its material") {
        dir.write("m.obj", quad_obj);
        dir.write("m.mtl", "newmtl tex\nmap_Kd nope.png\nnewmtl tex2\n");
        CHECK_THAT(scene_file_error(mesh_scene("m.obj")),
                   Contains(mtl + ": material 'tex': map_Kd 'nope.png': " + dir.path() +
                            "/nope.png: cannot open texture"));
        dir.write("bad.png", "not an image at all");
        dir.write("m.mtl", "newmtl tex\nmap_Kd bad.png\nnewmtl tex2\n");
        CHECK_THAT(scene_file_error(mesh_scene("m.obj")),
                   Contains(mtl + ": material 'tex': map_Kd 'bad.png': cannot decode texture"));
        dir.write("t.gltf", textured_triangle_gltf("missing.png"));
        CHECK_THAT(scene_file_error(mesh_scene("t.gltf")),
                   Contains(dir.path() +
                            "/t.gltf: material 'logo': base colour texture "
                            "'missing.png': " +
                            dir.path() + "/missing.png: cannot open texture"));
    }
    SECTION("images are counted against the scene's room before they are decoded") {
        // A PNG's signature and header only: 16384 x 16384 texels, RGB;
        // its data missing, it cannot be decoded.
        const std::string huge_png = std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16) +
                                     std::string("\0\0\x40\0\0\0\x40\0\x08\x02\0\0\0", 13) +
                                     std::string("\0\0\0\0", 4);
        const auto bytes = reinterpret_cast<const unsigned char*>(huge_png.data());
        // Refused from its header, so never decoded (which would fail).
        CHECK_THROWS_WITH(decode_texture("m.mtl: material 'a': map_Kd 'h.png'", "h.png", bytes,
                                         huge_png.size(), (1u << 28) - 1),
                          Equals("m.mtl: material 'a': map_Kd 'h.png': texture is 16384 x 16384 "
                                 "texels, more than the scene has room for (268435455 more of "
                                 "the " + std::to_string(scene_texel_budget()) + " a scene may have on this machine)"));
        CHECK_THROWS_WITH(decode_texture("h", "h.png", bytes, huge_png.size(), 1u << 28),
                          StartsWith("h: cannot decode texture"));
        // An OBJ's materials, each with its own 2 x 2 image: the third
        // goes over 11 texels.
        std::string obj_text = "mtllib n.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\n";
        std::string mtl_text;
        for (int i = 0; i < 3; ++i) {
            const std::string m = "n" + std::to_string(i);
            obj_text += "usemtl " + m + "\nf 1/1 2/1 3/1\n";
            mtl_text += "newmtl " + m + "\nKd 1 1 1\nmap_Kd " + m + ".png\n";
            dir.write(m + ".png", "");
            write_test_png(dir.path() + "/" + m + ".png");
        }
        dir.write("n.mtl", mtl_text);
        const std::string n_obj = dir.write("n.obj", obj_text);
        const auto load = [](const std::string& path, std::uint64_t texels) {
            return load_mesh_parts(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0,
                                   true, true, texels);
        };
        CHECK_THROWS_WITH(load(n_obj, 11),
                          Equals(dir.path() + "/n.mtl: material 'n2': map_Kd 'n2.png': texture "
                                              "is 2 x 2 texels, more than the scene has room for "
                                              "(3 more of the " +
                                              std::to_string(scene_texel_budget()) +
                                              " a scene may have on this machine)"));
        CHECK(load(n_obj, 12).textures.size() == 3);
        // A glTF's textures, counted in its import's child process.
        const std::string gltf = dir.write("t.gltf", textured_triangle_gltf("t.png"));
        CHECK_THROWS_WITH(load(gltf, 3),
                          Equals(gltf + ": material 'logo': base colour texture 't.png': "
                                        "texture is 2 x 2 texels, more than the scene has room "
                                        "for (3 more of the " + std::to_string(scene_texel_budget()) +
                                        " a scene may have on this machine)"));
        CHECK(load(gltf, 4).textures.at(0).texels.size() == 4);
    }
    SECTION("vt lines and the faces' references to them are checked") {
        dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0 0 0\nf 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("m.obj")),
                   EndsWith(obj + ":4: expected a texture coordinate as 'vt u [v [w]]', got 4 "
                                  "values"));
        dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 x\nf 1 2 3\n");
        CHECK_THAT(scene_file_error(mesh_scene("m.obj")),
                   EndsWith(obj + ":4: expected a texture coordinate as a decimal number, got "
                                  "'x'"));
        dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/9\n");
        CHECK_THAT(scene_file_error(mesh_scene("m.obj")),
                   EndsWith(obj + ":5: face refers to texture coordinate 9, but the file has 1 "
                                  "texture coordinates (vt)"));
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

TEST_CASE("a camera block loads over a scene's; bad ones are one message", "[scene_loader][camera]") {
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

    const auto message = [&](const std::string& text) {
        try {
            parse_camera_block(text, "cam.json", origin);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    CHECK(message(R"({"camera": {"aperture_radius": -0.1}})") ==
          "cam.json: /camera/aperture_radius: expected a finite number >= 0, got -0.1");
    CHECK(message(R"({"camera": {"focus_distance": 0}})") ==
          "cam.json: /camera/focus_distance: expected a finite positive number, got 0");
    CHECK(message(R"({"camera": {"positon": [0, 0, 0]}})").find("positon") != std::string::npos);
    CHECK(message(R"({"render": {"width": 8}})").find("render") != std::string::npos);
    CHECK(message("[1, 2]").find("cam.json") == 0);
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
