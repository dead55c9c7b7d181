// Reading scenes from JSON: nlohmann::json in, trac0r::Scene out, with one
// message per mistake that says where it is, what was expected and what was
// found ("FILE: /json/pointer: expected ..., got ..."; the messages and the
// parsing are json_diagnostics.h's).
//
// Schema and defaults. Units are metres and radians, except vertical_fov
// (degrees). "[n]" is an array of n numbers. Every key not listed here is an
// error, and so is a key given twice in one object: a misspelt optional key
// would otherwise be ignored and its default used without a word.
//
// | key                    | type    | rule                                    | default         |
// |------------------------|---------|-----------------------------------------|-----------------|
// | camera                 | object  | optional                                | (below)         |
// | camera.position        | [3]     | finite                                  | [0, 0.31, 1.2]  |
// | camera.direction       | [3]     | finite, non-zero                        | [0, 0, -1]      |
// | camera.world_up        | [3]     | finite, non-zero, not along direction   | [0, 1, 0]       |
// | camera.projection      | string  | perspective/orthographic                | perspective     |
// | camera.vertical_fov    | number  | perspective: degrees, in (0, 180)       | 53.13           |
// | camera.view_height     | number  | orthographic: > 0, metres               | 2               |
// | camera.aperture_radius | number  | >= 0, metres (0: a pinhole)             | 0               |
// | camera.focus_distance  | number  | > 0, metres along direction             | 1               |
// | render                 | object  | optional                                | (below)         |
// | render.width           | integer | in [1, 16384]                           | 800             |
// | render.height          | integer | in [1, 16384]                           | 600             |
// | render.max_depth       | integer | in [1, 100000]                          | 5               |
// | render.view            | string  | standard/filmic (view_transform.h)      | standard        |
// | materials              | object  | required, non-empty: name -> material   |                 |
// | material.type          | string  | required: emissive/diffuse/glass/glossy |                 |
// |                        |         | /conductor/plastic/principled           |                 |
// | material.color         | [3]     | required; in [0, 1] (emissive: >= 0;    |                 |
// |                        |         | a conductor with "metal": optional)     | [1, 1, 1]       |
// | material.emittance     | number  | emissive: required, > 0                 |                 |
// |                        |         | diffuse: optional, >= 0                 | 0               |
// |                        |         | colour x emittance <= 1e30 per channel  |                 |
// | material.roughness     | number  | glossy, glass, conductor, plastic,      | 0               |
// |                        |         | principled; in [0, 1]                   | (principled 0.5)|
// | material.two_sided     | boolean | emissive, diffuse: emits from both sides | true           |
// | material.ior           | number  | glass, plastic, principled; > 0         | 1.5             |
// | material.metal         | string  | conductor: gold/silver/copper/aluminium | none (Schlick)  |
// |                        |         | /chromium/tungsten                      |                 |
// | material.metallic      | number  | principled, in [0, 1]                   | 0               |
// | material.specular      | number  | principled, in [0, 1]                   | 1               |
// | shapes                 | array   | required, non-empty                     |                 |
// | shape.type             | string  | required: plane/box/icosphere/mesh      |                 |
// | shape.material         | string  | a name in materials; meshes: optional   | "default"       |
// | shape.position         | [3]     | finite                                  | [0, 0, 0]       |
// | shape.orientation      | [3]     | finite, radians                         | [0, 0, 0]       |
// | plane.size             | [2]     | required, > 0 (local x, z)              |                 |
// | box.size               | [3]     | required, > 0                           |                 |
// | icosphere.radius       | number  | required, > 0                           |                 |
// | icosphere.subdivisions | integer | in [0, 7] (20 * 4^n triangles)          | 2               |
// | mesh.file              | string  | required; .obj/.ply/.gltf/.glb path      |                 |
// | mesh.scale             | [3]     | finite, non-zero (negative mirrors)     | [1, 1, 1]       |
// | mesh.smooth            | boolean | shade with the file's vertex normals    | true            |
// | mesh.smooth_angle      | number  | degrees in [0, 180]: auto smooth        | none            |
// | mesh.file_materials    | boolean | faces take the file's materials (MTL...) | true           |
// | environment            | object  | optional: "color" or "map" (below)      | none (black)    |
// | environment.color      | [3]     | >= 0: a constant environment            |                 |
// | environment.map        | string  | an equirectangular .exr or .hdr path    |                 |
// | environment.strength   | number  | >= 0                                    | 1               |
// | environment.rotation   | number  | map only: degrees about +y              | 0               |
// | lights                 | array   | optional: point, spot and sun lights    | []              |
// | light.type             | string  | required: point/spot/sun                |                 |
// | light.color            | [3]     | >= 0                                    | [1, 1, 1]       |
// | point/spot.position    | [3]     | required, finite                        |                 |
// | point/spot.intensity   | number  | required, >= 0, W/sr                    |                 |
// | spot/sun.direction     | [3]     | required, non-zero: the spot's axis,    |                 |
// |                        |         | the direction towards the sun           |                 |
// | spot.angle             | number  | degrees in (0, 180]: the cone's angle   | 45              |
// | spot.blend             | number  | in [0, 1]: the soft edge's share        | 0.15            |
// | sun.irradiance         | number  | required, >= 0, W/m^2                   |                 |
// | sun.angle              | number  | degrees in [0, 90]: angular diameter    | 0.53            |
//
// Every number must be finite as a float (1e39 is rejected); "> 0" and
// ">= 0" imply finite. Integers may be written 800 or 800.0 but not 800.5.
// The shape transform is T * Rx * Ry * Rz * S. Materials get indices in the
// order nlohmann iterates the materials object (by name).
#include "trac0r/scene_loader.h"

