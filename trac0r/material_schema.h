// What each type of material holds, in the scene format's words: the keys
// and ranges that the JSON loader reads (material_loader.cpp) and
// SceneBuilder::add_material checks, defined once.
#ifndef TRAC0R_MATERIAL_SCHEMA_H
#define TRAC0R_MATERIAL_SCHEMA_H

#include "trac0r/material.h"

#include <vector>

namespace trac0r {
namespace json_diagnostics {
enum class NumberRule;  // json_diagnostics.h
}

// One number a type of material takes besides its colour: the scene
// format's key, its range, whether a file must give it, its default and
// the field it sets. A key of another type (roughness on a diffuse
// material) is an error in a file.
struct MaterialKey {
    MaterialType type;
    const char* key;
    json_diagnostics::NumberRule rule;
    bool required;   // else optional, with the default below
    float fallback;  // the default
    float Material::*field;
};

const std::vector<MaterialKey>& material_keys();

// The colour's range: emitted radiance may exceed 1, reflectances may not.
json_diagnostics::NumberRule material_color_rule(MaterialType type);

}  // namespace trac0r

#endif
