// PLY and glTF 2.0 meshes (assimp_mesh.cpp, in its child process) through
// scene files: their normals, materials and transforms, .glb, and their
// mistakes as one message naming the file.
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
