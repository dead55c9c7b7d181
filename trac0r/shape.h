// Shapes: triangle lists made by the factories of the scene format, each
// with one AABB and one material (the thesis' structure).
#ifndef TRAC0R_SHAPE_H
#define TRAC0R_SHAPE_H

#include "trac0r/geometry.h"
#include "trac0r/material.h"
#include "trac0r/model_defects.h"
#include "trac0r/texture.h"

#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

namespace trac0r {

// A triangle's unit normals at v0, v1, v2, for smooth shading; all zero
// where it has none (it is shaded flat).
using VertexNormalTriple = std::array<glm::vec3, 3>;

// A triangle's tangents at v0, v1, v2, for normal maps: xyz the direction
// of increasing u, w the bitangent's sign (the bitangent, the direction of
// increasing v, is w * cross(normal, tangent), as glTF's TANGENT and
// MikkTSpace define it); all zero where it has none.
using VertexTangentTriple = std::array<glm::vec4, 3>;

// A triangle's texture coordinates at v0, v1, v2 (u right, v up from the
// image's bottom), where the file gives them.
struct TriangleUv {
    std::array<glm::vec2, 3> uv{};
    bool present = false;
};

struct Shape {
    std::vector<Triangle> triangles;
    // Empty: every triangle is flat. Else one per triangle (a mesh whose
    // file gives vertex normals, with "smooth" on).
    std::vector<VertexNormalTriple> normals;
    // Empty: no triangle has texture coordinates. Else one per triangle.
    std::vector<TriangleUv> uvs;
    // Empty: the file gives no tangents (they are computed from the
    // texture coordinates where a normal map needs them, tangents.h). Else
    // one per triangle.
    std::vector<VertexTangentTriple> tangents;
    AABB aabb;
    int material = 0;    // index into Scene::materials
    std::string source;  // a mesh's file, as the scene loader found it; "" for the rest
};

// model = T * Rx * Ry * Rz * S (scale first, then z, y, x rotations in
// radians, then translation), as in the thesis.
glm::mat4 model_matrix(const glm::vec3& position, const glm::vec3& orientation,
                       const glm::vec3& scale);

// Applies the model matrix to every vertex and recomputes the AABB; and to
// the vertex normals, where given (one per triangle), by its inverse
// transpose. Texture coordinates, where given (one per triangle), stay
// with their vertices; tangents, where given, turn with the model matrix
// (their sign flips where it mirrors).
Shape make_shape(std::vector<Triangle> local_triangles, const glm::mat4& model, int material,
                 const std::vector<VertexNormalTriple>& local_normals = {},
                 const std::vector<TriangleUv>& local_uvs = {},
                 const std::vector<VertexTangentTriple>& local_tangents = {});

// The unit plane in local xz (normal +y), size (x, z).
Shape make_plane(const glm::vec3& position, const glm::vec3& orientation, const glm::vec2& size,
                 int material);
// The unit cube centred at the origin, scaled by size.
Shape make_box(const glm::vec3& position, const glm::vec3& orientation, const glm::vec3& size,
               int material);
// The unit icosahedron subdivided n times (20 * 4^n triangles), radius r.
Shape make_icosphere(const glm::vec3& position, const glm::vec3& orientation, float radius,
                     int subdivisions, int material);
// The faces of a mesh file that share a material, as a Shape.
struct MeshPart {
    Shape shape;
    int material = -1;  // index into MeshParts::materials; -1: the shape's own
};

struct MeshParts {
    std::vector<MeshPart> parts;      // in the order their materials are first used
    std::vector<Material> materials;  // the file's materials that faces use, mapped
    std::vector<Texture> textures;    // their base-colour textures (Material::texture)
    std::vector<std::string> warnings;  // a reader's warning lines (ModelDefects::lines)
};

// A mesh file split by its faces' materials: a PLY or glTF 2.0 by its
// extension (.ply, .gltf, .glb, any case), else an OBJ; a file that is not
// of the format its extension names is refused (assimp's reader of that
// format alone reads it, never one that guesses from the contents). An OBJ (tinyobjloader, after
// trac0r's checker) with the materials of its mtllib files (relative to
// the OBJ, checked as checked_mtl_text says), a PLY, or a glTF 2.0 (.gltf,
// .glb; assimp) with its metallic-roughness materials. Each material is
// mapped to one of the renderer's four (docs/scene-format.md, "Materials
// from the file"); faces without one, and every face when
// `file_materials` is false, take `material`. Smooth as load_obj_mesh.
// Throws std::runtime_error naming the file (and line, or material) for
// a file that cannot be read and a material that cannot be mapped. Its
// textures may have `texel_budget` texels in all (what the scene has room
// for): each is refused from its image's header, before it is decoded,
// where it would go over.
// `defects`: where the file's defects that leave it renderable are
// reported (model_defects.h; its warnings end up there); nullptr: each is
// an error.
MeshParts load_mesh_parts(const std::string& path, const glm::vec3& position,
                          const glm::vec3& orientation, const glm::vec3& scale, int material,
                          bool smooth, bool file_materials,
                          std::uint64_t texel_budget = max_scene_texels,
                          ModelDefects* defects = nullptr);

// A PLY or glTF file is read (by assimp) in a child process of its own,
// so that a reader that crashes, hangs or corrupts memory on a malformed
// file is one clear error naming the file, not the program's end; one
// that runs longer than this limit (300 s unless set) is stopped. Throws
// std::invalid_argument unless seconds is in (0, 1e6]. Not thread-safe:
// for a program's start (the fuzzer sets less than its own time limit).
void set_mesh_import_time_limit(double seconds);
double mesh_import_time_limit();

// An OBJ mesh (all its shapes, faces triangulated). With `smooth`, a face
// whose three vertices have normals (vn) is shaded with them; without, or
// where a vertex has none, the face is flat. Throws std::runtime_error
// naming the file when it cannot be read.
Shape load_obj_mesh(const std::string& path, const glm::vec3& position,
                    const glm::vec3& orientation, const glm::vec3& scale, int material,
                    bool smooth = true);

}  // namespace trac0r

#endif
