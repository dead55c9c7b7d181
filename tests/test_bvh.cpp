// The BVH: a valid tree over every triangle, and traversal that finds
// exactly what testing every triangle finds.
#include <catch2/catch.hpp>

#include "trac0r/bvh.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/camera.h"
#include "trac0r/kernel/bundle.h"
#include "trac0r/kernel/tile_grid.h"
#include "trac0r/kernel/trace.h"
#include "trac0r/kernel/traverse.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
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

// A scene the optimal collapse makes too deep: `levels` clusters of 32
// small triangles, each a quarter the size of the one before and beside
// the rest of the scene, which lies in the corner at the origin. The SAH
// splits a cluster from the rest at each level, and the cluster's subtree
// is larger than the rest, so the collapse spends a wide node's lanes on
// the cluster and goes down the spine one binary level per node (its depth
// is levels + 1). At 24 levels the smallest clusters are 1e-14
// of the scene, far below the scales docs/stability.md covers: rays meet
// them only on their way to the larger ones.
Scene nested_clusters(int levels) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Shape shape;
    float s = 1.0f;
    for (int k = 0; k < levels; ++k, s *= 0.25f) {
        for (int i = 0; i < 32; ++i) {
            // Centroids in x from s/2 to s, y and z from 0 to s.
            const glm::vec3 c =
                s * glm::vec3(0.5f + 0.45f * u(rng), 0.95f * u(rng), 0.95f * u(rng));
            const float size = 0.05f * s;
            shape.triangles.emplace_back(c, c + size * glm::vec3(u(rng), u(rng), 0.0f),
                                         c + size * glm::vec3(0.0f, u(rng), u(rng)));
            shape.aabb.extend(shape.triangles.back().bounds());
        }
    }
    Scene scene;
    Material m;
    m.type = MaterialType::diffuse;
    scene.materials.push_back(m);
    scene.shapes.push_back(shape);
    return scene;
}

// Lane i of a node: its box, empty (inverted) for an unused lane.
AABB lane_box(const kernel::BvhNode& n, int i) {
    AABB box;
    box.min = glm::vec3(kernel::node_plane(&n, 0, i), kernel::node_plane(&n, 2, i),
                        kernel::node_plane(&n, 4, i));
    box.max = glm::vec3(kernel::node_plane(&n, 1, i), kernel::node_plane(&n, 3, i),
                        kernel::node_plane(&n, 5, i));
    return box;
}

bool contains(const AABB& outer, const AABB& inner) {
    return glm::all(glm::lessThanEqual(outer.min, inner.min)) &&
           glm::all(glm::greaterThanEqual(outer.max, inner.max));
}

bool contains(const AABB& box, const glm::vec3& v) {
    return glm::all(glm::lessThanEqual(box.min, v)) && glm::all(glm::greaterThanEqual(box.max, v));
}

