#include "trac0r/smoothing_groups.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace trac0r {

std::vector<VertexNormalTriple> smoothing_group_normals(
    const std::vector<glm::vec3>& positions, const std::vector<GroupedTriangle>& triangles) {
    const VertexNormalTriple flat = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    std::vector<VertexNormalTriple> out(triangles.size(), flat);
    // Per (vertex, group): the sum of the angle-weighted unit normals.
    std::map<std::pair<std::uint32_t, std::uint32_t>, glm::dvec3> sums;
    std::vector<glm::dvec3> unit(triangles.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const GroupedTriangle& tri = triangles[t];
        if (tri.group == 0) {
            continue;
        }
        const glm::dvec3 p[3] = {glm::dvec3(positions[tri.vertex[0]]),
                                 glm::dvec3(positions[tri.vertex[1]]),
                                 glm::dvec3(positions[tri.vertex[2]])};
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double length = glm::length(n);
        if (!(length > 0.0) || !std::isfinite(length)) {
            continue;
        }
        unit[t] = n / length;
        for (int k = 0; k < 3; ++k) {
            sums[{tri.vertex[k], tri.group}] +=
                unit[t] * corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
        }
    }
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const GroupedTriangle& tri = triangles[t];
        if (tri.group == 0 || unit[t] == glm::dvec3(0.0)) {
            continue;
        }
        VertexNormalTriple normals = flat;
        bool usable = true;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 sum = sums[{tri.vertex[k], tri.group}];
            const double length = glm::length(sum);
            usable = usable && length > 0.0 && std::isfinite(length);
            if (usable) {
                normals[k] = glm::vec3(sum / length);
            }
        }
        if (usable) {
            out[t] = normals;
        }
    }
    return out;
}

}  // namespace trac0r
