// SceneBuilder: a scene built in code is the scene file's scene, digest for
// digest; what it refuses, a scene file is refused for with the same
// words; and what only code can get wrong (a texture index, a name given
// twice) is refused too, leaving the scene as it was.
#include <catch2/catch.hpp>

#include "trac0r/material.h"
#include "trac0r/scene_builder.h"
#include "trac0r/scene_loader.h"

#include <functional>
#include <string>

using namespace trac0r;
using Catch::Matchers::EndsWith;
using Catch::Matchers::Equals;

namespace {

const std::string scenes_dir = std::string(TRAC0R_SOURCE_DIR) + "/scenes";

// Every kind of material, shape and light the format has, in one file.
const char* const everything_json = R"({
  "camera": {"position": [0, 0.45, 1.6], "direction": [0, -0.18, -1], "vertical_fov": 45},
  "materials": {
    "brass":  {"type": "glossy", "color": [0.95, 0.8, 0.45], "roughness": 0.15},
    "clay":   {"type": "diffuse", "color": [0.75, 0.32, 0.18]},
    "coat":   {"type": "plastic", "color": [0.2, 0.3, 0.8], "roughness": 0.3, "ior": 1.45},
    "gold":   {"type": "conductor", "metal": "gold", "roughness": 0.2},
    "glass":  {"type": "glass", "color": [0.97, 0.98, 1.0], "ior": 1.5, "roughness": 0.1},
    "lamp":   {"type": "emissive", "color": [1, 0.9, 0.8], "emittance": 12, "two_sided": false},
    "paint":  {"type": "principled", "color": [0.5, 0.1, 0.1], "metallic": 0.25,
               "roughness": 0.4, "specular": 0.5, "emission": [0.1, 0, 0]}
  },
  "shapes": [
    {"type": "plane", "material": "clay", "position": [0, 0, 0], "size": [4, 3]},
    {"type": "box", "material": "coat", "position": [0.45, 0.12, -0.75],
     "orientation": [0, -0.5, 0], "size": [0.24, 0.24, 0.24]},
    {"type": "icosphere", "material": "glass", "position": [0.5, 0.15, -0.2], "radius": 0.15,
     "subdivisions": 3},
    {"type": "plane", "material": "lamp", "position": [0, 1.5, 0], "orientation": [3.14159265, 0, 0],
     "size": [0.3, 0.3]},
    {"type": "mesh", "material": "brass", "file": "meshes/tetrahedron.obj",
     "position": [-0.15, 0.1, 0.05], "scale": [0.1, 0.1, 0.1], "smooth_angle": 30},
    {"type": "mesh", "file": "meshes/textured_cube.obj", "position": [-0.55, 0.15, -0.35]},
    {"type": "icosphere", "material": "gold", "position": [0, 0.3, -1], "radius": 0.1},
    {"type": "icosphere", "material": "paint", "position": [0.3, 0.3, -1], "radius": 0.1}
  ],
  "environment": {"color": [0.1, 0.2, 0.4], "strength": 0.5},
  "lights": [
    {"type": "point", "position": [1, 2, 1], "color": [1, 1, 0.9], "intensity": 3},
    {"type": "spot", "position": [-1, 2, 1], "direction": [1, -2, -1], "intensity": 20,
     "angle": 30, "blend": 0.2},
    {"type": "sun", "direction": [0.3, 1, 0.2], "irradiance": 2, "angle": 0.53}
  ]
})";

Material material(const std::string& name, MaterialType type, glm::vec3 color) {
    Material m;
    m.name = name;
    m.type = type;
    m.color = color;
    return m;
}

ShapePlacement at(const std::string& material, glm::dvec3 position,
                  glm::vec3 orientation = glm::vec3(0.0f)) {
    ShapePlacement p;
    p.material = material;
    p.position = position;
    p.orientation = orientation;
    return p;
}