// Checks the subtree at `node`; returns its depth in nodes and counts leaf
// triangles.
int check_subtree(const PackedScene& p, std::uint32_t node, std::vector<int>& seen) {
    REQUIRE(node < p.nodes.size());
    const kernel::BvhNode& n = p.nodes[node];
    int used = 0;
    int depth = 1;
    for (int i = 0; i < T0_BVH_WIDTH; ++i) {
        const AABB box = lane_box(n, i);
        const std::uint32_t count = n.count[i / 4][i % 4];
        const std::uint32_t child = kernel::node_child(&n, i);
        if (box.min.x > box.max.x) {
            // Unused: inverted on every axis, so no ray enters it, and empty.
            REQUIRE(glm::all(glm::greaterThan(box.min, box.max)));
            REQUIRE(count == 0);
            continue;
        }
        ++used;
        if (count > 0) {
            // A leaf: child is T0_BVH_LEAF | a packet, whose first
            // count lanes are triangles (the same floats as their
            // records) and the rest unused (infinite area, never hit).
            REQUIRE(count <= 4);
            REQUIRE((child & T0_BVH_LEAF) != 0u);
            const std::uint32_t packet_index = child & ~T0_BVH_LEAF;
            REQUIRE(packet_index < p.packets.size());
            const kernel::TrianglePacket& packet = p.packets[packet_index];
            for (std::uint32_t lane = 0; lane < 4; ++lane) {
                if (lane >= count) {
                    REQUIRE(std::isinf(packet.area[lane]));
                    continue;
                }
                const std::uint32_t t = packet.triangle[lane];
                ++seen.at(t);
                const kernel::TriangleRecord& tri = p.triangles[t];
                REQUIRE(packet.area[lane] == tri.normal.w);
                const glm::vec3 vertices[3] = {glm::vec3(tri.v0), glm::vec3(tri.v1),
                                               glm::vec3(tri.v2)};
                for (int k = 0; k < 3; ++k) {
                    REQUIRE(glm::vec3(packet.vertex[3 * k][lane], packet.vertex[3 * k + 1][lane],
                                      packet.vertex[3 * k + 2][lane]) == vertices[k]);
                    // The boxes are built from the same floats: containment
                    // is exact.
                    REQUIRE(contains(box, vertices[k]));
                }
            }
            continue;
        }
        REQUIRE((child & T0_BVH_LEAF) == 0u);
        REQUIRE(child > node);  // children come after their parent: no cycle
        REQUIRE(child < p.nodes.size());
        const kernel::BvhNode& c = p.nodes[child];
        for (int j = 0; j < T0_BVH_WIDTH; ++j) {
            const AABB inner = lane_box(c, j);
            REQUIRE((inner.min.x > inner.max.x || contains(box, inner)));
        }
        depth = std::max(depth, 1 + check_subtree(p, child, seen));
    }
    // Only a tree that is one leaf has a node with a single child.
    REQUIRE((used >= 2 || (node == 0 && n.count[0][0] > 0)));
    return depth;
}

