// Reading scenes from JSON (the format: docs/scene-format.md).
#ifndef TRAC0R_SCENE_LOADER_H
#define TRAC0R_SCENE_LOADER_H

#include "trac0r/scene.h"

#include <stdexcept>
#include <string>

namespace trac0r {

// One clear message: "FILE: /json/path: what was expected (got ...)".
class SceneError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// How model files are read. Lenient (the default): a defect that leaves a
// model renderable (model_defects.h: a face of two vertices, a usemtl
// naming no material, a texture that is not there) is passed over, one
// warning line a kind in Scene::warnings. Strict: each is an error.
struct LoadOptions {
    bool strict = false;
    // PLY and glTF files, and every texture image, are read in a forked
    // child process (isolated_call.h) with a time and memory limit, so that
    // a hostile file ends only the child and becomes one error line. The
    // programs and the Python module keep this on. Off, they are read in
    // the calling process, without limits: for a host that must not fork.
    bool isolate_readers = true;
    // A scene whose shapes are added in code (mesh_arrays.h, the Python
    // module): "shapes" may be absent or empty.
    bool shapes_optional = false;
};

// Loads a scene file; relative mesh paths are relative to its directory.
Scene load_scene_file(const std::string& path, const LoadOptions& options = LoadOptions());

// Parses scene JSON text; `origin` names it in messages and `base_dir`
// resolves relative mesh paths.
Scene parse_scene(const std::string& json_text, const std::string& origin,
                  const std::string& base_dir, const LoadOptions& options = LoadOptions());

// The material a mesh without a "material" key takes: the scene's
// material named "default" where it has one, else this one, a grey
// diffuse (colour 0.8), added to the scene when first used.
Material default_mesh_material();

// The built-in default: the thesis' Cornell box (scenes/cornell.json,
// embedded at build time).
Scene builtin_scene();
const char* builtin_scene_json();

// A camera block, as the window prints it (camera_block_json): a JSON
// object {"camera": {...}}, or the block {...} alone, with the scene
// file's camera keys and rules; its position made relative to the scene's
// `scene_origin`. SceneError names the file and JSON path.
Camera parse_camera_block(const std::string& json_text, const std::string& origin,
                          const glm::dvec3& scene_origin);
Camera load_camera_file(const std::string& path, const glm::dvec3& scene_origin);

// One object of the scene format, as JSON text, added to `scene` through
// a SceneBuilder (scene_builder.h) with the loader's keys, defaults and
// messages: `kind` "material" ({"NAME": {...}}, as in "materials"),
// "shape" (one of "shapes"; a mesh's file is found from base_dir),
// "light" (one of "lights") or "environment". A mistake is a SceneError
// "ORIGIN: /json/pointer: ...", and the scene is left as it was; an
// unknown kind is std::invalid_argument. The Python module's
// Scene.add_material and its like.
void add_scene_object(Scene& scene, const std::string& kind, const std::string& json_text,
                      const std::string& origin, const std::string& base_dir,
                      const LoadOptions& options = LoadOptions());

}  // namespace trac0r

#endif
