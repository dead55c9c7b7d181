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

// What a glTF material has that assimp 5.2 does not read.
struct GltfMaterialExtras {
    std::string name;  // the material's "name" ("" where it has none)
    // KHR_materials_emissive_strength's emissiveStrength (1: none).
    float emissive_strength = 1.0f;
    // KHR_texture_transform of its textures: the base colour's (else the
    // first of metallic-roughness, normal, emissive, occlusion that has
    // one) as the 2 x 3 affine map of glTF texture coordinates (u right,
    // v down from the image's top) that the extension defines, T R S:
    // (u', v') = (m[0] u + m[1] v + m[2], m[3] u + m[4] v + m[5]).
    bool uv_transform = false;
    std::vector<double> uv_matrix = {1, 0, 0, 0, 1, 0};
    // Whether another texture of the material has a different one (which
    // its one set of coordinates cannot follow).
    bool transforms_differ = false;
};

// Each material's extras, in the order of the file's materials (which
// assimp does not keep: match them by name). Empty where the JSON cannot be read (assimp refuses it
// first). Throws std::runtime_error naming the file, material and key for
// a strength that is not a number in [0, 1e30] or a transform that is not
// finite numbers.
std::vector<GltfMaterialExtras> gltf_material_extras(const std::string& json_text,
                                                     const std::string& path);

}  // namespace trac0r

#endif