// everything_json, in code (materials in the order the loader adds them:
// by name).
Scene everything_in_code() {
    Scene scene;
    SceneBuilder b(scene);
    Camera camera;
    camera.position = glm::vec3(0.0f, 0.45f, 1.6f);
    camera.direction = glm::vec3(0.0f, -0.18f, -1.0f);
    camera.vertical_fov = 45.0f;
    b.set_camera(camera);

    Material brass = material("brass", MaterialType::glossy, {0.95f, 0.8f, 0.45f});
    brass.roughness = 0.15f;
    b.add_material(brass);
    b.add_material(material("clay", MaterialType::diffuse, {0.75f, 0.32f, 0.18f}));
    Material coat = material("coat", MaterialType::plastic, {0.2f, 0.3f, 0.8f});
    coat.roughness = 0.3f;
    coat.ior = 1.45f;
    b.add_material(coat);
    Material glass = material("glass", MaterialType::glass, {0.97f, 0.98f, 1.0f});
    glass.roughness = 0.1f;
    b.add_material(glass);
    Material gold = material("gold", MaterialType::conductor, glm::vec3(1.0f));
    gold.metal = "gold";
    gold.roughness = 0.2f;
    b.add_material(gold);
    Material lamp = material("lamp", MaterialType::emissive, {1.0f, 0.9f, 0.8f});
    lamp.emittance = 12.0f;
    lamp.two_sided = false;
    b.add_material(lamp);
    Material paint = material("paint", MaterialType::principled, {0.5f, 0.1f, 0.1f});
    paint.metallic = 0.25f;
    paint.roughness = 0.4f;
    paint.specular = 0.5f;
    paint.emission = glm::vec3(0.1f, 0.0f, 0.0f);
    b.add_material(paint);

    b.add_plane(at("clay", {0, 0, 0}), {4.0f, 3.0f});
    b.add_box(at("coat", {0.45, 0.12, -0.75}, {0.0f, -0.5f, 0.0f}), glm::vec3(0.24f));
    b.add_icosphere(at("glass", {0.5, 0.15, -0.2}), 0.15f, 3);
    b.add_plane(at("lamp", {0, 1.5, 0}, {3.14159265f, 0.0f, 0.0f}), {0.3f, 0.3f});
    MeshFilePlacement tetrahedron;
    tetrahedron.material = "brass";
    tetrahedron.position = {-0.15, 0.1, 0.05};
    tetrahedron.scale = glm::vec3(0.1f);
    tetrahedron.smooth_angle = 30.0f;
    b.add_mesh_file(scenes_dir + "/meshes/tetrahedron.obj", tetrahedron);
    MeshFilePlacement cube;
    cube.position = {-0.55, 0.15, -0.35};
    b.add_mesh_file(scenes_dir + "/meshes/textured_cube.obj", cube);
    b.add_icosphere(at("gold", {0, 0.3, -1}), 0.1f);
    b.add_icosphere(at("paint", {0.3, 0.3, -1}), 0.1f);

    Environment sky;
    sky.color = glm::vec3(0.1f, 0.2f, 0.4f);
    sky.strength = 0.5f;
    b.set_environment(sky);
    Lamp point;
    point.type = LampType::point;
    point.position = glm::vec3(1.0f, 2.0f, 1.0f);
    point.color = glm::vec3(1.0f, 1.0f, 0.9f);
    point.power = 3.0f;
    b.add_lamp(point);
    Lamp spot;
    spot.type = LampType::spot;
    spot.position = glm::vec3(-1.0f, 2.0f, 1.0f);
    spot.direction = glm::vec3(1.0f, -2.0f, -1.0f);
    spot.power = 20.0f;
    spot.angle = 30.0f;
    spot.blend = 0.2f;
    b.add_lamp(spot);
    Lamp sun;
    sun.type = LampType::sun;
    sun.direction = glm::vec3(0.3f, 1.0f, 0.2f);
    sun.power = 2.0f;
    sun.angle = 0.53f;
    b.add_lamp(sun);
    return scene;
}

// The SceneError message of parsing `json`; "" (and a failure) for none.
std::string file_error(const std::string& json) {
    try {
        parse_scene(json, "test.json", scenes_dir);
    } catch (const SceneError& e) {
        return e.what();
    }
    FAIL("no SceneError for: " << json);
    return "";
}

