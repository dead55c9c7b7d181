// glTF extensions that Debian's assimp (5.2) does not read, read by
// trac0r from the file's JSON (trac0r/gltf_json.h): KHR_texture_transform
// applied to the coordinates, matched to assimp's materials by name
// (assimp orders a file's materials its own way).
#include "test_support.h"

#include "trac0r/gltf_json.h"
#include "trac0r/gltf_nodes.h"
#include "trac0r/gltf_size.h"

#include <cmath>

using namespace trac0r;

namespace {

// Two triangles in the xy plane with coordinates (x, y) at their
// vertices: the first of material 0 ("moved": a base-colour texture with
// KHR_texture_transform `transform`), the second of material 1 ("plain":
// the same texture, none).
std::string two_materials_gltf(const std::string& transform) {
    const float values[30] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0,
                              2, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::string buffer(reinterpret_cast<const char*>(values), sizeof values);
    Rgb8Image image;
    image.width = 1;
    image.height = 1;
    image.bytes = {200, 100, 50};
    TempDir png_dir;
    const std::string png_path = png_dir.path() + "/t.png";
    write_png(png_path, image);
    std::ifstream png_file(png_path, std::ios::binary);
    const std::string png((std::istreambuf_iterator<char>(png_file)),
                          std::istreambuf_iterator<char>());
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"mesh": 1}],
  "extensionsUsed": ["KHR_texture_transform"],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "material": 0}]},
             {"primitives": [{"attributes": {"POSITION": 1, "TEXCOORD_0": 3}, "material": 1}]}],
  "materials": [{"name": "moved", "pbrMetallicRoughness": {"metallicFactor": 0,
                  "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": )" +
           transform + R"(}}}},
                {"name": "plain", "pbrMetallicRoughness": {"metallicFactor": 0,
                  "baseColorTexture": {"index": 0}}}],
  "textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,)" +
           base64(png) + R"("}],
  "buffers": [{"byteLength": 120, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                  {"buffer": 0, "byteOffset": 72, "byteLength": 48}],
  "accessors": [
    {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [2, 0, 0], "max": [3, 1, 0]},
    {"bufferView": 1, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC2"},
    {"bufferView": 1, "byteOffset": 24, "componentType": 5126, "count": 3, "type": "VEC2"}]})";
}

}  // namespace

TEST_CASE("KHR_texture_transform moves a material's texture coordinates", "[gltf][texture]") {
    // The buffer's coordinates (glTF's: v down from the image's top) are
    // (0, 0), (1, 0), (0, 1) on both triangles; assimp gives v up (1 - v).
    // The transform: offset (0.25, 0.5), rotation 90 degrees, scale
    // (2, 3): (u, v) -> (c 2u + s 3v + 0.25, -s 2u + c 3v + 0.5).
    TempDir dir;
    const std::string path = dir.write(
        "t.gltf",
        two_materials_gltf(
            R"({"offset": [0.25, 0.5], "rotation": 1.5707963267948966, "scale": [2, 3]})"));
    const MeshParts mesh =
        load_mesh_parts(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true, true);
    REQUIRE(mesh.parts.size() == 2);
    const glm::vec2 gltf_uv[3] = {{0, 0}, {1, 0}, {0, 1}};
    for (const MeshPart& part : mesh.parts) {
        const std::string& name = mesh.materials[static_cast<std::size_t>(part.material)].name;
        CAPTURE(name);
        REQUIRE(part.shape.uvs.size() == 1);
        for (int k = 0; k < 3; ++k) {
            // The vertex's own coordinates, by its x (the second triangle
            // is the first moved by 2 in x).
            const float x = part.shape.triangles[0].v0.x >= 2.0f ? 2.0f : 0.0f;
            const glm::vec3 p =
                k == 0 ? part.shape.triangles[0].v0
                       : (k == 1 ? part.shape.triangles[0].v1 : part.shape.triangles[0].v2);
            const glm::vec2 g =
                gltf_uv[static_cast<int>(p.x - x + 0.5f) + 2 * static_cast<int>(p.y + 0.5f)];
            glm::dvec2 expected(g.x, g.y);
            if (name == "moved") {
                expected = glm::dvec2(3.0 * g.y + 0.25, -2.0 * g.x + 0.5);
            }
            const glm::vec2 got = part.shape.uvs[0].uv[k];
            CAPTURE(k, g.x, g.y, got.x, got.y);
            CHECK(got.x == Approx(expected.x).margin(1e-6));
            CHECK(got.y == Approx(1.0 - expected.y).margin(1e-6));
        }
    }
}

