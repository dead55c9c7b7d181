// Reading a scene file's "environment" and "lights" (the scene loader's
// part for light that is not a surface's; the schema: scene_loader.cpp and
// docs/scene-format.md).
#ifndef TRAC0R_LIGHT_LOADER_H
#define TRAC0R_LIGHT_LOADER_H

#include "trac0r/json_diagnostics.h"
#include "trac0r/lights.h"

#include <string>
#include <vector>

namespace trac0r {

// The "environment" object; a map's path is relative to base_dir.
Environment read_environment(const json_diagnostics::json& value,
                             const json_diagnostics::Location& at, const std::string& base_dir);

// The "lights" array; positions are made relative to the scene's origin.
std::vector<Lamp> read_lamps(const json_diagnostics::json& value,
                             const json_diagnostics::Location& at, const glm::dvec3& origin);

}  // namespace trac0r

#endif
