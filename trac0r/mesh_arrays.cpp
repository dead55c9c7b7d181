#include "trac0r/mesh_arrays.h"

#include "trac0r/scene_builder.h"
#include "trac0r/shape.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace trac0r {

namespace {

// An array's or argument's problem: "FIELD: PROBLEM".
void require(bool ok, const std::string& field, const std::string& problem) {
    if (!ok) {
        throw SceneValueError("mesh", field, "", problem);
    }
}

// The vertices' count of an array of `width` numbers a vertex.
std::size_t vertex_count(const std::vector<float>& values, std::size_t width, const char* name,
                         const char* what) {
    require(values.size() % width == 0, name,
            "expected " + std::to_string(width) + " numbers a vertex (" + what + "), got " +
                std::to_string(values.size()) + " numbers");
    for (std::size_t i = 0; i < values.size(); ++i) {
        require(std::isfinite(values[i]), name,
                "vertex " + std::to_string(i / width) + " has a number that is not finite");
    }
    return values.size() / width;
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 vec3_at(const std::vector<float>& v, std::size_t i) {
    return glm::vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
}

}  // namespace

void SceneBuilder::add_mesh(const MeshArrays& mesh, const MeshPlacement& placement) {
    const std::size_t vertices = vertex_count(mesh.positions, 3, "positions", "x, y, z");
    require(vertices > 0, "positions", "expected at least 3 vertices, got none");
    if (!mesh.normals.empty()) {
        require(vertex_count(mesh.normals, 3, "normals", "x, y, z") == vertices, "normals",
                "expected one a vertex (" + std::to_string(vertices) + "), got " +
                    std::to_string(mesh.normals.size() / 3));
    }
    if (!mesh.uvs.empty()) {
        require(vertex_count(mesh.uvs, 2, "uvs", "u, v") == vertices, "uvs",
                "expected one a vertex (" + std::to_string(vertices) + "), got " +
                    std::to_string(mesh.uvs.size() / 2));
    }
    require(!mesh.indices.empty() && mesh.indices.size() % 3 == 0, "indices",
            "expected 3 a triangle, got " + std::to_string(mesh.indices.size()));
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
        require(mesh.indices[i] < vertices, "indices",
                "triangle " + std::to_string(i / 3) + " has vertex " +
                    std::to_string(mesh.indices[i]) + ", past the " + std::to_string(vertices) +
                    " vertices");
    }
    require(placement.scale.x != 0.0f && placement.scale.y != 0.0f && placement.scale.z != 0.0f &&
                finite(glm::dvec3(placement.scale)),
            "scale", "expected three finite numbers, none zero");
    require(finite(placement.position), "position", "expected three finite numbers");
    require(finite(glm::dvec3(placement.orientation)), "orientation",
            "expected three finite numbers");
    const std::size_t count = mesh.indices.size() / 3;
    std::vector<Triangle> triangles;
    std::vector<VertexNormalTriple> normals;
    std::vector<TriangleUv> uvs;
    triangles.reserve(count);
    for (std::size_t t = 0; t < count; ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        triangles.emplace_back(vec3_at(mesh.positions, v[0]), vec3_at(mesh.positions, v[1]),
                               vec3_at(mesh.positions, v[2]));
        if (!mesh.normals.empty()) {
            VertexNormalTriple n;
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 given = vec3_at(mesh.normals, v[k]);
                const float length = glm::length(given);
                n[static_cast<std::size_t>(k)] = length > 0.0f ? given / length : glm::vec3(0.0f);
            }
            normals.push_back(n);
        }
        if (!mesh.uvs.empty()) {
            TriangleUv uv;
            for (int k = 0; k < 3; ++k) {
                uv.uv[static_cast<std::size_t>(k)] =
                    glm::vec2(mesh.uvs[2 * v[k]], mesh.uvs[2 * v[k] + 1]);
            }
            uv.present = true;
            uvs.push_back(uv);
        }
    }
    const glm::vec3 position = glm::vec3(placement.position - scene_.origin);
    const glm::mat4 model = model_matrix(position, placement.orientation, placement.scale);
    Shape shape = make_shape(std::move(triangles), model, 0, normals, uvs);
    // The material last, so that a refused mesh adds no default material.
    check_usable({shape}, "mesh");
    shape.material = material_index(placement.material, "mesh");
    scene_.shapes.push_back(std::move(shape));
}

void add_mesh(Scene& scene, const MeshArrays& mesh, const MeshPlacement& placement) {
    SceneBuilder(scene).add_mesh(mesh, placement);
}

}  // namespace trac0r
