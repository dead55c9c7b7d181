// The BVH: a valid tree over every triangle, and traversal that finds
// exactly what testing every triangle finds.
#include <catch2/catch.hpp>

#include "trac0r/bvh.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/intersect.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <algorithm>
#include <memory>
#include <random>

using namespace trac0r;

namespace {

// A scene of many small triangles in a unit cube, some sliver-thin.
Scene triangle_soup(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Shape shape;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        const float size = 0.05f + 0.1f * std::fabs(u(rng));
        shape.triangles.emplace_back(c, c + size * glm::vec3(u(rng), u(rng), u(rng)),
                                     c + size * glm::vec3(u(rng), u(rng), u(rng)));
        shape.aabb.extend(shape.triangles.back().bounds());
    }
    Scene scene;
    Material m;
    m.type = MaterialType::diffuse;
    scene.materials.push_back(m);
    scene.shapes.push_back(shape);
    return scene;
}

bool contains(const kernel::BvhNode& outer, const kernel::BvhNode& inner) {
    return glm::all(glm::lessThanEqual(glm::vec3(outer.aabb_min), glm::vec3(inner.aabb_min))) &&
           glm::all(glm::greaterThanEqual(glm::vec3(outer.aabb_max), glm::vec3(inner.aabb_max)));
}

// Checks the subtree at `node`; returns its depth and counts leaf triangles.
int check_subtree(const PackedScene& p, std::uint32_t node, std::vector<int>& seen) {
    const kernel::BvhNode& n = p.nodes[node];
    const std::uint32_t first = bvh_node_first(n);
    const std::uint32_t count = bvh_node_count(n);
    if (count > 0) {
        REQUIRE(count <= 4);
        for (std::uint32_t i = first; i < first + count; ++i) {
            ++seen.at(i);
            const kernel::TriangleRecord& t = p.triangles[i];
            // The record holds the vertices themselves, and the boxes are
            // built from the same floats: containment is exact.
            for (const glm::vec3& v : {glm::vec3(t.v0), glm::vec3(t.v1), glm::vec3(t.v2)}) {
                REQUIRE(glm::all(glm::lessThanEqual(glm::vec3(n.aabb_min), v)));
                REQUIRE(glm::all(glm::greaterThanEqual(glm::vec3(n.aabb_max), v)));
            }
        }
        return 1;
    }
    REQUIRE(first + 1 < p.nodes.size());
    REQUIRE(contains(n, p.nodes[first]));
    REQUIRE(contains(n, p.nodes[first + 1]));
    return 1 + std::max(check_subtree(p, first, seen), check_subtree(p, first + 1, seen));
}

void check_tree(const PackedScene& p) {
    std::vector<int> seen(p.triangles.size(), 0);
    const int depth = check_subtree(p, 0, seen);
    REQUIRE(depth == p.bvh_depth);
    REQUIRE(depth <= T0_BVH_STACK_SIZE);
    // Every triangle is in exactly one leaf.
    REQUIRE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

PackOptions with(Accel accel) {
    PackOptions o;
    o.accel = accel;
    return o;
}

}  // namespace

TEST_CASE("the BVH is a valid tree over every triangle", "[bvh]") {
    for (int count : {1, 2, 5, 100, 5000}) {
        CAPTURE(count);
        const PackedScene p = pack_scene(triangle_soup(count, 3), with(Accel::bvh));
        REQUIRE(p.features & T0_FEATURE_BVH);
        REQUIRE(p.shapes.empty());
        check_tree(p);
    }
    check_tree(pack_scene(builtin_scene(), with(Accel::bvh)));
}

TEST_CASE("a BVH over coincident triangles stays shallow", "[bvh]") {
    // All centroids equal: no SAH split exists, the builder must halve.
    Scene scene = triangle_soup(1, 1);
    const Triangle t = scene.shapes[0].triangles[0];
    scene.shapes[0].triangles.assign(20000, t);
    const PackedScene p = pack_scene(scene, with(Accel::bvh));
    check_tree(p);
}

TEST_CASE("BVH traversal finds the same nearest hit as testing every triangle", "[bvh]") {
    const Scene scene = triangle_soup(2000, 9);
    const PackedScene bvh = pack_scene(scene, with(Accel::bvh));
    const PackedScene flat = pack_scene(scene, with(Accel::flat));
    const kernel::SceneView bvh_view = bvh.view();
    const kernel::SceneView flat_view = flat.view();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 origin(u(rng), u(rng), u(rng));
        const glm::vec3 direction = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        const kernel::Ray ray = kernel::make_ray(origin, direction);
        const kernel::Hit a = kernel::traverse_bvh(&bvh_view, ray, T0_NO_HIT, 0);
        const kernel::Hit b = kernel::traverse_flat(&flat_view, ray, T0_NO_HIT, 0);
        REQUIRE((a.triangle >= 0) == (b.triangle >= 0));
        if (a.triangle >= 0) {
            ++hits;
            REQUIRE(a.t == b.t);  // the same triangle test on the same data
        }
        // Shadow rays: any hit below a limit, the same answer both ways.
        const float limit = 0.5f;
        REQUIRE(kernel::occluded(&bvh_view, ray, limit) == kernel::occluded(&flat_view, ray, limit));
        REQUIRE(kernel::occluded(&bvh_view, ray, limit) == (b.triangle >= 0 && b.t < limit));
    }
    REQUIRE(hits > 1000);  // the rays do meet the soup
}

TEST_CASE("flat and BVH renders of the Cornell box are the same image", "[bvh][render]") {
    Scene scene = builtin_scene();
    scene.render.width = 48;
    scene.render.height = 36;
    auto render = [&](Accel accel) {
        Renderer r(scene, std::make_unique<CpuBackend>(), 3, with(accel));
        for (int i = 0; i < 4; ++i) {
            r.render_frame();
        }
        return r.image();
    };
    // Same rays, same nearest hits: bit-identical (ties between coplanar
    // triangles could differ, and the Cornell box has none in view).
    REQUIRE(render(Accel::flat).pixels == render(Accel::bvh).pixels);
}

TEST_CASE("--accel auto keeps the flat list for tiny scenes", "[bvh]") {
    const PackedScene tiny = pack_scene(triangle_soup(10, 1));
    REQUIRE(tiny.features & T0_FEATURE_FLAT);
    REQUIRE(tiny.nodes.empty());
    const PackedScene big = pack_scene(triangle_soup(5000, 1));
    REQUIRE(big.features & T0_FEATURE_BVH);
}
