// Lenient loading (trac0r/model_defects.h): a model with a defect that
// other importers pass over loads with one warning line a kind and
// renders; strict loading (--strict) refuses each as it always did.
#include "scene_test_support.h"
#include "test_support.h"
#include "viewer_process.h"

#include "trac0r/gltf_json.h"
#include "trac0r/gltf_repeats.h"
#include "trac0r/input_file.h"

#include <nlohmann/json.hpp>

using namespace trac0r;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using trac0r_scene_test::strict;

namespace {

// The warning lines of `scene` that contain `text`.
std::size_t warnings_with(const Scene& scene, const std::string& text) {
    std::size_t n = 0;
    for (const std::string& line : scene.warnings) {
        n += line.find(text) != std::string::npos ? 1u : 0u;
    }
    return n;
}

std::string strict_error(const std::string& path) {
    try {
        load_scene_file(path, strict());
    } catch (const SceneError& e) {
        return e.what();
    }
    FAIL("no SceneError for " << path << " (strict)");
    return "";
}

// A unit square of two faces in the xy plane, each of one material.
const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n";

}  // namespace

TEST_CASE("an OBJ's defects: skipped or replaced with a warning each, refused when strict",
          "[defects][mesh]") {
    TempDir dir;
    const std::string obj = dir.path() + "/m.obj";
    const std::string mtl = dir.path() + "/m.mtl";
    dir.write("m.mtl", "newmtl red\nKd 0.8 0.1 0.1\nmap_Kd nope.png\n");
    // Two faces of two vertices and one repeating a vertex (lines 10, 11
    // and 13), usemtl naming nothing twice (lines 12 and 14), a texture
    // that is not there.
    dir.write("m.obj", "mtllib m.mtl\n" + square + "usemtl red\nf 1 2\nf 3 4\n" +
                           "usemtl blue\nf 1 1 2\nusemtl green\nf 1/1 2/2 3/3\n" +
                           "usemtl red\nf 1/1 3/3 4/3\n");
    const std::string json =
        dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "m.obj", "material": "white"}]})");
    const Scene scene = load_scene_file(json);
    CAPTURE(scene.warnings.size());
    for (const std::string& w : scene.warnings) {
        CAPTURE(w);
    }
    REQUIRE(scene.warnings.size() == 5);
    CHECK(scene.warnings[0] == obj +
                                   ":10: warning: a face of 2 vertices; skipped (2 times; the "
                                   "first here) (--strict refuses it)");
    CHECK(warnings_with(scene, obj + ":13: warning: a face of fewer than 3 distinct vertices; "
                                     "skipped (--strict refuses it)") == 1);
    CHECK(warnings_with(scene, obj + ":12: warning: usemtl 'blue': no material of that name in "
                                     "its mtllib files (m.mtl); its faces take the shape's "
                                     "material") == 1);
    CHECK(warnings_with(scene, obj + ":14: warning: usemtl 'green'") == 1);
    CHECK(warnings_with(scene, mtl + ": warning: material 'red': map_Kd 'nope.png': " + dir.path() +
                                   "/nope.png: cannot open texture") == 1);
    // What is left renders: the green face in white (the shape's), the
    // red one red without its texture.
    REQUIRE(scene.shapes.size() == 2);
    std::size_t triangles = 0;
    for (const Shape& s : scene.shapes) {
        triangles += s.triangles.size();
        const Material& m = scene.materials[static_cast<std::size_t>(s.material)];
        CHECK(m.texture == -1);
        CHECK((m.name == "white" || m.name == "red"));
    }
    CHECK(triangles == 2);
    // Strict: the first defect, as the error it always was.
    CHECK_THAT(strict_error(json),
               EndsWith(obj + ":10: expected a face of 3 to 10000 vertices, got 2"));
    dir.write("m.obj", "mtllib m.mtl\n" + square + "f 1 1 2\nf 1 2 3\n");
    CHECK_THAT(strict_error(json), EndsWith(obj + ":9: a face of fewer than 3 distinct vertices"));
    dir.write("m.obj", "mtllib m.mtl\n" + square + "usemtl blue\nf 1 2 3\n");
    CHECK_THAT(strict_error(json),
               EndsWith(obj + ":9: usemtl 'blue': no material of that name in its mtllib files "
                              "(m.mtl)"));
    dir.write("m.obj", "mtllib m.mtl\n" + square + "usemtl red\nf 1/1 2/2 3/3\n");
    CHECK_THAT(strict_error(json), Contains(mtl + ": material 'red': map_Kd 'nope.png': " +
                                            dir.path() + "/nope.png: cannot open texture"));
    // A missing MTL file: its materials are left out, and the usemtl
    // naming them warn.
    dir.write("m.obj", "mtllib gone.mtl\n" + square + "usemtl red\nf 1 2 3\n");
    const Scene gone = load_scene_file(json);
    CHECK(warnings_with(gone, obj + ":1: warning: mtllib 'gone.mtl': cannot open " + dir.path() +
                                  "/gone.mtl; its materials are left out") == 1);
    CHECK(warnings_with(gone, obj + ":9: warning: usemtl 'red'") == 1);
    CHECK_THAT(strict_error(json), Contains(obj + ":1: mtllib 'gone.mtl': "));
}

