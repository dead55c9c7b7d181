#include "trac0r/light_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace trac0r {

namespace {

const double pi = 3.14159265358979323846;

// A cone of directions: unit axis w and the cosine of its half-angle (-1:
// every direction).
struct Cone {
    glm::dvec3 w{0.0, 0.0, 1.0};
    double cos_theta = 1.0;
};

double angle_of(double cosine) { return std::acos(std::min(1.0, std::max(-1.0, cosine))); }

// The smallest cone holding both (pbrt-v4's DirectionCone Union).
Cone cone_union(const Cone& a, const Cone& b) {
    const double theta_a = angle_of(a.cos_theta);
    const double theta_b = angle_of(b.cos_theta);
    const double theta_d = angle_of(glm::dot(a.w, b.w));
    if (std::min(theta_d + theta_b, pi) <= theta_a) {
        return a;
    }
    if (std::min(theta_d + theta_a, pi) <= theta_b) {
        return b;
    }
    const double theta_o = 0.5 * (theta_a + theta_d + theta_b);
    const glm::dvec3 axis = glm::cross(a.w, b.w);
    if (theta_o >= pi || !(glm::dot(axis, axis) > 1e-24)) {
        return Cone{glm::dvec3(0.0, 0.0, 1.0), -1.0};
    }
    // a.w turned by theta_o - theta_a about a.w x b.w (Rodrigues).
    const glm::dvec3 k = glm::normalize(axis);
    const double r = theta_o - theta_a;
    const glm::dvec3 w = a.w * std::cos(r) + glm::cross(k, a.w) * std::sin(r) +
                         k * glm::dot(k, a.w) * (1.0 - std::cos(r));
    return Cone{glm::normalize(w), std::cos(theta_o)};
}

// What the tree keeps of the lights under a node, in double.
struct Bounds {
    glm::dvec3 lo{std::numeric_limits<double>::max()};
    glm::dvec3 hi{-std::numeric_limits<double>::max()};
    double power = 0.0;  // the peak intensities' sum (light_tree.h: importance)
    Cone normals;        // theta_o
    double cos_e = 1.0;  // how far past the normals light leaves
    bool two_sided = false;
};

Bounds bounds_union(const Bounds& a, const Bounds& b) {
    Bounds u;
    u.lo = glm::min(a.lo, b.lo);
    u.hi = glm::max(a.hi, b.hi);
    u.power = a.power + b.power;
    u.normals = cone_union(a.normals, b.normals);
    u.cos_e = std::min(a.cos_e, b.cos_e);
    u.two_sided = a.two_sided || b.two_sided;
    return u;
}

Bounds light_bounds(const PackedScene& packed, const kernel::LightRecord& light, double power) {
    Bounds b;
    b.power = power;
    if (light.ids.y == T0_LIGHT_TRIANGLE) {
        const kernel::TriangleRecord& t = packed.triangles[light.ids.x];
        for (const glm::vec4* v : {&t.v0, &t.v1, &t.v2}) {
            b.lo = glm::min(b.lo, glm::dvec3(glm::vec3(*v)));
            b.hi = glm::max(b.hi, glm::dvec3(glm::vec3(*v)));
        }
        b.normals = Cone{glm::dvec3(glm::vec3(t.normal)), 1.0};
        b.cos_e = 0.0;  // a surface: light leaves up to 90 degrees from its normal
        b.two_sided = packed.materials[t.ids.x].type.z == 0u;
        return b;
    }
    b.lo = b.hi = glm::dvec3(glm::vec3(light.a));
    if (light.ids.y == T0_LIGHT_SPOT) {
        // The cone of full intensity, and beyond it the soft edge.
        const double inner = angle_of(light.c.w);
        const double outer = angle_of(light.a.w);
        b.normals = Cone{glm::dvec3(glm::vec3(light.c)), light.c.w};
        b.cos_e = std::cos(std::max(0.0, outer - inner));
        return b;
    }
    b.normals = Cone{glm::dvec3(0.0, 0.0, 1.0), -1.0};  // a point lamp: every direction
    b.cos_e = 0.0;
    return b;
}

// A cosine stored in float a little below its value, so that float's
// rounding never makes a cone narrower than the lights in it.
float widened(double cosine) {
    return static_cast<float>(std::max(-1.0, std::min(1.0, cosine) - 1e-5));
}

kernel::LightTreeNode node_of(const Bounds& b) {
    kernel::LightTreeNode n{};
    n.lo = glm::vec4(glm::vec3(b.lo), static_cast<float>(b.power));
    n.hi = glm::vec4(glm::vec3(b.hi), widened(b.normals.cos_theta));
    n.axis = glm::vec4(glm::vec3(b.normals.w), widened(b.cos_e));
    n.info = glm::uvec4(0u, 0u, b.two_sided ? 1u : 0u, 0u);
    return n;
}

struct Builder {
    PackedScene& packed;
    std::vector<Bounds> leaves;      // by light index
    std::vector<glm::dvec3> centre;  // by light index

    // The subtree over lights[first, last) into node `at`; its bounds.
    Bounds build(std::vector<std::uint32_t>& lights, std::size_t first, std::size_t last,
                 std::uint32_t at, std::uint32_t trail, int depth) {
        if (last - first == 1) {
            const std::uint32_t light = lights[first];
            kernel::LightTreeNode n = node_of(leaves[light]);
            n.info.x = light;
            n.info.y = 1u;
            packed.light_nodes[at] = n;
            packed.lights[light].ids.z = trail;
            return leaves[light];
        }
        glm::dvec3 lo(std::numeric_limits<double>::max());
        glm::dvec3 hi(-std::numeric_limits<double>::max());
        for (std::size_t i = first; i < last; ++i) {
            lo = glm::min(lo, centre[lights[i]]);
            hi = glm::max(hi, centre[lights[i]]);
        }
        const glm::dvec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const std::size_t middle = first + (last - first) / 2;
        std::nth_element(
            lights.begin() + static_cast<long>(first), lights.begin() + static_cast<long>(middle),
            lights.begin() + static_cast<long>(last), [&](std::uint32_t a, std::uint32_t b) {
                return centre[a][axis] < centre[b][axis] ||
                       (centre[a][axis] == centre[b][axis] && a < b);
            });
        const std::uint32_t children = static_cast<std::uint32_t>(packed.light_nodes.size());
        packed.light_nodes.resize(packed.light_nodes.size() + 2);
        const Bounds left = build(lights, first, middle, children, trail, depth + 1);
        const Bounds right =
            build(lights, middle, last, children + 1, trail | (1u << depth), depth + 1);
        const Bounds both = bounds_union(left, right);
        kernel::LightTreeNode n = node_of(both);
        n.info.x = children;
        packed.light_nodes[at] = n;
        return both;
    }
};

}  // namespace

void build_light_tree(PackedScene& packed, const std::vector<double>& intensity) {
    Builder b{packed, {}, {}};
    std::vector<std::uint32_t> lights;
    b.leaves.resize(packed.lights.size());
    b.centre.resize(packed.lights.size());
    for (std::uint32_t i = packed.distant_count; i < packed.lights.size(); ++i) {
        b.leaves[i] = light_bounds(packed, packed.lights[i], intensity[i]);
        b.centre[i] = 0.5 * (b.leaves[i].lo + b.leaves[i].hi);
        lights.push_back(i);
    }
    packed.light_nodes.clear();
    if (lights.empty()) {
        return;
    }
    packed.light_nodes.resize(1);
    b.build(lights, 0, lights.size(), 0u, 0u, 0);
}

}  // namespace trac0r
