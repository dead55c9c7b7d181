// Tangents for normal maps (trac0r/tangents.h, shape.h): computed from
// texture coordinates as MikkTSpace does where a file gives none, and a
// glTF's own TANGENT where it does, through the shape's transform.
#include "test_support.h"

#include "trac0r/tangents.h"

#include <fstream>
#include <iterator>

using namespace trac0r;

namespace {

const float pi = 3.14159265f;

TriangleUv uv_of(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    TriangleUv uv;
    uv.present = true;
    uv.uv = {a, b, c};
    return uv;
}

// The unit floor (y = 0, normal +y) with texture coordinates u = u_sign x,
// v = -z.
Shape floor_with_uvs(float u_sign) {
    Shape floor = make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(1.0f), 0);
    for (const Triangle& t : floor.triangles) {
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        TriangleUv uv;
        uv.present = true;
        for (int k = 0; k < 3; ++k) {
            uv.uv[k] = glm::vec2(u_sign * v[k].x, -v[k].z);
        }
        floor.uvs.push_back(uv);
    }
    return floor;
}

void require_vec(const glm::vec3& got, const glm::vec3& expected, float margin = 1e-6f) {
    CAPTURE(got.x, got.y, got.z, expected.x, expected.y, expected.z);
    REQUIRE(got.x == Approx(expected.x).margin(margin));
    REQUIRE(got.y == Approx(expected.y).margin(margin));
    REQUIRE(got.z == Approx(expected.z).margin(margin));
}

}  // namespace

TEST_CASE("uv_tangents: along increasing u, signed by the layout's handedness", "[tangents]") {
    for (float u_sign : {1.0f, -1.0f}) {
        CAPTURE(u_sign);
        const std::vector<VertexTangentTriple> tangents = uv_tangents(floor_with_uvs(u_sign));
        REQUIRE(tangents.size() == 2);
        for (const VertexTangentTriple& t : tangents) {
            for (const glm::vec4& corner : t) {
                require_vec(glm::vec3(corner), glm::vec3(u_sign, 0.0f, 0.0f));
                // The bitangent w cross(n, t) is the direction of v: -z.
                const glm::vec3 b = corner.w * glm::cross(glm::vec3(0, 1, 0), glm::vec3(corner));
                require_vec(b, glm::vec3(0.0f, 0.0f, -1.0f));
            }
        }
    }
}

TEST_CASE("uv_tangents: one vertex, one tangent, in the plane of its normal", "[tangents]") {
    // A roof: two triangles meeting at the ridge from (0, 1, 0) to
    // (1, 1, 0), sloping down to z = +1 and z = -1, with the ridge's
    // corners sharing the normal +y (smooth) and u = z across both. Each
    // triangle's own tangent runs down or up its slope; at the ridge both
    // project onto the plane of +y as +z, and the corners there are one
    // vertex: they share it exactly.
    Shape roof;
    const glm::vec3 r0(0, 1, 0), r1(1, 1, 0), front(0.5f, 0, 1), back(0.5f, 0, -1);
    roof.triangles = {Triangle(r0, front, r1), Triangle(r1, back, r0)};
    const glm::vec3 up(0, 1, 0);
    const glm::vec3 n_front = glm::normalize(glm::vec3(0, 1, 1));
    const glm::vec3 n_back = glm::normalize(glm::vec3(0, 1, -1));
    roof.normals = {{up, n_front, up}, {up, n_back, up}};
    const auto uv = [](const glm::vec3& p) { return glm::vec2(p.z, p.x); };
    roof.uvs = {uv_of(uv(r0), uv(front), uv(r1)), uv_of(uv(r1), uv(back), uv(r0))};
    const std::vector<VertexTangentTriple> t = uv_tangents(roof);
    REQUIRE(t.size() == 2);
    // Ridge corners: r0 is corner 0 of the first and 2 of the second.
    REQUIRE(t[0][0] == t[1][2]);
    REQUIRE(t[0][2] == t[1][0]);
    require_vec(glm::vec3(t[0][0]), glm::vec3(0, 0, 1));
    // The eaves' corners keep their own triangle's tangent, in the plane
    // of their own normal: down the front slope, up the back one.
    require_vec(glm::vec3(t[0][1]), glm::normalize(glm::vec3(0, -1, 1)));
    require_vec(glm::vec3(t[1][1]), glm::normalize(glm::vec3(0, 1, 1)));
    for (int i = 0; i < 2; ++i) {
        for (int k = 0; k < 3; ++k) {
            REQUIRE(glm::length(glm::vec3(t[i][k])) == Approx(1.0f).epsilon(1e-6));
            REQUIRE(std::fabs(glm::dot(glm::vec3(t[i][k]), roof.normals[i][k])) < 1e-6f);
        }
    }
}