#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/isolated_call.h"
#include "trac0r/json_diagnostics.h"
#include "trac0r/light_loader.h"
#include "trac0r/material_loader.h"
#include "trac0r/refused_value.h"
#include "trac0r/scene_builder.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <vector>

namespace trac0r {

// Generated by the build from scenes/cornell.json (cmake/embed.cmake).
extern const char* const embedded_cornell_json;

namespace {

using namespace json_diagnostics;

// ---- Camera and render settings --------------------------------------------

float read_fov(const json& value, const Location& at) {
    const std::string expected = "a number of degrees in (0, 180)";
    if (!value.is_number() || !fits_float(value)) {
        fail_expected(at, expected, value);
    }
    const float degrees = value.get<float>();
    if (!(degrees > 0.0f && degrees < 180.0f)) {
        fail_expected(at, expected, value);
    }
    return degrees;
}

// The camera, its position relative to *origin, which it chooses
// (local_origin of the position as the file writes it, in double).
Camera read_camera(const json& value, const Location& at, glm::dvec3* origin) {
    const ObjectReader o(value, at, "a camera object");
    o.allow_only({"position", "direction", "world_up", "projection", "vertical_fov", "view_height",
                  "aperture_radius", "focus_distance"},
                 "the camera");
    Camera camera;
    const glm::dvec3 position =
        o.optional_dvec3("position", NumberRule::finite, glm::dvec3(camera.position));
    *origin = local_origin(position);
    camera.position = glm::vec3(position - *origin);
    camera.direction = o.optional_vec3("direction", NumberRule::finite, camera.direction);
    camera.world_up = o.optional_vec3("world_up", NumberRule::finite, camera.world_up);
    if (o.has("projection") && read_choice(o["projection"], o.at("projection"),
                                           {"perspective", "orthographic"}) == "orthographic") {
        camera.projection = Projection::orthographic;
    }
    // Each projection's size key, and not the other's: a field of view
    // given to an orthographic camera would be ignored without a word.
    const bool orthographic = camera.projection == Projection::orthographic;
    if (o.has("vertical_fov")) {
        if (orthographic) {
            fail(o.at("vertical_fov"),
                 "an orthographic camera has no field of view: give its view_height (metres)");
        }
        camera.vertical_fov = read_fov(o["vertical_fov"], o.at("vertical_fov"));
    }
    if (o.has("view_height")) {
        if (!orthographic) {
            fail(o.at("view_height"),
                 "view_height is an orthographic camera's: give "
                 "\"projection\": \"orthographic\", or a vertical_fov");
        }
        camera.view_height = o.optional_float("view_height", NumberRule::positive, 0.0f);
    }
    camera.aperture_radius =
        o.optional_float("aperture_radius", NumberRule::non_negative, camera.aperture_radius);
    camera.focus_distance =
        o.optional_float("focus_distance", NumberRule::positive, camera.focus_distance);
    // Zero vectors and a direction along world_up are the camera's own
    // conditions to state; its message names the field.
    if (const char* problem = camera_problem(camera)) {
        fail(at, problem);
    }
    return camera;
}

RenderSettings read_render(const json& value, const Location& at) {
    const ObjectReader o(value, at, "a render settings object");
    o.allow_only({"width", "height", "max_depth", "view"}, "the render settings");
    const int max_image_side = 16384;
    RenderSettings render;
    render.width = o.optional_int("width", 1, max_image_side, render.width);
    render.height = o.optional_int("height", 1, max_image_side, render.height);
    render.max_depth = o.optional_int("max_depth", 1, 100000, render.max_depth);
    if (o.has("view")) {
        render.view =
            parse_view_transform(read_choice(o["view"], o.at("view"), view_transform_names()));
    }
    return render;
}

// ---- Shapes -----------------------------------------------------------------

// What a shape needs besides its keys, to build it.
struct ShapeContext {
    SceneBuilder* builder = nullptr;
    std::string base_dir;
};

// The shape's "material": "" where a mesh has none (SceneBuilder's
// default), else a string (the builder looks it up).
std::string read_material_name(const ObjectReader& o, bool optional) {
    if (optional && !o.has("material")) {
        return "";
    }
    const json& value = o.required("material", "the name of a material");
    if (!value.is_string() || value.get<std::string>().empty()) {
        fail_expected(o.at("material"), "the name of a material", value);
    }
    return value.get<std::string>();
}

void read_mesh(const ObjectReader& o, const ShapeContext& context, MeshFilePlacement placement) {
    const std::string expected = "the path of a mesh file (.obj, .ply, .gltf or .glb)";
    const json& file = o.required("file", expected);
    if (!file.is_string() || file.get<std::string>().empty()) {
        fail_expected(o.at("file"), expected, file);
    }
    placement.scale = o.optional_vec3("scale", NumberRule::non_zero, glm::vec3(1.0f));
    placement.smooth = o.optional_bool("smooth", true);
    placement.file_materials = o.optional_bool("file_materials", true);
    if (o.has("smooth_angle")) {
        placement.smooth_angle = o.required_float("smooth_angle", NumberRule::non_negative);
    }
    const std::string path = resolve_path(context.base_dir, file.get<std::string>());
    try {
        context.builder->add_mesh_file(path, placement);
    } catch (const std::runtime_error& e) {
        // tinyobjloader's messages end in a newline; ours are one line.
        std::string message = e.what();
        message.erase(message.find_last_not_of(" \n\r") + 1);
        fail(o.at("file"), message);
    }
}

// The keys of each shape type beyond type, material, position, orientation.
const std::map<std::string, std::vector<std::string>>& shape_type_keys() {
    static const std::map<std::string, std::vector<std::string>> keys = {
        {"plane", {"size"}},
        {"box", {"size"}},
        {"icosphere", {"radius", "subdivisions"}},
        {"mesh", {"file", "scale", "smooth", "smooth_angle", "file_materials"}}};
    return keys;
}

// A shape of the file, added to the builder's scene (a mesh: its parts by
// material).
void read_shape(const json& value, const Location& at, const ShapeContext& context) {
    const ObjectReader o(value, at, "a shape object");
    const std::vector<std::string> types = {"plane", "box", "icosphere", "mesh"};
    const std::string type =
        read_choice(o.required("type", "one of " + join(types, "\"")), o.at("type"), types);
    std::vector<std::string> allowed = {"type", "material", "position", "orientation"};
    const std::vector<std::string>& own = shape_type_keys().at(type);
    allowed.insert(allowed.end(), own.begin(), own.end());
    o.allow_only(allowed, with_article(type) + " shape");

    // A mesh's faces may all have their file's materials: its own is
    // optional (default_mesh_material).
    ShapePlacement placement;
    placement.material = read_material_name(o, type == "mesh");
    // In the file's coordinates, in double: the builder makes them relative
    // to the local origin, then rounds them to float once.
    placement.position = o.optional_dvec3("position", NumberRule::finite, glm::dvec3(0.0));
    placement.orientation = o.optional_vec3("orientation", NumberRule::finite, glm::vec3(0.0f));
    SceneBuilder& builder = *context.builder;
    try {
        if (type == "plane") {
            builder.add_plane(placement,
                              read_vec2(o.required("size", expectation(NumberRule::positive, 2)),
                                        o.at("size"), NumberRule::positive));
        } else if (type == "box") {
            builder.add_box(placement, o.required_vec3("size", NumberRule::positive));
        } else if (type == "icosphere") {
            const float radius = o.required_float("radius", NumberRule::positive);
            builder.add_icosphere(placement, radius, o.optional_int("subdivisions", 0, 7, 2));
        } else {
            MeshFilePlacement mesh;
            mesh.material = placement.material;
            mesh.position = placement.position;
            mesh.orientation = placement.orientation;
            read_mesh(o, context, mesh);
        }
    } catch (const SceneValueError& e) {
        fail_refused(value, at, e);
    }
}

void read_shapes(const json& value, const Location& at, const ShapeContext& context) {
    if (!value.is_array() || value.empty()) {
        fail_expected(at, "a non-empty array of shapes", value);
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
        read_shape(value[i], at.index(i), context);
    }
}

// ---- The document -----------------------------------------------------------

Scene read_scene(const json& document, const Location& at, const std::string& base_dir,
                 const LoadOptions& options) {
    const ObjectReader o(document, at, "a JSON object with materials and shapes");
    o.allow_only({"camera", "render", "materials", "shapes", "environment", "lights"},
                 "the top level");
    Scene scene;
    SceneBuilder builder(scene, options);
    if (o.has("camera")) {
        glm::dvec3 origin(0.0);
        const Camera camera = read_camera(o["camera"], o.at("camera"), &origin);
        scene.origin = origin;
        try {
            builder.set_camera(camera);
        } catch (const SceneValueError& e) {
            fail_refused(o["camera"], o.at("camera"), e);
        }
    }
    if (o.has("render")) {
        scene.render = read_render(o["render"], o.at("render"));
    }
    read_materials(o.required("materials", "an object of named materials"), o.at("materials"),
                   builder);
    ShapeContext context;
    context.builder = &builder;
    context.base_dir = base_dir;
    const bool no_shapes = options.shapes_optional &&
                           (!o.has("shapes") || (o["shapes"].is_array() && o["shapes"].empty()));
    if (!no_shapes) {
        read_shapes(o.required("shapes", "an array of shapes"), o.at("shapes"), context);
    }
    if (o.has("environment")) {
        read_environment(o["environment"], o.at("environment"), base_dir, builder);
    }
    if (o.has("lights")) {
        read_lamps(o["lights"], o.at("lights"), builder);
    }
    return scene;
}

// ---- Parsing ----------------------------------------------------------------

std::string directory_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) {
        return "";
    }
    return slash == 0 ? "/" : path.substr(0, slash);
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::string& origin,
                  const std::string& base_dir, const LoadOptions& options) {
    const ReaderIsolation isolation(options.isolate_readers);
    try {
        return read_scene(parse_json(json_text, origin), Location{origin, ""}, base_dir, options);
    } catch (const JsonError& e) {
        throw SceneError(e.what());  // the same message, as the scene file's error
    }
}

