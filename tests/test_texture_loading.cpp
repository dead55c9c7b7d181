// Base-colour textures of OBJ + MTL and glTF models through scene files:
// the file's coordinates, the scene's room counted from each image's
// header, and the mistakes of texture statements.
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
// image_uri, sampled by `sampler` (a glTF sampler object; "": none); its
// buffer embedded.
std::string textured_triangle_gltf(const std::string& image_uri,
                                   const std::string& sampler = "") {
    const float values[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    const std::string buffer(reinterpret_cast<const char*>(values), sizeof values);
    return std::string(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
  "materials": [{"name": "logo", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                 "baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
  "textures": [{"source": 0)") +
           (sampler.empty() ? "" : ", \"sampler\": 0") + "}]" +
           (sampler.empty() ? "" : ", \"samplers\": [" + sampler + "]") +
           R"(, "images": [{"uri": ")" + image_uri + R"("}],
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
            CHECK(scene.textures[0].wrap_u == TextureWrap::repeat);
            CHECK(scene.textures[0].wrap_v == TextureWrap::repeat);
        }
    }
    SECTION("a glTF sampler's wrap modes, through the reader's child process") {
        dir.write("t.gltf",
                  textured_triangle_gltf("t.png", R"({"wrapS": 33071, "wrapT": 33648})"));
        const Scene scene = load_scene_file(mesh_scene("t.gltf"));
        REQUIRE(scene.textures.size() == 1);
        CHECK(scene.textures[0].wrap_u == TextureWrap::clamp);
        CHECK(scene.textures[0].wrap_v == TextureWrap::mirror);
        const PackedScene packed = pack_scene(scene);
        REQUIRE(packed.textures.size() == 1);
        CHECK(packed.textures[0].info.w == (1u | 2u << 2));
        dir.write("t.gltf", textured_triangle_gltf("t.png", R"({"wrapS": 10497})"));
        CHECK(load_scene_file(mesh_scene("t.gltf")).textures[0].wrap_u == TextureWrap::repeat);
    }
    SECTION("one image under two samplers is two textures; under one, one") {
        // Materials a and c take the image clamped, b repeated: assimp
        // gives each material its own copy of the sampler's modes.
        std::string gltf = textured_triangle_gltf("t.png", R"({"wrapS": 33071, "wrapT": 33071})");
        const auto swap = [&](const std::string& from, const std::string& to) {
            REQUIRE(gltf.find(from) != std::string::npos);
            gltf.replace(gltf.find(from), from.size(), to);
        };
        swap(R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0})",
             R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0},
                {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 1},
                {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 2})");
        swap(R"([{"name": "logo", )",
             R"([{"name": "a", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
                {"name": "b", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}},
                {"name": "c", )");
        swap(R"("textures": [{"source": 0, "sampler": 0}])",
             R"("textures": [{"source": 0, "sampler": 0}, {"source": 0}])");
        dir.write("t.gltf", gltf);
        const Scene scene = load_scene_file(mesh_scene("t.gltf"));
        REQUIRE(scene.textures.size() == 2);
        const auto texture_of = [&](const std::string& name) {
            for (const Material& m : scene.materials) {
                if (m.name == name) {
                    REQUIRE(m.texture >= 0);
                    return scene.textures[static_cast<std::size_t>(m.texture)];
                }
            }
            FAIL("no material " << name);
            return Texture();
        };
        CHECK(texture_of("a").wrap_u == TextureWrap::clamp);
        CHECK(texture_of("b").wrap_u == TextureWrap::repeat);
        CHECK(texture_of("b").wrap_v == TextureWrap::repeat);
        CHECK(texture_of("c").wrap_v == TextureWrap::clamp);
        CHECK(texture_of("a").source == texture_of("c").source);
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
        CHECK_THROWS_WITH(
            decode_texture("m.mtl: material 'a': map_Kd 'h.png'", "h.png", bytes, huge_png.size(),
                           (1u << 28) - 1),
            Equals("m.mtl: material 'a': map_Kd 'h.png': texture is 16384 x 16384 "
                   "texels, more than the scene has room for (268435455 more of "
                   "the " +
                   std::to_string(scene_texel_budget()) + " a scene may have on this machine)"));
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
            return load_mesh_parts(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true,
                                   true, texels);
        };
        CHECK_THROWS_WITH(
            load(n_obj, 11),
            Equals(dir.path() +
                   "/n.mtl: material 'n2': map_Kd 'n2.png': texture "
                   "is 2 x 2 texels, more than the scene has room for "
                   "(3 more of the " +
                   std::to_string(scene_texel_budget()) + " a scene may have on this machine)"));
        CHECK(load(n_obj, 12).textures.size() == 3);
        // A glTF's textures, counted in its import's child process.
        const std::string gltf = dir.write("t.gltf", textured_triangle_gltf("t.png"));
        CHECK_THROWS_WITH(
            load(gltf, 3),
            Equals(gltf +
                   ": material 'logo': base colour texture 't.png': "
                   "texture is 2 x 2 texels, more than the scene has room "
                   "for (3 more of the " +
                   std::to_string(scene_texel_budget()) + " a scene may have on this machine)"));
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
