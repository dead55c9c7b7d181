// Reading a scene file's "materials" (the scene loader's part for
// surfaces; the schema: scene_loader.cpp and docs/scene-format.md).
#ifndef TRAC0R_MATERIAL_LOADER_H
#define TRAC0R_MATERIAL_LOADER_H

#include "trac0r/json_diagnostics.h"
#include "trac0r/material.h"
#include "trac0r/scene_builder.h"

#include <vector>

namespace trac0r {

// The "materials" object: a non-empty object of named materials, added
// to the builder in the order nlohmann iterates it (by name).
void read_materials(const json_diagnostics::json& value, const json_diagnostics::Location& at,
                    SceneBuilder& builder);

}  // namespace trac0r

#endif
