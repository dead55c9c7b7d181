// Reading a scene file's "environment" and "lights" (the scene loader's
// part for light that is not a surface's; the schema: scene_loader.cpp and
// docs/scene-format.md).
#ifndef TRAC0R_LIGHT_LOADER_H
#define TRAC0R_LIGHT_LOADER_H

#include "trac0r/json_diagnostics.h"
#include "trac0r/lights.h"
#include "trac0r/scene_builder.h"

#include <string>
#include <vector>

namespace trac0r {

// The "environment" object, set on the builder's scene; a map's path is
// relative to base_dir.
void read_environment(const json_diagnostics::json& value, const json_diagnostics::Location& at,
                      const std::string& base_dir, SceneBuilder& builder);

// The "lights" array, added to the builder's scene; positions are made
// relative to the scene's origin.
void read_lamps(const json_diagnostics::json& value, const json_diagnostics::Location& at,
                SceneBuilder& builder);
// One light object of that array.
void read_light(const json_diagnostics::json& value, const json_diagnostics::Location& at,
                SceneBuilder& builder);

}  // namespace trac0r

#endif
