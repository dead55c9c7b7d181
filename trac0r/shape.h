// Shapes: triangle lists made by the factories of the scene format, each
// with one AABB and one material (the thesis' structure).
#ifndef TRAC0R_SHAPE_H
#define TRAC0R_SHAPE_H

#include "trac0r/geometry.h"

#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

namespace trac0r {

// A triangle's unit normals at v0, v1, v2, for smooth shading; all zero
// where it has none (it is shaded flat).
using VertexNormalTriple = std::array<glm::vec3, 3>;

struct Shape {
    std::vector<Triangle> triangles;
    // Empty: every triangle is flat. Else one per triangle (a mesh whose
    // file gives vertex normals, with "smooth" on).
    std::vector<VertexNormalTriple> normals;
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
// transpose.
Shape make_shape(std::vector<Triangle> local_triangles, const glm::mat4& model, int material,
                 const std::vector<VertexNormalTriple>& local_normals = {});

// The unit plane in local xz (normal +y), size (x, z).
Shape make_plane(const glm::vec3& position, const glm::vec3& orientation, const glm::vec2& size,
                 int material);
// The unit cube centred at the origin, scaled by size.
Shape make_box(const glm::vec3& position, const glm::vec3& orientation, const glm::vec3& size,
               int material);
// The unit icosahedron subdivided n times (20 * 4^n triangles), radius r.
Shape make_icosphere(const glm::vec3& position, const glm::vec3& orientation, float radius,
                     int subdivisions, int material);
// A material of an OBJ's MTL library as the file gives it; the scene
// loader maps it to one of the renderer's four (scene_loader.cpp).
struct MtlMaterial {
    std::string name;
    std::string file;              // the .mtl it came from
    glm::vec3 diffuse{0.0f};       // Kd
    glm::vec3 specular{0.0f};      // Ks
    glm::vec3 emission{0.0f};      // Ke
    glm::vec3 transmission{0.0f};  // Tf
    float shininess = 0.0f;        // Ns
    float ior = 1.0f;              // Ni
    float dissolve = 1.0f;         // d (or 1 - Tr); 1 is opaque
    int illum = 0;                 // the illumination model
};

// The faces of an OBJ mesh that share a material, as a Shape.
struct ObjPart {
    Shape shape;
    int mtl = -1;  // index into ObjMesh::materials; -1: faces with no usemtl
};

struct ObjMesh {
    std::vector<ObjPart> parts;          // in the order their materials are first used
    std::vector<MtlMaterial> materials;  // the MTL materials the faces use
};

// An OBJ mesh split by its faces' materials (usemtl), each material read
// from the mtllib files (relative to the OBJ's directory), checked as
// checked_mtl_text says; each part's shape has material `material`, which
// the caller replaces for the parts with an MTL material. Smooth as
// load_obj_mesh. Throws std::runtime_error "path:line: ..." for a library
// that cannot be read and a usemtl that names no material of them.
ObjMesh load_obj_parts(const std::string& path, const glm::vec3& position,
                       const glm::vec3& orientation, const glm::vec3& scale, int material,
                       bool smooth);

// An OBJ mesh (all its shapes, faces triangulated). With `smooth`, a face
// whose three vertices have normals (vn) is shaded with them; without, or
// where a vertex has none, the face is flat. Throws std::runtime_error
// naming the file when it cannot be read.
Shape load_obj_mesh(const std::string& path, const glm::vec3& position,
                    const glm::vec3& orientation, const glm::vec3& scale, int material,
                    bool smooth = true);

}  // namespace trac0r

#endif