TEST_CASE("gltf_material_extras: transforms as matrices, their differences, bad values", "[gltf]") {
    const std::string json = R"({"materials": [
      {"name": "a", "emissiveTexture": {"index": 0},
       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions":
          {"KHR_texture_transform": {"offset": [1, 2]}}}}},
      {"name": "b", "normalTexture": {"index": 0, "extensions":
          {"KHR_texture_transform": {"scale": [2, 2]}}}},
      {"name": "c"}]})";
    const std::vector<GltfMaterialExtras> extras = gltf_material_extras(json, "f.gltf");
    REQUIRE(extras.size() == 3);
    CHECK(extras[0].name == "a");
    CHECK(extras[0].uv_transform);
    CHECK(extras[0].uv_matrix == std::vector<double>{1, 0, 1, -0.0, 1, 2});
    CHECK(extras[0].transforms_differ);  // its emissive texture has none
    CHECK(extras[1].uv_transform);
    CHECK(extras[1].uv_matrix == std::vector<double>{2, 0, 0, -0.0, 2, 0});
    CHECK_FALSE(extras[1].transforms_differ);
    CHECK_FALSE(extras[2].uv_transform);
    CHECK_THROWS_WITH(gltf_material_extras(R"({"materials": [{"name": "x", "normalTexture":
        {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [1, "a"]}}}}]})",
                                           "f.gltf"),
                      Catch::Contains("f.gltf: material 'x': KHR_texture_transform: offset "
                                      "[1,\"a\"]: expected two finite numbers"));
}

TEST_CASE("a glTF's promised triangles, and a file promising more than the machine holds",
          "[gltf]") {
    // Mesh 0: 30 indices (10 triangles) and a strip of 5 vertices (3);
    // mesh 1: 9 vertices without indices (3). Node 0 and node 2 (a child
    // of node 1, moved) instance mesh 0, node 3 mesh 1; node 4 is in no
    // scene.
    const std::string json = R"({"scene": 0, "scenes": [{"nodes": [0, 1, 3]}],
      "nodes": [{"mesh": 0}, {"children": [2], "translation": [1, 0, 0]}, {"mesh": 0},
                {"mesh": 1}, {"mesh": 1}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0},
                                 {"attributes": {"POSITION": 1}, "mode": 5}]},
                 {"primitives": [{"attributes": {"POSITION": 2}}]}],
      "accessors": [{"count": 30}, {"count": 5}, {"count": 9}]})";
    CHECK(gltf_promised_triangles(json, "f.gltf") == 2 * (10 + 3) + 3);
    // Node 2 unmoved places mesh 0 where node 0 does: read once.
    std::string repeated = json;
    repeated.replace(repeated.find(R"(, "translation": [1, 0, 0])"), 26, "");
    CHECK(gltf_promised_triangles(repeated, "f.gltf") == 10 + 3 + 3);
    CHECK(gltf_promised_triangles("not json", "f.gltf") == 0);
    // 10^12 triangles: refused before the reader sees the file (its
    // buffer does not even exist).
    TempDir dir;
    const std::string path = dir.write("huge.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
      "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0}]}],
      "buffers": [{"byteLength": 4, "uri": "missing.bin"}],
      "bufferViews": [{"buffer": 0, "byteLength": 4}],
      "accessors": [{"bufferView": 0, "componentType": 5125, "count": 3000000000000,
                     "type": "SCALAR"},
                    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 1]}]})");
    CHECK_THROWS_WITH(
        load_mesh_parts(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true, true),
        Catch::Contains("huge.gltf: cannot read mesh: it promises 1000000000000 "
                        "triangles, which would take about "));
}

TEST_CASE("glTF nodes nested too deep for the reader are refused before it runs", "[gltf]") {
    // A chain of n nodes, the last placing the triangle: 257 levels below
    // the root is one too many (assimp's recursion crashed on 2 x 10^4).
    const auto chain = [](int n) {
        std::string nodes;
        for (int i = 0; i + 1 < n; ++i) {
            nodes += R"({"children": [)" + std::to_string(i + 1) + "]}, ";
        }
        return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [)" +
               nodes +
               R"({"mesh": 0}],
  )" + gltf_one_triangle_tail();
    };
    TempDir dir;
    const std::string deep = dir.write("deep.gltf", chain(258));
    CHECK_THROWS_WITH(
        load_mesh_parts(deep, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true, true),
        dir.path() + "/deep.gltf: cannot read mesh: its nodes nest deeper than 256");
    CHECK_THROWS_AS(gltf_promised_triangles(chain(258), "deep.gltf"), GltfNodesTooDeep);
    // 256 levels below the root: read, the triangle where the chain puts it.
    const std::string fits = dir.write("fits.gltf", chain(257));
    const MeshParts parts =
        load_mesh_parts(fits, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true, true);
    REQUIRE(parts.parts.size() == 1);
    CHECK(parts.parts[0].shape.triangles.size() == 1);
}