// The SceneValueError of `add`; a failure for none.
SceneValueError code_error(const std::function<void()>& add) {
    try {
        add();
    } catch (const SceneValueError& e) {
        return e;
    }
    FAIL("no SceneValueError");
    return SceneValueError("", "", "", "");
}

// A scene with one material "white" and one plane, with `material` added
// to its materials and `extra` to its top level.
std::string scene_with(const std::string& material, const std::string& extra = "") {
    return R"({"materials": {"white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]})" +
           (material.empty() ? "" : ", " + material) +
           R"(}, "shapes": [{"type": "plane", "material": "white", "size": [1, 1]}])" + extra + "}";
}

// A scene like scene_with's, in code.
Scene white_scene() {
    Scene scene;
    SceneBuilder(scene).add_material(material("white", MaterialType::diffuse, glm::vec3(0.8f)));
    return scene;
}

}  // namespace

TEST_CASE("a scene built in code is the scene file's, digest for digest", "[scene_builder]") {
    const Scene from_file = parse_scene(everything_json, "everything.json", scenes_dir);
    const Scene in_code = everything_in_code();
    REQUIRE(in_code.materials.size() == from_file.materials.size());
    REQUIRE(in_code.shapes.size() == from_file.shapes.size());
    CHECK(in_code.lamps.size() == 3);
    CHECK(in_code.environment.present);
    CHECK(in_code.textures.size() == 1);  // the cube's MTL texture, moved into the scene's
    CHECK(scene_digest(in_code) == scene_digest(from_file));
}

TEST_CASE("what the builder refuses, a scene file is refused for in the same words",
          "[scene_builder]") {
    struct Case {
        const char* what;
        std::string json;
        std::function<void(SceneBuilder&)> add;
        const char* message;  // the builder's what()
    };
    Material rough = material("m", MaterialType::glossy, glm::vec3(0.5f));
    rough.roughness = 1.5f;
    Material bright = material("m", MaterialType::emissive, glm::vec3(1.0f));
    bright.emittance = 1e31f;
    Lamp hot;
    hot.power = 1e31f;
    Lamp directionless_sun;
    directionless_sun.type = LampType::sun;
    directionless_sun.direction = glm::vec3(0.0f);
    directionless_sun.power = 1.0f;
    Environment sky;
    sky.color = glm::vec3(2.0f);
    sky.strength = 1e30f;
    const std::vector<Case> cases = {
        {"a roughness past 1",
         scene_with(R"("m": {"type": "glossy", "color": [0.5, 0.5, 0.5], "roughness": 1.5})"),
         [&](SceneBuilder& b) { b.add_material(rough); },
         "material \"m\": roughness: expected a number in [0, 1], got 1.5"},
        {"emission past float's sum",
         scene_with(R"("m": {"type": "emissive", "color": [1, 1, 1], "emittance": 1e31})"),
         [&](SceneBuilder& b) { b.add_material(bright); },
         "material \"m\": emittance: the colour times the emittance is 1e+31 in a channel, above "
         "1e30, the most the renderer can sum over a pixel's samples in float: scale the scene's "
         "emission down"},
        {"an unknown material",
         R"({"materials": {"white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]}},
             "shapes": [{"type": "box", "material": "blue", "size": [1, 1, 1]}]})",
         [](SceneBuilder& b) { b.add_box(at("blue", glm::dvec3(0.0)), glm::vec3(1.0f)); },
         "box: material: unknown material \"blue\" (known materials: \"white\")"},
        {"a box of negative size",
         R"({"materials": {"white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]}},
             "shapes": [{"type": "box", "material": "white", "size": [-1, 1, 1]}]})",
         [](SceneBuilder& b) {
             b.add_box(at("white", glm::dvec3(0.0)), {-1.0f, 1.0f, 1.0f});
         },
         "box: size: expected an array of 3 finite positive numbers, got [-1, 1, 1]"},
        {"a plane too small for float",
         R"({"materials": {"white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]}},
             "shapes": [{"type": "plane", "material": "white", "size": [1e-30, 1e-30]}]})",
         [](SceneBuilder& b) { b.add_plane(at("white", glm::dvec3(0.0)), glm::vec2(1e-30f)); },
         "plane: no triangle of the shape can be rendered (of 2, each has in float arithmetic an "
         "area of zero or below float's smallest normal, or a vertex that is not finite: "
         "degenerate faces, or a size, scale or position too small or too large)"},
        {"an empty material name", scene_with(R"("": {"type": "diffuse", "color": [1, 1, 1]})"),
         [](SceneBuilder& b) {
             b.add_material(material("", MaterialType::diffuse, glm::vec3(1.0f)));
         },
         "material \"\": a material needs a name"},
        {"a lamp past float's sum",
         scene_with("",
                    R"(, "lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1e31}])"),
         [&](SceneBuilder& b) { b.add_lamp(hot); },
         "point light: intensity: the colour times the intensity is 1e+31 in a channel, above "
         "1e30, the most the renderer can sum over a pixel's samples in float"},
        {"a sun without a direction",
         scene_with("",
                    R"(, "lights": [{"type": "sun", "direction": [0, 0, 0], "irradiance": 1}])"),
         [&](SceneBuilder& b) { b.add_lamp(directionless_sun); },
         "sun light: direction: expected a direction (3 finite numbers, not all zero): towards "
         "the sun, got [0, 0, 0]"},
        {"an environment past float's sum",
         scene_with("", R"(, "environment": {"color": [2, 2, 2], "strength": 1e30})"),
         [&](SceneBuilder& b) { b.set_environment(sky); },
         "environment: strength: the colour times the strength is 2e+30 in a channel, above "
         "1e30, the most the renderer can sum over a pixel's samples in float"},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        Scene scene = white_scene();
        SceneBuilder builder(scene);
        const SceneValueError e = code_error([&] { c.add(builder); });
        CHECK_THAT(e.what(), Equals(c.message));
        // The file's message: its location, then the same problem.
        CHECK_THAT(file_error(c.json), EndsWith(": " + e.problem()));
    }
}