TEST_CASE("uv_tangents: averages over a vertex's triangles, weighted by angle", "[tangents]") {
    // A fan of two flat triangles in the floor around the origin, sharing
    // the corner there, with u running along x in one and along z in the
    // other (so their own tangents are +x and +z): the shared corner gets
    // the angle-weighted mean, here 90 and 45 degrees.
    Shape fan;
    const glm::vec3 o(0, 0, 0);
    fan.triangles = {Triangle(o, glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)),
                     Triangle(o, glm::vec3(1, 0, 0), glm::vec3(1, 0, -1))};
    // First: u = x, v = z (its angle at o 90 degrees); second: u = -z, v = x
    // (45 degrees). The shared corner has the same position, normal, (u, v)
    // = (0, 0) and sign in both.
    fan.uvs = {uv_of({0, 0}, {0, 1}, {1, 0}), uv_of({0, 0}, {0, 1}, {1, 1})};
    const std::vector<VertexTangentTriple> t = uv_tangents(fan);
    REQUIRE(t[0][0].w == t[1][0].w);
    const glm::vec3 expected =
        glm::normalize(0.5f * pi * glm::vec3(1, 0, 0) + 0.25f * pi * glm::vec3(0, 0, -1));
    require_vec(glm::vec3(t[0][0]), expected);
    REQUIRE(t[0][0] == t[1][0]);
    // A seam (other coordinates at the same position) makes two vertices
    // there: each triangle keeps its own tangent.
    Shape seam = fan;
    for (glm::vec2& uv : seam.uvs[1].uv) {
        uv += glm::vec2(5.0f, 0.0f);
    }
    const std::vector<VertexTangentTriple> s = uv_tangents(seam);
    require_vec(glm::vec3(s[0][0]), glm::vec3(1, 0, 0));
    require_vec(glm::vec3(s[1][0]), glm::vec3(0, 0, -1));
}

TEST_CASE("uv_tangents: none without coordinates, or with degenerate ones", "[tangents]") {
    Shape floor = floor_with_uvs(1.0f);
    floor.uvs[0].present = false;
    floor.uvs[1] = uv_of({0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f});
    for (const VertexTangentTriple& t : uv_tangents(floor)) {
        REQUIRE(t == VertexTangentTriple{});
    }
    Shape bare = make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(1.0f), 0);
    REQUIRE(uv_tangents(bare) == std::vector<VertexTangentTriple>(2, VertexTangentTriple{}));
}

TEST_CASE("make_shape turns tangents with the model, flipping the sign where it mirrors",
          "[tangents]") {
    const std::vector<Triangle> one = {
        Triangle(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 0, -1))};
    const glm::vec4 file(0.0f, 0.0f, 1.0f, -1.0f);
    const std::vector<VertexTangentTriple> tangents = {{file, file, file}};
    const glm::mat4 turn =
        model_matrix(glm::vec3(3.0f), glm::vec3(0.0f, 0.5f * pi, 0.0f), glm::vec3(2.0f));
    const Shape turned = make_shape(one, turn, 0, {}, {}, tangents);
    REQUIRE(turned.tangents.size() == 1);
    const glm::vec3 expected = glm::normalize(glm::mat3(turn) * glm::vec3(file));
    for (const glm::vec4& t : turned.tangents[0]) {
        require_vec(glm::vec3(t), expected);
        REQUIRE(t.w == -1.0f);
    }
    const glm::mat4 mirror = model_matrix(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1, 1, -1));
    const Shape mirrored = make_shape(one, mirror, 0, {}, {}, tangents);
    for (const glm::vec4& t : mirrored.tangents[0]) {
        require_vec(glm::vec3(t), glm::vec3(0, 0, -1));
        REQUIRE(t.w == 1.0f);
    }
}

