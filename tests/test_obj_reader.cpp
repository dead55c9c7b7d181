// The OBJ reader (obj_mesh.cpp, obj_checker.cpp) through scene files:
// what exporters write loads, every mistake is named by file and line,
// vertex normals, and materials from the MTL files.
#include <catch2/catch.hpp>

#include "scene_test_support.h"
#include "test_support.h"
#include "trac0r/image_io.h"
#include "trac0r/input_checks.h"
#include "trac0r/kernel/types.h"
#include "trac0r/packed_scene.h"
#include "trac0r/scene_loader.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
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
        dir.write("p.mtl",
                  "newmtl shiny\nKd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nNs 250\nNi 1.4\nillum 2\n"
                  "newmtl pbr\nKd 0.6 0.5 0.4\nPr 0.35\nPm 0.8\n"
                  "newmtl bad\nKd 0.6 0.5 0.4\nPr 1.5\n");
        dir.write("m.obj",
                  "mtllib p.mtl\n" + quad + "usemtl shiny\nf 1 2 3\nusemtl pbr\nf 1 3 4\n");
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

TEST_CASE("OBJ meshes: UTF-16 text with a byte-order mark reads as its UTF-8",
          "[scene_loader]") {
    TempDir dir;
    const std::string text = "# a t\xC3\xA9trahedron\nv 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\n"
                             "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
    // UTF-16 of `text` (all of it below U+0800), with the mark.
    const auto utf16 = [&](bool big) {
        std::string out = big ? std::string("\xFE\xFF", 2) : std::string("\xFF\xFE", 2);
        for (std::size_t i = 0; i < text.size(); ++i) {
            unsigned code = static_cast<unsigned char>(text[i]);
            if (code >= 0xC0) {  // a two-byte UTF-8 sequence
                code = (code & 0x1F) << 6 | (static_cast<unsigned char>(text[++i]) & 0x3F);
            }
            const char hi = static_cast<char>(code >> 8);
            const char lo = static_cast<char>(code & 0xFF);
            out += big ? std::string{hi, lo} : std::string{lo, hi};
        }
        return out;
    };
    dir.write("utf8.obj", text);
    dir.write("be.obj", utf16(true));
    dir.write("le.obj", utf16(false));
    const auto shape_of = [&](const std::string& file) {
        const std::string scene = dir.write(
            file + ".json",
            with_shape(R"({"type": "mesh", "file": ")" + file + R"(", "material": "white"})"));
        return load_scene_file(scene, strict()).shapes.at(0);
    };
    const Shape utf8 = shape_of("utf8.obj");
    REQUIRE(utf8.triangles.size() == 4);
    for (const char* file : {"be.obj", "le.obj"}) {
        const Shape s = shape_of(file);
        REQUIRE(s.triangles.size() == 4);
        for (std::size_t t = 0; t < 4; ++t) {
            CHECK(same_vec3(s.triangles[t].v0, utf8.triangles[t].v0));
            CHECK(same_vec3(s.triangles[t].v1, utf8.triangles[t].v1));
            CHECK(same_vec3(s.triangles[t].v2, utf8.triangles[t].v2));
        }
    }
}