void check_tree(const PackedScene& p) {
    std::vector<int> seen(p.triangles.size(), 0);
    const int depth = check_subtree(p, 0, seen);
    REQUIRE(depth == p.bvh_depth);
    // Every triangle is in exactly one leaf.
    REQUIRE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

// Checks a Bvh as build_bvh returns it: every triangle in exactly one
// leaf, leaves of 1 to max_leaf triangles, and a depth the traversal
// stack holds.
void check_leaves(const Bvh& bvh, std::size_t triangles, int max_leaf) {
    REQUIRE(bvh.order.size() == triangles);
    std::vector<int> seen(triangles, 0);
    for (const BvhLeaf& leaf : bvh.leaves) {
        REQUIRE(leaf.count >= 1);
        REQUIRE(leaf.count <= static_cast<std::uint32_t>(max_leaf));
        for (std::uint32_t k = 0; k < leaf.count; ++k) {
            ++seen.at(bvh.order.at(leaf.first + k));
        }
    }
    REQUIRE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    REQUIRE(7 * bvh.depth + 1 <= T0_BVH_STACK_SIZE);
}

PackOptions with(Accel accel) {
    PackOptions o;
    o.accel = accel;
    return o;
}

// Traces `rays` through the BVH and the flat list of `scene`: the same
// nearest hits and shadow-ray answers. Returns how many rays hit.
int same_hits(const Scene& scene, const std::vector<kernel::Ray>& rays) {
    const PackedScene bvh = pack_scene(scene, with(Accel::bvh));
    const PackedScene flat = pack_scene(scene, with(Accel::flat));
    const kernel::SceneView bvh_view = bvh.view();
    const kernel::SceneView flat_view = flat.view();
    int hits = 0;
    for (const kernel::Ray& ray : rays) {
        const kernel::Hit a = kernel::traverse_bvh(&bvh_view, &ray, T0_NO_HIT, 0);
        const kernel::Hit b = kernel::traverse_flat(&flat_view, &ray, T0_NO_HIT, 0);
        REQUIRE((a.triangle >= 0) == (b.triangle >= 0));
        if (a.triangle >= 0) {
            ++hits;
            // The same triangle test on the same data: the same distance,
            // barycentrics and triangle (indices differ between layouts).
            REQUIRE(a.t == b.t);
            REQUIRE(a.u == b.u);
            REQUIRE(a.v == b.v);
            const kernel::TriangleRecord& ta = bvh.triangles[static_cast<std::size_t>(a.triangle)];
            const kernel::TriangleRecord& tb = flat.triangles[static_cast<std::size_t>(b.triangle)];
            REQUIRE(glm::vec3(ta.v0) == glm::vec3(tb.v0));
            REQUIRE(glm::vec3(ta.v1) == glm::vec3(tb.v1));
            REQUIRE(glm::vec3(ta.v2) == glm::vec3(tb.v2));
        }
        // Shadow rays: any hit below a limit, the same answer both ways.
        const float limit = 0.5f;
        REQUIRE(kernel::occluded(&bvh_view, &ray, limit) ==
                kernel::occluded(&flat_view, &ray, limit));
        REQUIRE(kernel::occluded(&bvh_view, &ray, limit) == (b.triangle >= 0 && b.t < limit));
        // The GPU's walk (T0_LANE_TRAVERSAL) visits what the CPU's does, in
        // the same order: the same hit, bit for bit, the nearest and the
        // first below a limit.
        for (const float t_max : {T0_NO_HIT, limit}) {
            for (const int any_hit : {0, 1}) {
                const kernel::Hit s = kernel::traverse_bvh_sorted(&bvh_view, &ray, t_max, any_hit);
                const kernel::Hit g = kernel::traverse_bvh_groups(&bvh_view, &ray, t_max, any_hit);
                CAPTURE(t_max, any_hit, s.t, g.t);
                REQUIRE(s.triangle == g.triangle);
                REQUIRE(bits_of(s.t) == bits_of(g.t));
                REQUIRE(bits_of(s.u) == bits_of(g.u));
                REQUIRE(bits_of(s.v) == bits_of(g.v));
            }
        }
    }
    return hits;
}

// What bundled_camera_hits saw: tiles whose camera rays shared their
// leaves, tiles whose rays traversed the tree, and rays that hit.
struct BundleCounts {
    int bundled_tiles = 0;
    int traversed_tiles = 0;
    int hits = 0;
};

// Every camera ray of a width x height image of `scene`, made as
// render_tile makes them (begin_pixel, frame 3), bundled by 8 x 8 tile as
// render_tile bundles them: among its tile's leaves (camera_hit) it finds
// the nearest hit that traverse_bvh finds, bit for bit.
BundleCounts bundled_camera_hits(const Scene& scene, int width, int height) {
    const PackedScene packed = pack_scene(scene, with(Accel::bvh));
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord camera =
        scaled_camera(make_camera_record(scene.camera, width, height), packed.scale);
    BundleCounts counts;
    const std::uint32_t w = static_cast<std::uint32_t>(width);
    const std::uint32_t h = static_cast<std::uint32_t>(height);
    for (std::uint32_t t = 0; t < kernel::tile_count(w, h); ++t) {
        const kernel::TileRect tile = kernel::tile_rect(t, w, h);
        std::vector<kernel::PixelSample> samples;
        kernel::RayBundle bundle;
        kernel::bundle_start(&bundle, glm::vec3(camera.position));
        for (std::uint32_t y = tile.y0; y < tile.y1; ++y) {
            for (std::uint32_t x = tile.x0; x < tile.x1; ++x) {
                kernel::PixelSample s;
                kernel::begin_pixel(&view, camera, y * w + x, 7, 3, &s);
                if (!s.ray.any_parallel) {
                    kernel::bundle_add(&bundle, s.ray.inv_direction);
                }
                samples.push_back(s);
            }
        }
        kernel::LeafCandidate leaves[T0_BUNDLE_LEAVES];
        const int count = kernel::bundle_finish_leaves(&view, &bundle, leaves);
        (count >= 0 ? counts.bundled_tiles : counts.traversed_tiles) += 1;
        for (const kernel::PixelSample& s : samples) {
            const kernel::Hit a = kernel::camera_hit(&view, &s.ray, leaves, count);
            const kernel::Hit b = kernel::traverse_bvh(&view, &s.ray, T0_NO_HIT, 0);
            CAPTURE(tile.x0, tile.y0, count, b.t, s.ray.direction.x, s.ray.direction.y,
                    s.ray.direction.z);
            REQUIRE(a.triangle == b.triangle);
            REQUIRE(bits_of(a.t) == bits_of(b.t));
            REQUIRE(bits_of(a.u) == bits_of(b.u));
            REQUIRE(bits_of(a.v) == bits_of(b.v));
            counts.hits += b.triangle >= 0 ? 1 : 0;
        }
    }
    return counts;
}

}  // namespace