namespace {

// Two triangles of the floor (normal +y) with texture coordinates
// (x, -z) and the tangent (0, 0, 1) with sign -1 at every vertex (not the
// coordinates' +x), a normal texture on its material; `node` is its node.
std::string tangent_floor_gltf(const std::string& node) {
    const float p[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, 0}, {1, 0, -1}, {0, 0, -1}};
    std::vector<float> values;
    for (const auto& v : p) {
        values.insert(values.end(), {v[0], v[1], v[2]});
    }
    for (int i = 0; i < 6; ++i) {
        values.insert(values.end(), {0.0f, 1.0f, 0.0f});
    }
    for (const auto& v : p) {
        values.insert(values.end(), {v[0], -v[2]});
    }
    for (int i = 0; i < 6; ++i) {
        values.insert(values.end(), {0.0f, 0.0f, 1.0f, -1.0f});
    }
    const std::string buffer(reinterpret_cast<const char*>(values.data()),
                             values.size() * sizeof(float));
    REQUIRE(buffer.size() == 288);
    // A 1 x 1 PNG normal map (flat: 128, 128, 255).
    TempDir dir;
    Rgb8Image image;
    image.width = 1;
    image.height = 1;
    image.bytes = {128, 128, 255};
    const std::string png_path = dir.path() + "/n.png";
    write_png(png_path, image);
    std::ifstream png_file(png_path, std::ios::binary);
    const std::string png((std::istreambuf_iterator<char>(png_file)),
                          std::istreambuf_iterator<char>());
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [)" +
           node + R"(],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2,
                                             "TANGENT": 3}, "material": 0}]}],
  "materials": [{"name": "bumpy", "normalTexture": {"index": 0}}],
  "textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,)" +
           base64(png) + R"("}],
  "buffers": [{"byteLength": 288, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                  {"buffer": 0, "byteOffset": 72, "byteLength": 72},
                  {"buffer": 0, "byteOffset": 144, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 192, "byteLength": 96}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3",
     "min": [0, 0, -1], "max": [1, 0, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5126, "count": 6, "type": "VEC4"}]})";
}

}  // namespace

TEST_CASE("a glTF's TANGENT is the shape's, through its node and the scene's transform",
          "[tangents][mesh]") {
    TempDir dir;
    struct Case {
        std::string node;
        glm::vec3 orientation;
        glm::vec4 expected;
    };
    const Case cases[] = {
        {R"({"mesh": 0})", glm::vec3(0.0f), glm::vec4(0, 0, 1, -1)},
        // A mirroring node (x -> -x) leaves the direction and flips the sign.
        {R"({"mesh": 0, "scale": [-1, 1, 1]})", glm::vec3(0.0f), glm::vec4(0, 0, 1, 1)},
        // The scene's turn by 90 degrees about y takes +z to +x.
        {R"({"mesh": 0})", glm::vec3(0.0f, 0.5f * pi, 0.0f), glm::vec4(1, 0, 0, -1)},
    };
    for (const Case& c : cases) {
        CAPTURE(c.node, c.orientation.y);
        const std::string path = dir.write("floor.gltf", tangent_floor_gltf(c.node));
        const MeshParts mesh =
            load_mesh_parts(path, glm::vec3(0.0f), c.orientation, glm::vec3(1.0f), 0, true, true);
        REQUIRE(mesh.parts.size() == 1);
        REQUIRE(mesh.materials.size() == 1);
        REQUIRE(mesh.materials[0].normal_texture == 0);
        const Shape& shape = mesh.parts[0].shape;
        REQUIRE(shape.tangents.size() == 2);
        for (const VertexTangentTriple& t : shape.tangents) {
            for (const glm::vec4& corner : t) {
                require_vec(glm::vec3(corner), glm::vec3(c.expected), 1e-5f);
                REQUIRE(corner.w == c.expected.w);
            }
        }
        // Packed for the kernel as they are, not computed from the
        // coordinates (whose tangent is +-x).
        Scene scene;
        scene.materials = mesh.materials;
        scene.textures = mesh.textures;
        Shape placed = shape;
        placed.material = 0;
        scene.shapes.push_back(placed);
        const PackedScene packed = pack_scene(scene);
        REQUIRE(packed.tangents.size() == 2);
        for (const kernel::VertexTangents& t : packed.tangents) {
            require_vec(glm::vec3(t.t0), glm::vec3(c.expected), 1e-5f);
            REQUIRE(t.t0.w == c.expected.w);
        }
    }
}
