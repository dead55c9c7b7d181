#include "trac0r/tangents.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace trac0r {

namespace {

// What makes corners one vertex: position, normal, texture coordinates
// and the tangent's sign.
struct CornerKey {
    std::array<float, 9> values;
    bool operator==(const CornerKey& other) const { return values == other.values; }
};

struct CornerKeyHash {
    std::size_t operator()(const CornerKey& key) const {
        std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the bits
        for (float v : key.values) {
            std::uint32_t bits;
            std::memcpy(&bits, &v, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        return static_cast<std::size_t>(h);
    }
};

CornerKey corner_key(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv,
                     float sign) {
    // + 0.0f: -0 and +0 are one value (and hash alike).
    return {{position.x + 0.0f, position.y + 0.0f, position.z + 0.0f, normal.x + 0.0f,
             normal.y + 0.0f, normal.z + 0.0f, uv.x + 0.0f, uv.y + 0.0f, sign}};
}

// The angle of a triangle at corner p between the edges to a and b.
float corner_angle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 e1 = a - p;
    const glm::vec3 e2 = b - p;
    const float l = glm::length(e1) * glm::length(e2);
    if (!(l > 0.0f)) {
        return 0.0f;
    }
    return std::acos(std::min(1.0f, std::max(-1.0f, glm::dot(e1, e2) / l)));
}

// `v` without its component along the unit normal n, normalised; zero
// where nothing is left.
glm::vec3 projected_unit(const glm::vec3& v, const glm::vec3& n) {
    const glm::vec3 p = v - n * glm::dot(n, v);
    const float l = glm::length(p);
    return l > 0.0f && std::isfinite(l) ? p / l : glm::vec3(0.0f);
}

}  // namespace

std::vector<VertexTangentTriple> uv_tangents(const Shape& shape) {
    const std::size_t n = shape.triangles.size();
    std::vector<VertexTangentTriple> out(n, VertexTangentTriple{});
    if (shape.uvs.size() != n) {
        return out;
    }
    // Per corner (3 t + k): its normal, its triangle's projected tangent
    // times the corner's angle, and its vertex (an index into sums).
    std::vector<glm::vec3> normals(3 * n, glm::vec3(0.0f));
    std::vector<float> signs(n, 0.0f);
    std::vector<std::uint32_t> vertex_of(3 * n, 0);
    std::vector<glm::vec3> sums;
    std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> vertices;
    for (std::size_t t = 0; t < n; ++t) {
        const TriangleUv& uv = shape.uvs[t];
        if (!uv.present) {
            continue;
        }
        const Triangle& tri = shape.triangles[t];
        const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
        const glm::vec3 dp1 = p[1] - p[0];
        const glm::vec3 dp2 = p[2] - p[0];
        const glm::vec2 duv1 = uv.uv[1] - uv.uv[0];
        const glm::vec2 duv2 = uv.uv[2] - uv.uv[0];
        const float det = duv1.x * duv2.y - duv2.x * duv1.y;
        const glm::vec3 face_normal = glm::cross(dp1, dp2);
        if (!(std::fabs(det) > 0.0f) || !(glm::length(face_normal) > 0.0f)) {
            continue;
        }
        // dp/du and dp/dv; only their directions matter.
        const glm::vec3 tangent = (dp1 * duv2.y - dp2 * duv1.y) / det;
        const glm::vec3 bitangent = (dp2 * duv1.x - dp1 * duv2.x) / det;
        const glm::vec3 geometric = glm::normalize(face_normal);
        const bool smooth = t < shape.normals.size() && glm::length(shape.normals[t][0]) > 0.0f;
        const float sign =
            glm::dot(glm::cross(geometric, tangent), bitangent) < 0.0f ? -1.0f : 1.0f;
        signs[t] = sign;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 normal = smooth ? shape.normals[t][k] : geometric;
            normals[3 * t + k] = normal;
            const glm::vec3 weighted = projected_unit(tangent, normal) *
                                       corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            const auto found = vertices.emplace(corner_key(p[k], normal, uv.uv[k], sign),
                                                static_cast<std::uint32_t>(sums.size()));
            if (found.second) {
                sums.push_back(glm::vec3(0.0f));
            }
            vertex_of[3 * t + k] = found.first->second;
            sums[found.first->second] += weighted;
        }
    }
    for (std::size_t t = 0; t < n; ++t) {
        if (signs[t] == 0.0f) {
            continue;
        }
        VertexTangentTriple result{};
        bool usable = true;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 tangent =
                projected_unit(sums[vertex_of[3 * t + k]], normals[3 * t + k]);
            usable = usable && glm::length(tangent) > 0.0f;
            result[k] = glm::vec4(tangent, signs[t]);
        }
        if (usable) {
            out[t] = result;
        }
    }
    return out;
}

}  // namespace trac0r
