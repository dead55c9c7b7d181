// The OBJ reader: tinyobjloader over the text obj_checker.h has checked,
// with the materials of the file's mtllib files.
#ifndef TRAC0R_OBJ_MESH_H
#define TRAC0R_OBJ_MESH_H

#include "trac0r/model_defects.h"
#include "trac0r/shape.h"

#include <cstdint>
#include <string>

namespace trac0r {

// An OBJ's faces, triangulated, split by their materials (each mapped as
// file_materials.h says, with its textures) where `read_mtl`, else all
// with `material`. Smooth as load_obj_mesh (shape.h). Its defects
// (model_defects.h) go to `defects`; nullptr: each is an error.
MeshParts load_obj(const std::string& path, const glm::vec3& position, const glm::vec3& orientation,
                   const glm::vec3& scale, int material, bool smooth, bool read_mtl,
                   std::uint64_t texel_budget, ModelDefects* defects = nullptr);

}  // namespace trac0r

#endif
