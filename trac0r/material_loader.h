// Reading a scene file's "materials" (the scene loader's part for
// surfaces; the schema: scene_loader.cpp and docs/scene-format.md).
#ifndef TRAC0R_MATERIAL_LOADER_H
#define TRAC0R_MATERIAL_LOADER_H

#include "trac0r/json_diagnostics.h"
#include "trac0r/material.h"

#include <vector>

namespace trac0r {

// The "materials" object: a non-empty object of named materials, in the
// order nlohmann iterates it (by name).
std::vector<Material> read_materials(const json_diagnostics::json& value,
                                     const json_diagnostics::Location& at);

}  // namespace trac0r

#endif
