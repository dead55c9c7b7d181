// A scene around a model file opened on its own (trac0r_viewer model.glb):
// what a user who has only the model expects to see of it.
#ifndef TRAC0R_MODEL_SCENE_H
#define TRAC0R_MODEL_SCENE_H

#include "trac0r/scene_loader.h"

#include <string>

namespace trac0r {

// Whether `path` names a model file (.obj, .ply, .gltf, .glb, any case)
// rather than a scene file.
bool is_model_path(const std::string& path);

// A scene around the model: the model where its file puts it, its faces
// with the file's materials (else the default grey); lit by a glTF's own
// lights (KHR_lights_punctual, gltf_view.h), else by a constant white
// environment; seen by a glTF's first camera (at its aspect ratio, 600
// rows), else from in front (+z, glTF's and Blender's front view), to the
// right and above, by a camera of 45 degrees that frames the sphere
// around its bounds. `json` (where given) receives the scene
// as scene-file JSON, which loads back to this scene (--print-scene), the
// model by its absolute path. Throws SceneError as load_scene_file.
Scene model_scene(const std::string& model_path, const LoadOptions& options,
                  std::string* json = nullptr);

// A scene file, or the scene made around a model file (is_model_path), as
// trac0r_viewer and the Python module open either.
Scene open_scene(const std::string& path, const LoadOptions& options = LoadOptions());

}  // namespace trac0r

#endif