TEST_CASE("the builder refuses what only code can get wrong, leaving the scene as it was",
          "[scene_builder]") {
    Scene scene = white_scene();
    SceneBuilder b(scene);
    const std::size_t materials = scene.materials.size();

    Material textured = material("t", MaterialType::diffuse, glm::vec3(0.5f));
    textured.roughness_texture = 0;  // the scene has no texture
    CHECK_THAT(code_error([&] { b.add_material(textured); }).what(),
               Equals("material \"t\": roughness_texture: expected -1 or an index into the "
                      "scene's 0 textures, got 0"));
    CHECK_THAT(code_error([&] {
                   b.add_material(material("white", MaterialType::diffuse, glm::vec3(0.5f)));
               }).what(),
               Equals("material \"white\": the scene has a material of this name already"));
    CHECK_THAT(code_error([&] {
                   b.add_material(material("", MaterialType::diffuse, glm::vec3(0.5f)));
               }).what(),
               Equals("material \"\": a material needs a name"));
    Material nan_glossy = material("g", MaterialType::glossy, glm::vec3(0.5f));
    nan_glossy.roughness = std::nanf("");
    CHECK(code_error([&] { b.add_material(nan_glossy); }).field() == "roughness");
    Material gold = material("g", MaterialType::diffuse, glm::vec3(0.5f));
    gold.metal = "gold";
    CHECK_THAT(code_error([&] { b.add_material(gold); }).what(),
               Equals("material \"g\": metal: only a conductor has a named metal"));

    Lamp spot;
    spot.type = LampType::spot;
    spot.angle = 0.0f;
    CHECK_THAT(code_error([&] { b.add_lamp(spot); }).what(),
               Equals("spot light: angle: expected a number of degrees in (0, 180], got 0"));
    Lamp sun;
    sun.type = LampType::sun;
    sun.direction = glm::vec3(0.0f);
    CHECK(code_error([&] { b.add_lamp(sun); }).field() == "direction");

    Environment map;
    map.width = 2;
    map.height = 2;
    map.texels.assign(3, glm::vec3(1.0f));
    CHECK_THAT(code_error([&] { b.set_environment(map); }).what(),
               Equals("environment: map: a map of 2 x 2 texels holds 3"));
    Camera camera;
    camera.vertical_fov = 180.0f;
    CHECK_THAT(code_error([&] { b.set_camera(camera); }).what(),
               Equals("camera: camera.vertical_fov must be in (0, 180) degrees"));

    // A shape refused for its geometry adds no default material.
    code_error([&] { b.add_plane(at("", glm::dvec3(0.0)), glm::vec2(0.0f, 1.0f)); });
    code_error([&] { b.add_icosphere(at("", glm::dvec3(0.0)), 1.0f, 8); });
    MeshArrays flat;
    flat.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    flat.indices = {0, 1, 2};
    code_error([&] { b.add_mesh(flat, MeshPlacement()); });

    CHECK(scene.materials.size() == materials);
    CHECK(scene.shapes.empty());
    CHECK(scene.lamps.empty());
    CHECK_FALSE(scene.environment.present);

    // The default material, once, for every shape without one.
    b.add_icosphere(at("", glm::dvec3(0.0)), 1.0f);
    b.add_box(at("", glm::dvec3(2.0, 0.0, 0.0)), glm::vec3(1.0f));
    REQUIRE(scene.materials.size() == materials + 1);
    CHECK(scene.materials.back().name == "default");
    CHECK(scene.shapes[0].material == static_cast<int>(materials));
    CHECK(scene.shapes[1].material == static_cast<int>(materials));
}