TEST_CASE("a glTF texture that is not there: a warning from the reader's child process",
          "[defects][mesh]") {
    TempDir dir;
    const float values[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    const std::string buffer(reinterpret_cast<const char*>(values), sizeof values);
    dir.write("t.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
  "materials": [{"name": "logo", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                 "baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
  "textures": [{"source": 0}], "images": [{"uri": "missing.png"}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
                            base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]})");
    // No "material" on the mesh: every face has the file's.
    const std::string json =
        dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "t.gltf"}]})");
    const Scene scene = load_scene_file(json);
    REQUIRE(scene.warnings.size() == 1);
    CHECK(scene.warnings[0] == dir.path() +
                                   "/t.gltf: warning: material 'logo': base colour "
                                   "texture 'missing.png': " +
                                   dir.path() +
                                   "/missing.png: cannot open texture: No such file or "
                                   "directory; its factor is used alone (--strict refuses it)");
    REQUIRE(scene.shapes.size() == 1);
    const Material& logo = scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
    CHECK(logo.name == "logo");
    CHECK(logo.texture == -1);
    CHECK(logo.color == glm::vec3(0.5f));
    CHECK_THAT(strict_error(json), Contains("/missing.png: cannot open texture"));
}

TEST_CASE("glTF nodes repeating another's mesh and transform: drawn once, with a warning",
          "[defects][mesh]") {
    // One triangle, placed by five nodes: the origin twice, moved along x,
    // the origin again, and the origin by a node with a child (which
    // stays in the file: only leaves are left out before the reader).
    const std::string nodes = R"("scenes": [{"nodes": [0, 1, 2, 3, 4]}],
  "nodes": [{"mesh": 0}, {"mesh": 0}, {"mesh": 0, "translation": [2, 0, 0]}, {"mesh": 0},
            {"mesh": 0, "children": [5]}, {"translation": [0, 5, 0]}],)";
    const float values[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::string bin(reinterpret_cast<const char*>(values), sizeof values);
    // The .glb: the same nodes, the triangle in its binary chunk.
    std::string glb_json = R"({"asset": {"version": "2.0"}, "scene": 0, )" + nodes + R"(
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"byteLength": 36}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}]})";
    glb_json.append((4 - glb_json.size() % 4) % 4, ' ');
    const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<char*>(&v), 4); };
    const std::string glb = "glTF" + u32(2) +
                            u32(static_cast<std::uint32_t>(28 + glb_json.size() + 36)) +
                            u32(static_cast<std::uint32_t>(glb_json.size())) + "JSON" + glb_json +
                            u32(36) + std::string("BIN\0", 4) + bin;
    TempDir dir;
    dir.write("n.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, )" + nodes + "\n  " +
                            gltf_one_triangle_tail());
    dir.write("n.glb", glb);
    for (const std::string name : {"n.gltf", "n.glb"}) {
        INFO(name);
        const std::string json =
            dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": ")" +
                                    name + R"(", "material": "white"}]})");
        const Scene scene = load_scene_file(json);
        REQUIRE(scene.warnings.size() == 1);
        CHECK(scene.warnings[0] == dir.path() + "/" + name +
                                       ": warning: a node repeats another node's mesh and "
                                       "transform; drawn once (3 times) (--strict refuses it)");
        REQUIRE(scene.shapes.size() == 1);
        REQUIRE(scene.shapes[0].triangles.size() == 2);
        CHECK(scene.shapes[0].triangles[0].v1.x == Approx(1.0f));
        CHECK(scene.shapes[0].triangles[1].v1.x == Approx(3.0f));
        CHECK_THAT(strict_error(json),
                   Contains("/" + name + ": node 1 repeats node 0's mesh and transform"));
        // What the reader is given: the two repeating leaves out of the
        // scene's list, the rest as it was.
        std::size_t removed = 0;
        std::string first;
        const std::string text =
            gltf_without_repeated_leaves(read_input_file(dir.path() + "/" + name, "mesh"),
                                         name == "n.glb", name, &removed, &first);
        CHECK(removed == 2);
        CHECK(first == "node 1 repeats node 0's mesh and transform");
        const nlohmann::json doc = nlohmann::json::parse(gltf_json_text(text, name == "n.glb"));
        CHECK(doc["scenes"][0]["nodes"] == nlohmann::json({0, 2, 4}));
        CHECK(doc["nodes"].size() == 6);
        if (name == "n.glb") {
            CHECK(text.substr(text.size() - 36) == bin);  // the binary chunk kept
        }
    }
}