TEST_CASE("a tile's camera rays find their nearest hits among the leaves they share",
          "[bvh][bundle]") {
    // Odd sizes: tiles cut off at the right and bottom. The repository's
    // scenes, then the Cornell box from views where tiles' rays have
    // directions of both signs along two axes (the image's centre on an
    // axis), along none (a diagonal view from a corner, a wide lens), and
    // from inside the glass sphere.
    struct View {
        const char* what;
        Scene scene;
    };
    std::vector<View> views;
    for (const char* name : {"cornell.json", "cornell_diffuse.json", "mesh_demo.json"}) {
        views.push_back({name, load_test_scene(name, 1, 1)});
    }
    Scene corner = builtin_scene();
    corner.camera.position = glm::vec3(0.45f, 0.8f, -0.45f);
    corner.camera.direction = glm::vec3(-1.0f, -0.7f, 1.1f);
    corner.camera.vertical_fov = 120.0f;
    views.push_back({"from a corner, 120 degrees", corner});
    Scene inside = builtin_scene();
    inside.camera.position = glm::vec3(0.0f, 0.1f, -0.3f);  // the glass sphere's centre
    inside.camera.direction = glm::vec3(0.3f, 1.0f, 0.2f);
    views.push_back({"inside the glass sphere", inside});
    for (const View& v : views) {
        CAPTURE(v.what);
        const BundleCounts counts = bundled_camera_hits(v.scene, 157, 121);
        CAPTURE(counts.bundled_tiles, counts.traversed_tiles, counts.hits);
        // Most tiles share their leaves (at 157 x 121 a tile of the wide
        // lens spans 8 degrees, and one in ten meets too many), and most
        // rays meet something.
        REQUIRE(counts.bundled_tiles > 5 * counts.traversed_tiles);
        REQUIRE(counts.hits > 157 * 121 / 3);
    }
}

TEST_CASE("tiles whose camera rays meet more leaves than a bundle holds traverse the tree",
          "[bvh][bundle]") {
    const BundleCounts counts = bundled_camera_hits(cornell_with_dense_sphere(), 96, 72);
    CAPTURE(counts.bundled_tiles, counts.traversed_tiles);
    REQUIRE(counts.traversed_tiles > 0);
    REQUIRE(counts.bundled_tiles > 0);
}

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

TEST_CASE("the collapse packs each small cluster into one packet", "[bvh]") {
    // Eight clusters of four tiny triangles, far apart: the binary tree is
    // split down to single triangles, and the cheapest wide tree is one
    // node whose eight lanes are the clusters, each one packet (four
    // single-triangle lanes would test the same box four times).
    std::vector<AABB> bounds;
    for (int cluster = 0; cluster < 8; ++cluster) {
        const glm::vec3 corner(static_cast<float>(cluster % 2), static_cast<float>(cluster / 2 % 2),
                               static_cast<float>(cluster / 4));
        for (int i = 0; i < 4; ++i) {
            AABB b;
            b.extend(10.0f * corner + glm::vec3(0.01f * static_cast<float>(i)));
            b.extend(10.0f * corner + glm::vec3(0.01f * static_cast<float>(i) + 0.05f));
            bounds.push_back(b);
        }
    }
    const Bvh bvh = build_bvh(bounds);
    REQUIRE(bvh.nodes.size() == 1);
    REQUIRE(bvh.depth == 1);
    REQUIRE(bvh.leaves.size() == 8);
    for (const BvhLeaf& leaf : bvh.leaves) {
        REQUIRE(leaf.count == 4);
        // A cluster's four triangles, whichever the order.
        const std::uint32_t cluster = bvh.order[leaf.first] / 4;
        for (std::uint32_t k = 0; k < 4; ++k) {
            REQUIRE(bvh.order[leaf.first + k] / 4 == cluster);
        }
    }
    // With leaves of at most two or three, each cluster takes two lanes
    // (16 in all, so more than one node); of one, four.
    for (int max_leaf : {1, 2, 3}) {
        CAPTURE(max_leaf);
        const Bvh small = build_bvh(bounds, max_leaf);
        check_leaves(small, bounds.size(), max_leaf);
        REQUIRE(small.leaves.size() == (max_leaf == 1 ? 32u : 16u));
        REQUIRE(small.nodes.size() > 1);
    }
}

