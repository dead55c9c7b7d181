// OBJ smoothing groups (trac0r/smoothing_groups.h): a file without vertex
// normals is shaded smooth within each group (`s 1`), flat outside them
// (`s off`, `s 0`), as its author's program shows it.
#include "test_support.h"

#include "trac0r/smoothing_groups.h"

using namespace trac0r;

namespace {

void require_vec(const glm::vec3& got, const glm::vec3& expected) {
    CAPTURE(got.x, got.y, got.z, expected.x, expected.y, expected.z);
    REQUIRE(got.x == Approx(expected.x).margin(1e-6));
    REQUIRE(got.y == Approx(expected.y).margin(1e-6));
    REQUIRE(got.z == Approx(expected.z).margin(1e-6));
}

// A roof: two triangles meeting at the ridge from vertex 0 (0, 1, 0) to 1
// (1, 1, 0), sloping to z = +1 (vertex 2) and z = -1 (vertex 3); their
// normals (0, 1, 1) and (0, 1, -1), normalised.
const std::vector<glm::vec3> roof = {{0, 1, 0}, {1, 1, 0}, {0.5f, 0, 1}, {0.5f, 0, -1}};

}  // namespace

TEST_CASE("smoothing_group_normals: angle-weighted means within a group, flat outside",
          "[smoothing]") {
    const float s = 1.0f / std::sqrt(2.0f);
    // One group: at the ridge's vertices the two normals meet. Vertex 0's
    // angles in the two triangles are equal (mirror images), so the mean
    // is straight up; the eaves keep their own triangle's normal.
    std::vector<GroupedTriangle> one = {{{0, 2, 1}, 1}, {{1, 3, 0}, 1}};
    std::vector<VertexNormalTriple> n = smoothing_group_normals(roof, one);
    require_vec(n[0][0], glm::vec3(0, 1, 0));
    require_vec(n[0][2], glm::vec3(0, 1, 0));
    require_vec(n[1][0], glm::vec3(0, 1, 0));
    require_vec(n[0][1], glm::vec3(0, s, s));
    require_vec(n[1][1], glm::vec3(0, s, -s));
    // Two groups (or group 0): a sharp ridge.
    std::vector<GroupedTriangle> two = {{{0, 2, 1}, 1}, {{1, 3, 0}, 2}};
    n = smoothing_group_normals(roof, two);
    for (int k = 0; k < 3; ++k) {
        require_vec(n[0][k], glm::vec3(0, s, s));
        require_vec(n[1][k], glm::vec3(0, s, -s));
    }
    std::vector<GroupedTriangle> off = {{{0, 2, 1}, 0}, {{1, 3, 0}, 1}};
    n = smoothing_group_normals(roof, off);
    REQUIRE(n[0] == VertexNormalTriple{});
    require_vec(n[1][0], glm::vec3(0, s, -s));
    // Unequal angles weigh: a fan around vertex 0 of a 90 degree triangle
    // in the floor (normal +y) and a 45 degree one in the wall x = 0
    // (normal +x): at vertex 0 the mean (pi/2 y + pi/4 x), normalised.
    const std::vector<glm::vec3> fan = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 1, 1}};
    std::vector<GroupedTriangle> corner = {{{0, 1, 2}, 1}, {{0, 3, 4}, 1}};
    n = smoothing_group_normals(fan, corner);
    const float pi = 3.14159265f;
    require_vec(n[0][0],
                glm::normalize(0.5f * pi * glm::vec3(0, 1, 0) + 0.25f * pi * glm::vec3(1, 0, 0)));
    REQUIRE(n[1][0] == n[0][0]);
}