TEST_CASE("repeated glTF nodes: a .glb with an unpadded JSON length, a node listed twice",
          "[defects][mesh]") {
    const float values[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::string bin(reinterpret_cast<const char*>(values), sizeof values);
    const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<char*>(&v), 4); };
    const std::string mesh = R"(
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"byteLength": 36}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}]})";
    // A .glb whose JSON chunk's length counts its text but not the spaces
    // padding it to 4 bytes (against the format; assimp reads it).
    const auto glb = [&](std::string json) {
        while (json.size() % 4 != 1) {
            json.insert(json.size() - 1, " ");
        }
        const std::uint32_t length = static_cast<std::uint32_t>(json.size());
        const std::string padded = json + "   ";
        return "glTF" + u32(2) + u32(static_cast<std::uint32_t>(28 + padded.size() + 36)) +
               u32(length) + "JSON" + padded + u32(36) + std::string("BIN\0", 4) + bin;
    };
    TempDir dir;
    const auto load = [&](const std::string& name) {
        return load_scene_file(
            dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": ")" +
                                    name + R"(", "material": "white"}]})"));
    };
    // Nodes 0 and 1 at the origin: 1 is left out, 0 drawn.
    dir.write("odd.glb", glb(R"({"asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0}, {"mesh": 0}],)" +
                             mesh));
    const Scene odd = load("odd.glb");
    REQUIRE(odd.shapes.size() == 1);
    CHECK(odd.shapes[0].triangles.size() == 1);
    REQUIRE(odd.warnings.size() == 1);
    CHECK_THAT(odd.warnings[0], Contains("drawn once (--strict refuses it)"));
    // Node 2 is a root at the origin, repeating node 0, and node 1's child
    // moved by 5: listed twice, it stays in the file, and only its place
    // at the origin is left out.
    dir.write("twice.glb", glb(R"({"asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0, 2, 1]}],
  "nodes": [{"mesh": 0}, {"children": [2], "translation": [5, 0, 0]}, {"mesh": 0}],)" +
                               mesh));
    const Scene twice = load("twice.glb");
    REQUIRE(twice.shapes.size() == 1);
    REQUIRE(twice.shapes[0].triangles.size() == 2);
    CHECK(twice.shapes[0].triangles[0].v1.x == Approx(1.0f));
    CHECK(twice.shapes[0].triangles[1].v1.x == Approx(6.0f));
    REQUIRE(twice.warnings.size() == 1);
    CHECK_THAT(twice.warnings[0], Contains("drawn once (--strict refuses it)"));
}

TEST_CASE("a mesh without a material takes the default grey, or the scene's \"default\"",
          "[defects][scene_loader]") {
    TempDir dir;
    dir.write("m.obj", square + "f 1 2 3\n");
    const std::string plain =
        dir.write("a.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "m.obj"},
                                 {"type": "mesh", "file": "m.obj", "position": [2, 0, 0]}]})");
    const Scene scene = load_scene_file(plain);
    CHECK(scene.warnings.empty());
    REQUIRE(scene.shapes.size() == 2);
    REQUIRE(scene.materials.size() == 2);  // white, and the default added once
    const Material& m = scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
    CHECK(scene.shapes[1].material == scene.shapes[0].material);
    CHECK(m.name == "default");
    CHECK(m.type == MaterialType::diffuse);
    CHECK(m.color == glm::vec3(0.8f));
    const std::string own =
        dir.write("b.json", R"({"materials": {"default": {"type": "glossy", "color": [1, 1, 1],
                                                 "roughness": 0.2}},
                      "shapes": [{"type": "mesh", "file": "m.obj"}]})");
    const Scene with_own = load_scene_file(own);
    REQUIRE(with_own.materials.size() == 1);
    CHECK(with_own.materials[0].type == MaterialType::glossy);
    CHECK(with_own.shapes[0].material == 0);
    // The primitives still name theirs.
    const std::string plane =
        dir.write("c.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "plane", "size": [1, 1]}]})");
    CHECK_THAT(strict_error(plane), Contains("/shapes/0/material: required key is missing"));
}

TEST_CASE("trac0r_viewer renders a model with defects, warning once a kind; --strict refuses",
          "[defects][cli]") {
    TempDir dir;
    dir.write("m.obj", square + "f 1 2\nf 1 2 3\n");
    const std::string json =
        dir.write("s.json", R"({"materials": {"lamp": {"type": "emissive", "color": [1, 1, 1],
                                              "emittance": 1}},
                      "shapes": [{"type": "mesh", "file": "m.obj", "material": "lamp"}]})");
    const std::string png = dir.path() + "/o.png";
    const auto lenient = trac0r_test::run_viewer_process(
        json + " --headless --width 8 --height 6 --spp 1 --output " + png);
    CAPTURE(lenient.err);
    CHECK(lenient.exit_code == 0);
    CHECK_THAT(lenient.err, Contains(dir.path() + "/m.obj:8: warning: a face of 2 vertices; "
                                                  "skipped (--strict refuses it)"));
    std::remove(png.c_str());
    const auto refused = trac0r_test::run_viewer_process(
        json + " --strict --headless --width 8 --height 6 --spp 1 --output " + png);
    CAPTURE(refused.err);
    CHECK(refused.exit_code != 0);
    CHECK_THAT(refused.err,
               Contains(dir.path() + "/m.obj:8: expected a face of 3 to 10000 vertices, got 2"));
    CHECK_FALSE(std::ifstream(png).good());
}
