// The mesh a PLY or glTF import sends from its child process to the
// parent (assimp_mesh.h).
#ifndef TRAC0R_MESH_WIRE_H
#define TRAC0R_MESH_WIRE_H

#include "trac0r/mesh_parts.h"

#include <glm/glm.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r {

// The plain result of a PLY or glTF import, as its child process sends it
// to the parent (in this machine's byte order: the same program reads
// it): per part its material (an index into the materials, or -1), its
// triangles as the file places them (before the shape's transform), their
// vertex normals and texture coordinates where the part has them; then the
// materials and the textures they use.
// A result that does not read as WireWriter wrote it: the child's memory
// was corrupted (by the reader) or its message cut short.
struct WireError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// `parts` (their triangles as the file places them) with the material of
// each part (an index into files.materials, or -1), then files' materials
// and textures, as bytes.
std::string mesh_to_wire(const PartBuilder& parts, const std::vector<int>& part_materials,
                         const MeshParts& files);

// The parts mesh_to_wire wrote, each made a shape (model, `material` for
// the faces without the file's), checked again here: the child's memory
// may have been corrupted by the reader without its crashing. Throws
// WireError for what does not read as mesh_to_wire writes it.
MeshParts mesh_from_wire(const std::string& bytes, const glm::mat4& model, int material);

}  // namespace trac0r

#endif
