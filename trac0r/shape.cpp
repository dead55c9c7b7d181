#include "trac0r/shape.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <istream>
#include <streambuf>
#include <stdexcept>
#include <utility>

namespace trac0r {

glm::mat4 model_matrix(const glm::vec3& position, const glm::vec3& orientation,
                       const glm::vec3& scale) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
    m = glm::rotate(m, orientation.x, glm::vec3(1, 0, 0));
    m = glm::rotate(m, orientation.y, glm::vec3(0, 1, 0));
    m = glm::rotate(m, orientation.z, glm::vec3(0, 0, 1));
    return glm::scale(m, scale);
}

Shape make_shape(std::vector<Triangle> local_triangles, const glm::mat4& model, int material,
                 const std::vector<VertexNormalTriple>& local_normals,
                 const std::vector<TriangleUv>& local_uvs,
                 const std::vector<VertexTangentTriple>& local_tangents) {
    // A mirroring transform turns the winding inside out; swap two vertices
    // so normals keep pointing out of closed shapes (glass needs that).
    const bool mirrored = glm::determinant(glm::mat3(model)) < 0.0f;
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
    Shape shape;
    shape.material = material;
    shape.triangles.reserve(local_triangles.size());
    for (const Triangle& t : local_triangles) {
        const glm::vec3 a = glm::vec3(model * glm::vec4(t.v0, 1.0f));
        const glm::vec3 b = glm::vec3(model * glm::vec4(t.v1, 1.0f));
        const glm::vec3 c = glm::vec3(model * glm::vec4(t.v2, 1.0f));
        shape.triangles.push_back(mirrored ? Triangle(a, c, b) : Triangle(a, b, c));
        shape.aabb.extend(shape.triangles.back().bounds());
    }
    shape.normals.reserve(local_normals.size());
    for (const VertexNormalTriple& n : local_normals) {
        VertexNormalTriple world = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
        const VertexNormalTriple moved = {normal_matrix * n[0], normal_matrix * n[1],
                                          normal_matrix * n[2]};
        // Flat stays flat (zero); a normal the transform makes unusable
        // (not finite, or of no length) makes the triangle flat.
        bool usable = glm::length(n[0]) > 0.0f;
        for (const glm::vec3& m : moved) {
            const float length = glm::length(m);
            usable = usable && is_finite(m) && length > 0.0f && std::isfinite(length);
        }
        if (usable) {
            world = {glm::normalize(moved[0]), glm::normalize(moved[mirrored ? 2 : 1]),
                     glm::normalize(moved[mirrored ? 1 : 2])};
        }
        shape.normals.push_back(world);
    }
    shape.uvs = local_uvs;
    if (mirrored) {
        for (TriangleUv& t : shape.uvs) {
            std::swap(t.uv[1], t.uv[2]);
        }
    }
    shape.tangents.reserve(local_tangents.size());
    const glm::mat3 linear(model);
    for (const VertexTangentTriple& t : local_tangents) {
        VertexTangentTriple world{};
        bool usable = t[0].w != 0.0f;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 moved = linear * glm::vec3(t[k]);
            const float length = glm::length(moved);
            usable = usable && is_finite(moved) && length > 0.0f && std::isfinite(length);
            world[k] = glm::vec4(usable ? moved / length : glm::vec3(0.0f),
                                 mirrored ? -t[k].w : t[k].w);
        }
        if (!usable) {
            world = VertexTangentTriple{};  // none: computed from the coordinates
        } else if (mirrored) {
            std::swap(world[1], world[2]);
        }
        shape.tangents.push_back(world);
    }
    return shape;
}

namespace {

// Two triangles of the quad centre +- u/2 +- v/2, wound so their normal is
// cross(u, v).
void add_quad(std::vector<Triangle>& out, const glm::vec3& centre, const glm::vec3& u,
              const glm::vec3& v) {
    const glm::vec3 a = centre - 0.5f * u - 0.5f * v;
    const glm::vec3 b = centre + 0.5f * u - 0.5f * v;
    const glm::vec3 c = centre + 0.5f * u + 0.5f * v;
    const glm::vec3 d = centre - 0.5f * u + 0.5f * v;
    out.emplace_back(a, b, c);
    out.emplace_back(a, c, d);
}

std::vector<Triangle> unit_icosphere(int subdivisions) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : v) {
        p = glm::normalize(p);
    }
    std::vector<std::array<int, 3>> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<int, int>, int> midpoints;
        auto midpoint = [&](int i, int j) {
            const std::pair<int, int> key(std::min(i, j), std::max(i, j));
            auto found = midpoints.find(key);
            if (found != midpoints.end()) {
                return found->second;
            }
            v.push_back(glm::normalize(v[i] + v[j]));
            const int index = static_cast<int>(v.size()) - 1;
            midpoints[key] = index;
            return index;
        };
        std::vector<std::array<int, 3>> next;
        next.reserve(faces.size() * 4);
        for (const auto& f : faces) {
            const int ab = midpoint(f[0], f[1]);
            const int bc = midpoint(f[1], f[2]);
            const int ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces.swap(next);
    }
    std::vector<Triangle> out;
    out.reserve(faces.size());
    for (const auto& f : faces) {
        Triangle tri(v[f[0]], v[f[1]], v[f[2]]);
        // Convex and centred on the origin: outward means away from it.
        if (glm::dot(tri.normal, tri.centroid) < 0.0f) {
            tri = Triangle(v[f[0]], v[f[2]], v[f[1]]);
        }
        out.push_back(tri);
    }
    return out;
}

}  // namespace

Shape make_plane(const glm::vec3& position, const glm::vec3& orientation, const glm::vec2& size,
                 int material) {
    std::vector<Triangle> local;
    // Normal +y = cross(+z, +x).
    add_quad(local, glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0));
    return make_shape(local, model_matrix(position, orientation, glm::vec3(size.x, 1.0f, size.y)),
                      material);
}

Shape make_box(const glm::vec3& position, const glm::vec3& orientation, const glm::vec3& size,
               int material) {
    const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    std::vector<Triangle> local;
    // Each face's (u, v) has cross(u, v) along its outward normal.
    add_quad(local, 0.5f * x, y, z);
    add_quad(local, -0.5f * x, z, y);
    add_quad(local, 0.5f * y, z, x);
    add_quad(local, -0.5f * y, x, z);
    add_quad(local, 0.5f * z, x, y);
    add_quad(local, -0.5f * z, y, x);
    return make_shape(local, model_matrix(position, orientation, size), material);
}

Shape make_icosphere(const glm::vec3& position, const glm::vec3& orientation, float radius,
                     int subdivisions, int material) {
    return make_shape(unit_icosphere(subdivisions),
                      model_matrix(position, orientation, glm::vec3(radius)), material);
}

}  // namespace trac0r