TEST_CASE("a BVH over boxes without area stays shallow", "[bvh]") {
    // Degenerate triangles' boxes: points scattered in a cube, and points
    // on a line (the root's box has no area either). Their costs all tie at
    // 0 unless the collapse gives them a floor; ties take fewer lanes, so
    // without it every node had two lanes and the tree was as deep as the
    // binary one (12 levels for 4,096 points, against 4 to 5).
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int line = 0; line < 2; ++line) {
        CAPTURE(line);
        std::vector<AABB> bounds;
        for (int i = 0; i < 4096; ++i) {
            const glm::vec3 p =
                line ? glm::vec3(u(rng), 0.0f, 0.0f) : glm::vec3(u(rng), u(rng), u(rng));
            AABB b;
            b.extend(p);
            bounds.push_back(b);
        }
        const Bvh bvh = build_bvh(bounds);
        check_leaves(bvh, bounds.size(), 4);
        CAPTURE(bvh.depth);
        REQUIRE(!bvh.by_levels);
        REQUIRE(bvh.depth <= 6);
    }
}

TEST_CASE("the BVH is the same at every scale, also where float areas overflow", "[bvh]") {
    // Scaled by a power of two every float of the build scales exactly, so
    // the SAH must give the same tree; at 2^64 (1.8e19) the boxes' surface
    // areas overflow a float, and a build that takes them in float finds
    // every cost infinite (and made leaves of 150 triangles).
    std::vector<AABB> unit;
    std::vector<AABB> huge;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const float scale = 18446744073709551616.0f;  // 2^64
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        const glm::vec3 size = 0.05f * glm::abs(glm::vec3(u(rng), u(rng), u(rng)));
        AABB b;
        b.extend(c);
        b.extend(c + size);
        unit.push_back(b);
        AABB h;
        h.extend(scale * c);
        h.extend(scale * (c + size));
        huge.push_back(h);
    }
    const Bvh a = build_bvh(unit);
    const Bvh b = build_bvh(huge);
    check_leaves(a, unit.size(), 4);
    REQUIRE(b.order == a.order);
    REQUIRE(b.nodes.size() == a.nodes.size());
    REQUIRE(b.depth == a.depth);
    REQUIRE(b.leaves.size() == a.leaves.size());
    for (std::size_t i = 0; i < a.leaves.size(); ++i) {
        REQUIRE(b.leaves[i].first == a.leaves[i].first);
        REQUIRE(b.leaves[i].count == a.leaves[i].count);
    }
}

TEST_CASE("a BVH over coincident triangles stays shallow", "[bvh]") {
    // All centroids equal: no SAH split exists, the builder must halve.
    Scene scene = triangle_soup(1, 1);
    const Triangle t = scene.shapes[0].triangles[0];
    scene.shapes[0].triangles.assign(20000, t);
    const PackedScene p = pack_scene(scene, with(Accel::bvh));
    check_tree(p);
}

TEST_CASE("a BVH the optimal collapse makes too deep is collapsed by levels", "[bvh]") {
    const Scene scene = nested_clusters(24);
    const PackedScene p = pack_scene(scene, with(Accel::bvh));
    CAPTURE(p.bvh_depth);
    REQUIRE(p.bvh_by_levels);
    check_tree(p);
    REQUIRE(7 * p.bvh_depth + 1 <= T0_BVH_STACK_SIZE);
    // Twelve levels: the optimal collapse is shallow enough, and is kept.
    REQUIRE_FALSE(pack_scene(nested_clusters(12), with(Accel::bvh)).bvh_by_levels);
    // Forty levels (down to 1e-24 of the scene: build_bvh alone, the
    // packer would take such triangles for degenerate): the binary tree
    // reaches SAH depth 32 and halves below it, and the collapse by levels
    // still fits the stack.
    const Scene forty = nested_clusters(40);
    std::vector<AABB> bounds;
    for (const Triangle& t : forty.shapes[0].triangles) {
        bounds.push_back(t.bounds());
    }
    const Bvh deep = build_bvh(bounds);
    CAPTURE(deep.depth);
    REQUIRE(deep.by_levels);
    check_leaves(deep, bounds.size(), 4);
}