TEST_CASE("an OBJ without vn is smooth within its smoothing groups, flat without",
          "[smoothing][mesh]") {
    TempDir dir;
    const std::string vertices = "v 0 1 0\nv 1 1 0\nv 0.5 0 1\nv 0.5 0 -1\n";
    const float s = 1.0f / std::sqrt(2.0f);
    SECTION("s 1: one group, smooth across the ridge (LF and CR LF lines)") {
        for (const std::string& text :
             {vertices + "s 1\nf 1 3 2\nf 2 4 1\n",
              std::string("v 0 1 0\r\nv 1 1 0\r\nv 0.5 0 1\r\nv 0.5 0 -1\r\ns 1\r\n"
                          "f 1 3 2\r\nf 2 4 1\r\n")}) {
            const Shape shape = load_obj_mesh(dir.write("a.obj", text), glm::vec3(0.0f),
                                              glm::vec3(0.0f), glm::vec3(1.0f), 0);
            REQUIRE(shape.normals.size() == 2);
            require_vec(shape.normals[0][0], glm::vec3(0, 1, 0));
            require_vec(shape.normals[0][1], glm::vec3(0, s, s));
        }
    }
    SECTION("s 1 and s 2: sharp between groups") {
        const Shape shape =
            load_obj_mesh(dir.write("b.obj", vertices + "s 1\nf 1 3 2\ns 2\nf 2 4 1\n"),
                          glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0);
        REQUIRE(shape.normals.size() == 2);
        require_vec(shape.normals[0][0], glm::vec3(0, s, s));
        require_vec(shape.normals[1][0], glm::vec3(0, s, -s));
    }
    SECTION("s off, and no s at all: flat") {
        for (const std::string& groups :
             {std::string("s off\n"), std::string("s 0\n"), std::string()}) {
            const Shape shape =
                load_obj_mesh(dir.write("c.obj", vertices + groups + "f 1 3 2\nf 2 4 1\n"),
                              glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0);
            REQUIRE(shape.normals.empty());
        }
    }
    SECTION("the file's vn win over its groups; \"smooth\": false is flat") {
        const std::string text = vertices + "vn 1 0 0\ns 1\nf 1//1 3//1 2//1\nf 2 4 1\n";
        const Shape shape = load_obj_mesh(dir.write("d.obj", text), glm::vec3(0.0f),
                                          glm::vec3(0.0f), glm::vec3(1.0f), 0);
        REQUIRE(shape.normals.size() == 2);
        require_vec(shape.normals[0][0], glm::vec3(1, 0, 0));
        // The second face alone in its group: its own normal.
        require_vec(shape.normals[1][0], glm::vec3(0, s, -s));
        const Shape flat =
            load_obj_mesh(dir.write("e.obj", vertices + "s 1\nf 1 3 2\nf 2 4 1\n"), glm::vec3(0.0f),
                          glm::vec3(0.0f), glm::vec3(1.0f), 0, false);
        REQUIRE(flat.normals.empty());
    }
}

TEST_CASE("\"smooth_angle\" smooths a mesh without normals or groups below the angle",
          "[smoothing][scene_loader]") {
    TempDir dir;
    // The roof's two faces, without vn or s, meet at 90 degrees.
    dir.write("roof.obj", "v 0 1 0\nv 1 1 0\nv 0.5 0 1\nv 0.5 0 -1\nf 1 3 2\nf 2 4 1\n");
    const auto load = [&](const std::string& keys) {
        const std::string json =
            dir.write("s.json", R"({"materials": {"w": {"type": "diffuse", "color": [1, 1, 1]}},
                          "shapes": [{"type": "mesh", "file": "roof.obj", "material": "w")" +
                                    keys + "}]}");
        return load_scene_file(json);
    };
    const float s = 1.0f / std::sqrt(2.0f);
    // Above 90 degrees: smooth across the ridge (straight up there).
    const Scene smooth = load(R"(, "smooth_angle": 100)");
    REQUIRE(smooth.shapes[0].normals.size() == 2);
    require_vec(smooth.shapes[0].normals[0][0], glm::vec3(0, 1, 0));
    require_vec(smooth.shapes[0].normals[0][1], glm::vec3(0, s, s));
    // Below: each face its own normal (sharp, as flat).
    const Scene sharp = load(R"(, "smooth_angle": 80)");
    REQUIRE(sharp.shapes[0].normals.size() == 2);
    require_vec(sharp.shapes[0].normals[0][0], glm::vec3(0, s, s));
    require_vec(sharp.shapes[0].normals[1][0], glm::vec3(0, s, -s));
    // Without the key, or with "smooth": false: flat, as the file is.
    CHECK(load("").shapes[0].normals.empty());
    CHECK(load(R"(, "smooth_angle": 100, "smooth": false)").shapes[0].normals.empty());
    // A file's own normals win.
    dir.write("roof.obj",
              "v 0 1 0\nv 1 1 0\nv 0.5 0 1\nv 0.5 0 -1\nvn 1 0 0\n"
              "f 1//1 3//1 2//1\nf 2//1 4//1 1//1\n");
    require_vec(load(R"(, "smooth_angle": 100)").shapes[0].normals[0][0], glm::vec3(1, 0, 0));
    try {
        load(R"(, "smooth_angle": 200)");
        FAIL("loaded");
    } catch (const SceneError& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("/shapes/0/smooth_angle: expected degrees "
                                                       "in [0, 180], got 200"));
    }
}