TEST_CASE("a mesh file's materials stay its own, and a refused file adds nothing",
          "[scene_builder]") {
    Scene scene = white_scene();
    // A scene material named as the file's ("gold") does not take the
    // place of a later file's in another builder (Python's add_shape).
    Material gold = material("gold", MaterialType::conductor, glm::vec3(1.0f));
    SceneBuilder(scene).add_material(gold);
    SceneBuilder(scene).add_mesh_file(scenes_dir + "/meshes/cube_mtl.obj", MeshFilePlacement());
    const std::size_t after_first = scene.materials.size();
    const std::size_t parts = scene.shapes.size();
    // The same file again, from a new builder: its materials are found,
    // not added twice.
    SceneBuilder(scene).add_mesh_file(scenes_dir + "/meshes/cube_mtl.obj", MeshFilePlacement());
    CHECK(scene.materials.size() == after_first);
    CHECK(scene.shapes.size() == 2 * parts);
    CHECK(scene.shapes[parts].material == scene.shapes[0].material);
    for (const Material& m : scene.materials) {
        CHECK((m.file.empty() ? m.name != "brick"
                              : m.file.find("cube_mtl.obj") != std::string::npos));
    }

    // A file that cannot be read, in a scene without a default yet: the
    // default it would have taken is taken back, and added again on use.
    Scene fresh = white_scene();
    SceneBuilder b(fresh);
    CHECK_THROWS_AS(b.add_mesh_file(scenes_dir + "/meshes/no_such.obj", MeshFilePlacement()),
                    std::runtime_error);
    CHECK(fresh.materials.size() == 1);
    CHECK(fresh.shapes.empty());
    b.add_icosphere(at("", glm::dvec3(0.0)), 1.0f);
    REQUIRE(fresh.materials.size() == 2);
    CHECK(fresh.shapes[0].material == 1);
    CHECK(fresh.materials[1].name == "default");
}

TEST_CASE("an unknown material's name is shown as JSON, cut short", "[scene_builder]") {
    Scene scene = white_scene();
    const std::string name = "bad\n" + std::string(200, 'x');
    const std::string message =
        code_error([&] {
            SceneBuilder(scene).add_box(at(name, glm::dvec3(0.0)), glm::vec3(1.0f));
        }).what();
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.size() < 200);
}
