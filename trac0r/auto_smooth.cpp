#include "trac0r/auto_smooth.h"

#include "trac0r/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace trac0r {

namespace {

struct PositionHash {
    std::size_t operator()(const glm::vec3& p) const {
        std::uint64_t h = 1469598103934665603ull;
        for (int k = 0; k < 3; ++k) {
            const float v = p[k] + 0.0f;  // -0 and +0 alike
            std::uint32_t bits;
            std::memcpy(&bits, &v, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        return static_cast<std::size_t>(h);
    }
};

struct Corner {
    glm::dvec3 normal;  // its triangle's, unit
    double angle;       // the triangle's angle there
};

bool flat(const Shape& s, std::size_t t) {
    return t >= s.normals.size() || !(glm::length(s.normals[t][0]) > 0.0f);
}

}  // namespace

void auto_smooth(std::vector<Shape>& shapes, float degrees) {
    const double cos_limit =
        std::cos(static_cast<double>(degrees) * 3.14159265358979323846 / 180.0);
    // Per triangle without normals (in shapes' order), its unit normal;
    // zero where it has no area. Per position, the corners of those
    // triangles there.
    std::vector<glm::dvec3> units;
    std::unordered_map<glm::vec3, std::vector<Corner>, PositionHash> at;
    for (const Shape& s : shapes) {
        for (std::size_t t = 0; t < s.triangles.size(); ++t) {
            if (!flat(s, t)) {
                continue;
            }
            const Triangle& tri = s.triangles[t];
            const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
            const glm::dvec3 n = glm::cross(glm::dvec3(p[1] - p[0]), glm::dvec3(p[2] - p[0]));
            const double length = glm::length(n);
            const bool area = length > 0.0 && std::isfinite(length);
            units.push_back(area ? n / length : glm::dvec3(0.0));
            if (!area) {
                continue;
            }
            for (int k = 0; k < 3; ++k) {
                at[p[k]].push_back(
                    {units.back(), corner_angle(glm::dvec3(p[k]), glm::dvec3(p[(k + 1) % 3]),
                                                glm::dvec3(p[(k + 2) % 3]))});
            }
        }
    }
    std::size_t next = 0;  // into units
    for (Shape& s : shapes) {
        for (std::size_t t = 0; t < s.triangles.size(); ++t) {
            if (!flat(s, t)) {
                continue;
            }
            const glm::dvec3 own = units[next++];
            if (own == glm::dvec3(0.0)) {
                continue;
            }
            const Triangle& tri = s.triangles[t];
            const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
            VertexNormalTriple normals{};
            bool usable = true;
            for (int k = 0; k < 3 && usable; ++k) {
                glm::dvec3 sum(0.0);
                for (const Corner& c : at[p[k]]) {
                    if (glm::dot(c.normal, own) >= cos_limit - 1e-12) {
                        sum += c.normal * c.angle;
                    }
                }
                const double l = glm::length(sum);
                usable = l > 0.0 && std::isfinite(l);
                normals[k] = usable ? glm::vec3(sum / l) : glm::vec3(0.0f);
            }
            if (!usable) {
                continue;
            }
            if (s.normals.size() != s.triangles.size()) {
                s.normals.assign(s.triangles.size(), VertexNormalTriple{});
            }
            s.normals[t] = normals;
        }
    }
}

}  // namespace trac0r
