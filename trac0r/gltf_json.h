// What trac0r reads from a glTF file's own JSON where assimp 5.2 (Debian
// 12's) does not: the extensions it leaves out.
#ifndef TRAC0R_GLTF_JSON_H
#define TRAC0R_GLTF_JSON_H

#include <string>
#include <vector>

namespace trac0r {

// The glTF JSON of a file's text: a .gltf's whole text, a .glb's JSON
// chunk (glTF 2.0, 4.4); "" where a .glb's header or first chunk is not
// one (assimp refuses such a file first).
std::string gltf_json_text(const std::string& text, bool glb);

// Each material's KHR_materials_emissive_strength (emissiveStrength, 1
// where the material has none), in the order of the file's materials
// (which assimp keeps). Empty where the JSON cannot be read (assimp
// refuses it first). Throws std::runtime_error naming the file and
// material for a strength that is not a number >= 0.
std::vector<float> gltf_emissive_strengths(const std::string& json_text, const std::string& path);

}  // namespace trac0r

#endif