TEST_CASE("BVH traversal finds the same nearest hit as testing every triangle", "[bvh]") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    std::vector<kernel::Ray> rays;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 origin(u(rng), u(rng), u(rng));
        glm::vec3 direction = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        // One ray in four parallel to one or two axes: the node test's
        // per-lane path for zero direction components.
        if (i % 4 == 0) {
            direction[i % 3] = 0.0f;
            if (i % 8 == 0) {
                direction[(i + 1) % 3] = 0.0f;
            }
            if (glm::length(direction) == 0.0f) {
                direction[(i + 2) % 3] = 1.0f;
            }
            direction = glm::normalize(direction);
        }
        rays.push_back(kernel::make_ray(origin, direction));
    }
    REQUIRE(same_hits(triangle_soup(2000, 9), rays) > 1000);  // the rays do meet the soup
}

TEST_CASE("traversal of a BVH collapsed by levels finds the same hits", "[bvh]") {
    // Rays towards a point of a triangle of the eight largest clusters
    // (down to 6e-5 of the scene: the scales docs/stability.md covers),
    // from twice its distance to the corner away, through the smaller
    // clusters.
    const Scene scene = nested_clusters(24);
    const std::vector<Triangle>& triangles = scene.shapes[0].triangles;
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<kernel::Ray> rays;
    for (int i = 0; i < 20000; ++i) {
        const Triangle& t =
            triangles[static_cast<std::size_t>(i * 7919) % (32 * 8)];  // clusters 0 to 7
        const float b1 = u(rng);
        const float b2 = (1.0f - b1) * u(rng);
        const glm::vec3 target = t.v0 + b1 * (t.v1 - t.v0) + b2 * (t.v2 - t.v0);
        const glm::vec3 direction =
            glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
        rays.push_back(
            kernel::make_ray(target - 2.0f * glm::length(target) * direction, direction));
    }
    REQUIRE(same_hits(scene, rays) > 15000);
}

TEST_CASE("flat and BVH renders of the Cornell box are the same image", "[bvh][render]") {
    Scene scene = builtin_scene();
    scene.render.width = 45;  // the last column of tiles 5 pixels wide
    scene.render.height = 36;
    auto render = [&](Accel accel, Integrator integrator) {
        PackOptions options = with(accel);
        options.integrator = integrator;
        Renderer r(scene, std::make_unique<CpuBackend>(), 3, options);
        for (int i = 0; i < 4; ++i) {
            r.render_frame();
        }
        return r.image();
    };
    // Same rays, same nearest hits: bit-identical (ties between coplanar
    // triangles could differ, and the Cornell box has none in view). With
    // NEE also the same light samples: the light list is in the scene's
    // order, whatever the structure's triangle order.
    for (Integrator integrator : {Integrator::naive, Integrator::nee}) {
        CAPTURE(to_string(integrator));
        REQUIRE(render(Accel::flat, integrator).pixels == render(Accel::bvh, integrator).pixels);
    }
}

TEST_CASE("--accel auto keeps the flat list for tiny scenes", "[bvh]") {
    const PackedScene tiny = pack_scene(triangle_soup(10, 1));
    REQUIRE(tiny.features & T0_FEATURE_FLAT);
    REQUIRE(tiny.nodes.empty());
    const PackedScene big = pack_scene(triangle_soup(5000, 1));
    REQUIRE(big.features & T0_FEATURE_BVH);
}

namespace {

// A CPU backend whose crossover is elsewhere: the renderer must ask it.
class LateBvhBackend : public CpuBackend {
  public:
    std::size_t auto_bvh_min_triangles() const override { return 1000; }
};

}  // namespace

TEST_CASE("--accel auto uses the renderer's backend's threshold", "[bvh]") {
    Scene scene = triangle_soup(100, 2);
    scene.render.width = 8;
    scene.render.height = 6;
    REQUIRE(pack_scene(scene).features & T0_FEATURE_BVH);
    const Renderer cpu(scene, std::make_unique<CpuBackend>(), 1, PackOptions());
    REQUIRE(CpuBackend().auto_bvh_min_triangles() == auto_bvh_min_triangles);
    REQUIRE(cpu.packed().features & T0_FEATURE_BVH);
    const Renderer late(scene, std::make_unique<LateBvhBackend>(), 1, PackOptions());
    REQUIRE(late.packed().features & T0_FEATURE_FLAT);
    Scene few = triangle_soup(static_cast<int>(auto_bvh_min_triangles) - 1, 2);
    few.render.width = 8;
    few.render.height = 6;
    const Renderer tiny(few, std::make_unique<CpuBackend>(), 1, PackOptions());
    REQUIRE(tiny.packed().features & T0_FEATURE_FLAT);
}
