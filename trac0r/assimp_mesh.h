// The PLY and glTF 2.0 reader: assimp, in a child process of its own.
#ifndef TRAC0R_ASSIMP_MESH_H
#define TRAC0R_ASSIMP_MESH_H

#include "trac0r/shape.h"

#include <cstdint>
#include <string>

namespace trac0r {

// A PLY or glTF 2.0 file through assimp (its PLY or glTF 2.0 reader only,
// by the extension), in a child process of its own (isolated_call.h):
// assimp 5.2's readers crash on some malformed files (a heap overrun in
// the PLY reader, a null dereference in the glTF one: tests/fuzz/fuzz_mesh
// found them), and such a crash, a hang or a corrupted result is one clear
// error here, never the program's. Its meshes with their node transforms
// applied, polygons as fans of triangles, points and lines left out.
// Without `strict`, a texture that is not there or does not decode is
// passed over, as MeshParts::warnings says (model_defects.h).
MeshParts load_assimp(const std::string& path, const glm::vec3& position,
                      const glm::vec3& orientation, const glm::vec3& scale, int material,
                      bool smooth, bool file_materials, std::uint64_t texel_budget,
                      bool strict = true);

}  // namespace trac0r

#endif