Scene load_scene_file(const std::string& path, const LoadOptions& options) {
    std::string text;
    try {
        text = read_input_file(path, "scene file");
    } catch (const std::runtime_error& e) {
        throw SceneError(e.what());
    }
    return parse_scene(text, path, directory_of(path), options);
}

void add_scene_object(Scene& scene, const std::string& kind, const std::string& json_text,
                      const std::string& origin, const std::string& base_dir,
                      const LoadOptions& options) {
    const std::vector<std::string> kinds = {"material", "shape", "light", "environment"};
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
        throw std::invalid_argument("add_scene_object: kind: expected one of " +
                                    join(kinds, "\"") + ", got \"" + kind + "\"");
    }
    const ReaderIsolation isolation(options.isolate_readers);
    // What a mistake takes back: the builder only appends, or sets the
    // environment (and the warnings).
    const std::size_t materials = scene.materials.size();
    const std::size_t shapes = scene.shapes.size();
    const std::size_t textures = scene.textures.size();
    const std::size_t lamps = scene.lamps.size();
    const std::vector<std::string> warnings = scene.warnings;
    const Environment environment = kind == "environment" ? scene.environment : Environment();
    try {
        const json value = parse_json(json_text, origin);
        const Location at{origin, ""};
        SceneBuilder builder(scene, options);
        if (kind == "material") {
            read_materials(value, at, builder);
        } else if (kind == "shape") {
            ShapeContext context;
            context.builder = &builder;
            context.base_dir = base_dir;
            read_shape(value, at, context);
        } else if (kind == "light") {
            read_light(value, at, builder);
        } else {
            read_environment(value, at, base_dir, builder);
        }
    } catch (...) {
        scene.materials.erase(scene.materials.begin() + static_cast<std::ptrdiff_t>(materials),
                              scene.materials.end());
        scene.shapes.erase(scene.shapes.begin() + static_cast<std::ptrdiff_t>(shapes),
                           scene.shapes.end());
        scene.textures.erase(scene.textures.begin() + static_cast<std::ptrdiff_t>(textures),
                             scene.textures.end());
        scene.lamps.erase(scene.lamps.begin() + static_cast<std::ptrdiff_t>(lamps),
                          scene.lamps.end());
        scene.warnings = warnings;
        if (kind == "environment") {
            scene.environment = environment;
        }
        try {
            throw;
        } catch (const JsonError& e) {
            throw SceneError(e.what());
        }
    }
}

