// Material names and values in OBJ and MTL files as Blender and assimp
// read them (trac0r/obj_checker.h, mtl_checker.h): a name is the rest of its usemtl or
// newmtl line, blanks and all; a colour of one number is grey; a value out
// of the MTL format's range is taken as the nearest within, with a
// warning (an error when strict).
#include "test_support.h"

using namespace trac0r;

namespace {

const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

const Material& material_of(const Scene& scene, std::size_t shape) {
    return scene.materials[static_cast<std::size_t>(scene.shapes[shape].material)];
}

}  // namespace

TEST_CASE("material names with blanks, and one-number MTL colours", "[mtl][mesh]") {
    TempDir dir;
    // Leading, inner (a tab among them) and trailing blanks; the usemtl's
    // differ from the newmtl's but for their ends.
    dir.write("m.mtl",
              "newmtl   Hard Shiny\tPlastic  \nKd 0.25\nKs 0 0 0\n"
              "newmtl red\nKd 0.8 0.1 0.1\n");
    dir.write("m.obj", "mtllib m.mtl\n" + triangle + "usemtl  Hard Shiny\tPlastic \nf 1 2 3\n" +
                           "usemtl red\nf 1 3 2\n");
    const std::string json =
        dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "m.obj"}]})");
    LoadOptions strict;
    strict.strict = true;
    const Scene scene = load_scene_file(json, strict);
    CHECK(scene.warnings.empty());
    REQUIRE(scene.shapes.size() == 2);
    CHECK(material_of(scene, 0).name == "Hard Shiny Plastic");
    CHECK(material_of(scene, 0).color == glm::vec3(0.25f));
    CHECK(material_of(scene, 1).name == "red");
    CHECK(material_of(scene, 1).color == glm::vec3(0.8f, 0.1f, 0.1f));
}

TEST_CASE("a usemtl or newmtl without a name: a warning, refused when strict",
          "[mtl][mesh][defects]") {
    TempDir dir;
    dir.write("m.mtl", "newmtl\nKd 0.5 0.5 0.5\nnewmtl red\nKd 0.8 0.1 0.1\n");
    dir.write("m.obj", "mtllib m.mtl\n" + triangle + "usemtl red\nf 1 2 3\nusemtl\nf 1 3 2\n");
    const std::string json =
        dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "m.obj", "material": "white"}]})");
    const Scene scene = load_scene_file(json);
    REQUIRE(scene.warnings.size() == 2);
    CHECK(scene.warnings[0] == dir.path() +
                                   "/m.obj:7: warning: usemtl without a name; its faces take the "
                                   "shape's material (--strict refuses it)");
    CHECK(scene.warnings[1] == dir.path() +
                                   "/m.mtl:1: warning: newmtl without a name; no usemtl can name "
                                   "it (--strict refuses it)");
    REQUIRE(scene.shapes.size() == 2);
    CHECK(material_of(scene, 0).name == "red");
    CHECK(material_of(scene, 1).name == "white");
    LoadOptions strict;
    strict.strict = true;
    try {
        load_scene_file(json, strict);
        FAIL("loaded strictly");
    } catch (const SceneError& e) {
        CHECK_THAT(e.what(),
                   Catch::Matchers::EndsWith("/m.obj:7: expected 'usemtl NAME', got no name"));
    }
}

TEST_CASE("MTL values out of range: one rule, a warning each, refused when strict",
          "[mtl][mesh][defects]") {
    TempDir dir;
    // The reproducers' values (shared/repro/mtl_silently_accepted): each
    // was taken silently, d -1 as glass, Tf -1 as white glass, illum 3.7
    // as 3, a second newmtl of a name in place of the first.
    dir.write("m.mtl",
              "newmtl a\nKd 1.5 0.5 -0.25\nd 2\nNs 2000\n"
              "newmtl b\nKd 0.5 0.5 0.5\nd -1\nTf -1 0 0\nillum 3.7\n"
              "newmtl a\nKd 0 1 0\n");
    dir.write("m.obj", "mtllib m.mtl\n" + triangle + "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n");
    const std::string json =
        dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "m.obj"}]})");
    const Scene scene = load_scene_file(json);
    const std::string mtl = dir.path() + "/m.mtl";
    const std::vector<std::string> expected = {
        mtl + ":2: warning: Kd 1.5: expected a number in [0, 1]; taken as 1 (--strict refuses it)",
        mtl +
            ":2: warning: Kd -0.25: expected a number in [0, 1]; taken as 0 (--strict refuses "
            "it)",
        mtl + ":3: warning: d 2: expected a number in [0, 1]; taken as 1 (--strict refuses it)",
        mtl +
            ":4: warning: Ns 2000: expected a number in [0, 1000]; taken as 1000 (--strict "
            "refuses it)",
        mtl + ":7: warning: d -1: expected a number in [0, 1]; taken as 0 (--strict refuses it)",
        mtl + ":8: warning: Tf -1: expected a number in [0, 1]; taken as 0 (--strict refuses it)",
        mtl +
            ":9: warning: illum 3.7: expected a whole number from 0 to 10; taken as 3 "
            "(--strict refuses it)",
        mtl +
            ":10: warning: newmtl 'a' again (first on line 1); the first is used (--strict "
            "refuses it)"};
    CHECK(scene.warnings == expected);
    REQUIRE(scene.shapes.size() == 2);
    const Material& a = material_of(scene, 0);
    CHECK(a.name == "a");
    CHECK(a.color == glm::vec3(1.0f, 0.5f, 0.0f));
    LoadOptions strict;
    strict.strict = true;
    try {
        load_scene_file(json, strict);
        FAIL("loaded strictly");
    } catch (const SceneError& e) {
        CHECK_THAT(e.what(),
                   Catch::Matchers::EndsWith(mtl + ":2: Kd 1.5: expected a number in [0, 1]"));
    }
}
