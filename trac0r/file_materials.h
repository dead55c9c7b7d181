// The renderer's materials for a model file's own: an OBJ's MTL materials
// and a glTF's (through assimp), as the tables in docs/scene-format.md
// ("Materials from the file") map them.
#ifndef TRAC0R_FILE_MATERIALS_H
#define TRAC0R_FILE_MATERIALS_H

#include "trac0r/material.h"

#include <tiny_obj_loader.h>

#include <assimp/material.h>

#include <string>

namespace trac0r {

// An MTL material of `file`; throws std::runtime_error naming the file,
// the material and the statement for a value out of range.
Material material_from_mtl(const tinyobj::material_t& m, const std::string& file);

// The base-colour texture an MTL material names for the material `out`
// made of it; "" for none. *key is the statement's name, for messages.
std::string mtl_texture_name(const tinyobj::material_t& m, const Material& out, const char** key);

// Whether m is what assimp adds for glTF primitives that name no material
// (glTF's default material).
bool is_default_material(const aiMaterial& m);

// A glTF (or other assimp) material of `file`, its emission times
// `emissive_strength` (KHR_materials_emissive_strength, which assimp 5.2
// does not read: gltf_json.h); throws as material_from_mtl.
Material material_from_assimp(const aiMaterial& m, const std::string& file,
                              float emissive_strength = 1.0f);

}  // namespace trac0r

#endif