Material default_mesh_material() {
    Material m;
    m.name = "default";
    m.type = MaterialType::diffuse;
    m.color = glm::vec3(0.8f);
    return m;
}

const char* builtin_scene_json() {
    // cmake/embed.cmake puts a "// ---- cornell.json" line before the
    // file's text; skip it so the result is plain JSON, as in the file.
    const char* text = embedded_cornell_json;
    const char* newline = std::strchr(text, '\n');
    return std::strncmp(text, "// ---- ", 8) == 0 && newline ? newline + 1 : text;
}

Scene builtin_scene() { return parse_scene(builtin_scene_json(), "built-in scene", ""); }

Camera parse_camera_block(const std::string& json_text, const std::string& origin,
                          const glm::dvec3& scene_origin) {
    try {
        const json document = parse_json(json_text, origin);
        const Location at{origin, ""};
        // {"camera": {...}}, as the window prints it, or the block alone.
        const bool wrapped = document.is_object() && document.size() == 1 &&
                             document.begin().key() == "camera";
        const json& block = wrapped ? document["camera"] : document;
        const Location block_at = wrapped ? Location{origin, "/camera"} : at;
        glm::dvec3 file_origin(0.0);
        Camera camera = read_camera(block, block_at, &file_origin);
        // Relative to the scene's origin, as its own camera.
        camera.position = glm::vec3(glm::dvec3(camera.position) + file_origin - scene_origin);
        return camera;
    } catch (const JsonError& e) {
        throw SceneError(e.what());
    }
}

Camera load_camera_file(const std::string& path, const glm::dvec3& scene_origin) {
    std::string text;
    try {
        text = read_input_file(path, "camera file");
    } catch (const std::runtime_error& e) {
        throw SceneError(e.what());
    }
    return parse_camera_block(text, path, scene_origin);
}

}  // namespace trac0r
