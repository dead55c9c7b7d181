// The guides beside an image (kernel/guides.h): the first surface's depth,
// and the albedo and shading normal of the first surface that is not a
// mirror or glass.
#include "test_support.h"

#include "trac0r/camera.h"
#include "trac0r/filter.h"
#include "trac0r/guides.h"
#include "trac0r/kernel/guides.h"
#include "trac0r/kernel/lamp_edge.h"
#include "trac0r/packed_scene.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

using namespace trac0r;

namespace {

const float half_pi = 1.5707963f;

Material diffuse(const char* name, glm::vec3 colour) {
    Material m;
    m.name = name;
    m.color = colour;
    return m;
}

// A glossy material of colour (0.9, 0.8, 0.7); roughness 0 is a mirror.
Material glossy_material(float roughness) {
    Material m;
    m.name = "glossy";
    m.type = MaterialType::glossy;
    m.color = glm::vec3(0.9f, 0.8f, 0.7f);
    m.roughness = roughness;
    return m;
}

// The camera at the origin looking along +z; a plane facing it at z = 2
// (material 0) fills the view; behind the camera, at z = -3, a plane facing
// +z (material 1).
Scene facing_planes(const Material& front, const Material& behind) {
    Scene scene;
    scene.materials = {front, behind};
    // A plane's normal is local +y: turned by -pi/2 about x it is -z.
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(-half_pi, 0.0f, 0.0f),
                                      glm::vec2(100.0f), 0));
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(half_pi, 0.0f, 0.0f),
                                      glm::vec2(100.0f), 1));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.direction = glm::vec3(0.0f, 0.0f, 1.0f);
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = 16;
    scene.render.height = 12;
    return scene;
}

GuideImages guides_of(const Scene& scene) {
    return render_guides(pack_scene(scene),
                         make_camera_record(scene.camera, scene.render.width, scene.render.height));
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    return glm::length(a - b) <= tolerance;
}

// Every pixel's guides are these.
void require_every_pixel(const GuideImages& g, float depth, const glm::vec3& albedo,
                         const glm::vec3& normal) {
    REQUIRE(g.depth.size() == static_cast<std::size_t>(g.width) * g.height);
    for (std::size_t i = 0; i < g.depth.size(); ++i) {
        CAPTURE(i);
        CHECK(std::fabs(g.depth[i] - depth) < 1e-5f);
        CHECK(near(g.albedo[i], albedo));
        CHECK(near(g.normal[i], normal));
    }
}

// facing_planes (white in front, green behind) with a lamp material
// (index 2) for a plane in front of them.
Scene planes_and_lamp_material(const glm::vec3& lamp_colour) {
    Scene scene =
        facing_planes(diffuse("white", glm::vec3(0.5f)), diffuse("green", glm::vec3(1.0f)));
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = lamp_colour;
    lamp.emittance = 8.0f;
    scene.materials.push_back(lamp);
    return scene;
}

// The width of a pixel of facing_planes' 16 x 12 view at depth 1.9.
const float pixel_at_lamp = 2.0f * 1.9f * std::tan(glm::radians(30.0f)) * (16.0f / 12.0f) / 16.0f;

// planes_and_lamp_material with a lamp facing the camera at z = 1.9 over
// the left of the view, its right edge a quarter into pixel column 8 (the
// camera looks along +z, so image right is -x; column 8 starts at x = 0).
Scene planes_and_lamp_edge(const glm::vec3& lamp_colour) {
    Scene scene = planes_and_lamp_material(lamp_colour);
    scene.shapes.push_back(make_plane(glm::vec3(50.0f - 0.25f * pixel_at_lamp, 0.0f, 1.9f),
                                      glm::vec3(-half_pi, 0.0f, 0.0f), glm::vec2(100.0f), 2));
    return scene;
}

// Every image and field of two GuideImages equal, bit for bit.
void check_same_guides(const GuideImages& a, const GuideImages& b) {
    CHECK(a.width == b.width);
    CHECK(a.height == b.height);
    CHECK(a.albedo == b.albedo);
    CHECK(a.normal == b.normal);
    CHECK(a.depth == b.depth);
    CHECK(a.emitter == b.emitter);
    CHECK(a.emission == b.emission);
    CHECK(a.lamp_edges == b.lamp_edges);
    CHECK(a.lamp_edge_pixels == b.lamp_edge_pixels);
    CHECK(a.lamp_edge_traced == b.lamp_edge_traced);
    CHECK(a.lamp_edge_straight == b.lamp_edge_straight);
}

// A lamp turned 20 degrees about the view axis, one of its corners in the
// middle of the view: slanted edges, and a corner; 48 x 36.
Scene slanted_lamp() {
    Scene scene = planes_and_lamp_material(glm::vec3(1.0f));
    // The plane's quad is local xz (normal +y): -pi/2 about x faces it to
    // -z, and -20 degrees about y then turns it 20 degrees about the view
    // axis (rotations apply z, y, x, in the shape's frame). Its centre is
    // half its diagonal off the axis, so a corner is near the view's
    // centre; 0.6 m across, it lies inside the view (1.9 tan 30 = 1.1 m
    // up, 1.46 m across from the axis).
    const float turn = glm::radians(20.0f);
    const float side = 0.6f;
    scene.shapes.push_back(
        make_plane(glm::vec3(0.1f + 0.5f * side * (std::cos(turn) - std::sin(turn)),
                             0.05f + 0.5f * side * (std::sin(turn) + std::cos(turn)), 1.9f),
                   glm::vec3(-half_pi, -turn, 0.0f), glm::vec2(side), 2));
    scene.render.width = 48;
    scene.render.height = 36;
    return scene;
}

}  // namespace

TEST_CASE("guides of a diffuse surface: its depth, albedo and normal", "[guides]") {
    const glm::vec3 blue(0.2f, 0.4f, 0.6f);
    const GuideImages g =
        guides_of(facing_planes(diffuse("blue", blue), diffuse("green", glm::vec3(0, 1, 0))));
    REQUIRE(g.width == 16);
    REQUIRE(g.height == 12);
    // Depth along the camera's axis: the plane's distance at every pixel.
    require_every_pixel(g, 2.0f, blue, glm::vec3(0.0f, 0.0f, -1.0f));
}

TEST_CASE("guides go on through a mirror and glass to the surface they show", "[guides]") {
    const glm::vec3 green(0.1f, 0.7f, 0.2f);
    SECTION("a mirror: the first hit's depth, the wall behind the camera, tinted") {
        const Material mirror = glossy_material(0.0f);
        const GuideImages g = guides_of(facing_planes(mirror, diffuse("green", green)));
        // The normal faces the reflected ray.
        require_every_pixel(g, 2.0f, mirror.color * green, glm::vec3(0.0f, 0.0f, 1.0f));
    }
    SECTION("a rough glossy surface is a surface") {
        const Material glossy = glossy_material(0.3f);
        const GuideImages g = guides_of(facing_planes(glossy, diffuse("green", green)));
        CHECK(near(g.albedo[0], glossy.color));
    }
    SECTION("glass: refracted through to what lies beyond") {
        // A glass box 0.5 deep at z = 1 in front of the blue plane at z = 2:
        // through it, the plane, tinted twice (in and out).
        Scene scene =
            facing_planes(diffuse("blue", glm::vec3(0.2f, 0.4f, 0.6f)), diffuse("green", green));
        Material glass;
        glass.name = "glass";
        glass.type = MaterialType::glass;
        glass.color = glm::vec3(0.9f, 0.95f, 1.0f);
        scene.materials.push_back(glass);
        scene.shapes.push_back(make_box(glm::vec3(0.0f, 0.0f, 1.25f), glm::vec3(0.0f),
                                        glm::vec3(100.0f, 100.0f, 0.5f), 2));
        const GuideImages g = guides_of(scene);
        const std::size_t centre = 6 * 16 + 8;
        CHECK(std::fabs(g.depth[centre] - 1.0f) < 1e-5f);
        CHECK(near(g.albedo[centre], glass.color * glass.color * glm::vec3(0.2f, 0.4f, 0.6f)));
        CHECK(near(g.normal[centre], glm::vec3(0.0f, 0.0f, -1.0f)));
    }
}

TEST_CASE("guides where the ray meets nothing: infinite depth, zero albedo and normal",
          "[guides]") {
    Scene scene =
        facing_planes(diffuse("blue", glm::vec3(0.5f)), diffuse("green", glm::vec3(1.0f)));
    scene.shapes.pop_back();
    scene.camera.direction = glm::vec3(0.0f, 0.0f, -1.0f);  // away from the one plane left
    const GuideImages g = guides_of(scene);
    for (std::size_t i = 0; i < g.depth.size(); ++i) {
        CHECK(std::isinf(g.depth[i]));
        CHECK(g.albedo[i] == glm::vec3(0.0f));
        CHECK(g.normal[i] == glm::vec3(0.0f));
    }
}

TEST_CASE("a pixel's variance layer is the variance of its mean", "[guides]") {
    std::vector<kernel::AccumPixel> accumulator(3);
    accumulator[0].moments = glm::vec4(0.5f, 2.0f, 5.0f, 0.0f);  // M2 2 over 5 samples
    accumulator[1].moments = glm::vec4(0.5f, 0.0f, 1.0f, 0.0f);  // one sample: unknown
    accumulator[2].moments = glm::vec4(0.0f, 0.0f, 0.0f, 0.0f);
    const std::vector<float> v = mean_variance(accumulator);
    CHECK(v[0] == Approx(2.0 / 4.0 / 5.0));
    CHECK(std::isinf(v[1]));
    CHECK(std::isinf(v[2]));
}

TEST_CASE("along a lamp's edge, the share of each pixel that sees the lamp", "[guides]") {
    const Scene scene = planes_and_lamp_edge(glm::vec3(1.0f, 0.5f, 0.25f));
    const Material& lamp = scene.materials[2];
    const GuideImages g = guides_of(scene);
    CHECK(g.lamp_edges);
    const glm::vec3 radiance = lamp.color * lamp.emittance;
    for (int y = 0; y < 12; ++y) {
        CAPTURE(y);
        for (int x = 0; x < 16; ++x) {
            CAPTURE(x);
            const glm::vec4 e = g.emission[static_cast<std::size_t>(y) * 16 + x];
            // All lamp left of the edge, a quarter on it, none right of it.
            const float share = x < 8 ? 1.0f : (x == 8 ? 0.25f : 0.0f);
            CHECK(std::fabs(e.w - share) < 0.01f);
            CHECK(near(glm::vec3(e), radiance * e.w, 1e-4f));
            CHECK((g.emitter[static_cast<std::size_t>(y) * 16 + x] != 0) == (x < 8));
        }
    }
}

TEST_CASE("surface guides are the centre rays' alone; the lamp-edge split comes after",
          "[guides]") {
    const Scene scene = planes_and_lamp_edge(glm::vec3(1.0f));
    const PackedScene packed = pack_scene(scene);
    const kernel::CameraRecord camera = make_camera_record(scene.camera, 16, 12);
    GuideImages surface = render_surface_guides(packed, camera);
    CHECK_FALSE(surface.lamp_edges);
    for (std::size_t i = 0; i < surface.albedo.size(); ++i) {
        CAPTURE(i);
        // The centre ray's: all lamp or none, even in column 8.
        CHECK(surface.emission[i].w == (surface.emitter[i] ? 1.0f : 0.0f));
    }
    CHECK(surface.emission[8].w == 0.0f);  // row 0, column 8: a quarter lamp
    // The filter refuses guides without the split: it would take the
    // lamp's quarter of column 8 for noisy lighting.
    CHECK_THROWS_WITH(filter_guides(surface), Catch::Contains("lamp-edge split"));

    // Added afterwards, the split gives column 8 its quarter.
    add_lamp_edges(packed, camera, &surface);
    CHECK(surface.lamp_edges);
    CHECK(std::fabs(surface.emission[8].w - 0.25f) < 0.01f);
    // Guides of another size are refused, naming the function.
    GuideImages other = render_surface_guides(packed, make_camera_record(scene.camera, 8, 6));
    CHECK_THROWS_WITH(add_lamp_edges(packed, camera, &other),
                      Catch::Contains("add_lamp_edges") && Catch::Contains("size"));
}

TEST_CASE("surface guides made into kept guides are a new view's, split and all", "[guides]") {
    const Scene scene = planes_and_lamp_edge(glm::vec3(1.0f));
    const PackedScene packed = pack_scene(scene);
    const kernel::CameraRecord camera = make_camera_record(scene.camera, 16, 12);
    Camera moved = scene.camera;
    moved.position.x += 0.3f * pixel_at_lamp;
    const kernel::CameraRecord other_view = make_camera_record(moved, 16, 12);
    // Kept guides of one view, split, then made again for another view of
    // the same size, of a smaller and of a larger size: each time as new
    // ones are, without the split until it is added again.
    GuideImages kept = render_guides(packed, camera);
    REQUIRE(kept.lamp_edge_traced > 0);
    // Never larger than the first: the same storage throughout.
    const glm::vec3* const albedo = kept.albedo.data();
    const glm::vec4* const emission = kept.emission.data();
    for (const kernel::CameraRecord& view :
         {other_view, make_camera_record(scene.camera, 8, 6), camera}) {
        render_surface_guides(packed, view, &kept);
        CHECK(kept.albedo.data() == albedo);
        CHECK(kept.emission.data() == emission);
        check_same_guides(kept, render_surface_guides(packed, view));
        CHECK_FALSE(kept.lamp_edges);
        add_lamp_edges(packed, view, &kept);
        check_same_guides(kept, render_guides(packed, view));
    }
}

TEST_CASE("guides made by tiles are each ray's traced alone, bit for bit", "[guides][bundle]") {
    // render_surface_guides finds a tile's first hits among the BVH leaves
    // its centre rays share (kernel/bundle.h), and add_lamp_edges a pixel's
    // among those its rays share; each pixel's guides must be those of its
    // rays traced alone (guide_ray, through the tree).
    // Odd sizes: tiles cut off at the right and bottom; the glass and
    // mirror of cornell.json, the mesh of mesh_demo.json.
    std::vector<std::pair<const char*, Scene>> scenes;
    for (const char* name : {"cornell.json", "cornell_diffuse.json", "mesh_demo.json"}) {
        scenes.push_back({name, load_test_scene(name, 1, 1)});
    }
    scenes.push_back({"a slanted lamp", slanted_lamp()});
    for (const auto& named : scenes) {
        CAPTURE(named.first);
        const Scene& scene = named.second;
        PackOptions options;
        options.accel = Accel::bvh;
        const PackedScene packed = pack_scene(scene, options);
        const kernel::SceneView view = packed.view();
        REQUIRE(T0_HAS_FEATURE(&view, T0_FEATURE_BVH));
        const kernel::CameraRecord camera = make_camera_record(scene.camera, 157, 121);
        const GuideImages g = render_surface_guides(packed, camera);
        const kernel::CameraRecord scaled = scaled_camera(camera, packed.scale);
        int surfaces = 0;
        for (std::uint32_t y = 0; y < 121; ++y) {
            for (std::uint32_t x = 0; x < 157; ++x) {
                CAPTURE(x, y);
                glm::vec3 emitted;
                const kernel::GuidePixel p =
                    kernel::guide_ray(&view, scaled, x, y, 0.5f, 0.5f, &emitted);
                const std::size_t i = y * 157u + x;
                REQUIRE(g.albedo[i] == glm::vec3(p.albedo));
                REQUIRE(g.normal[i] == glm::vec3(p.normal));
                REQUIRE(g.emission[i] == glm::vec4(emitted, p.normal.w > 0.0f ? 1.0f : 0.0f));
                const float depth = p.albedo.w >= T0_NO_HIT ? std::numeric_limits<float>::infinity()
                                                            : p.albedo.w / packed.scale;
                REQUIRE(bits_of(g.depth[i]) == bits_of(depth));
                surfaces += p.normal.w == 0.0f && glm::length(glm::vec3(p.normal)) > 0.0f;
            }
        }
        // A third of the pixels or more show a surface (cornell_diffuse.json's
        // box fills 38 % of the view), so the comparison means something.
        CHECK(surfaces > 157 * 121 / 3);
        // The lamp-edge split traces its rays over a pixel likewise (below:
        // each pixel it measured holds the value of its rays traced alone).
        GuideImages split = g;
        add_lamp_edges(packed, camera, &split);
        REQUIRE(split.lamp_edge_traced > 0);
        // The pixels it tested: those whose centre rays and their eight
        // neighbours' do not all agree on lamp or not.
        int candidates = 0;
        for (int y = 0; y < 121; ++y) {
            for (int x = 0; x < 157; ++x) {
                int lamps = 0;
                int others = 0;
                for (int qy = std::max(y - 1, 0); qy <= std::min(y + 1, 120); ++qy) {
                    for (int qx = std::max(x - 1, 0); qx <= std::min(x + 1, 156); ++qx) {
                        (g.emitter[static_cast<std::size_t>(qy) * 157 + qx] ? lamps : others)++;
                    }
                }
                candidates += lamps > 0 && others > 0 ? 1 : 0;
            }
        }
        CHECK(split.lamp_edge_pixels == candidates);
        // Where one straight edge crosses it, from the line through its
        // crossings (straight_edge_emission); else from the full count.
        int changed = 0;
        for (std::uint32_t y = 0; y < 121; ++y) {
            for (std::uint32_t x = 0; x < 157; ++x) {
                const std::size_t i = y * 157u + x;
                if (split.emission[i] != g.emission[i]) {
                    CAPTURE(x, y);
                    glm::vec4 straight;
                    const int corners = kernel::pixel_corner_lamps(&view, scaled, x, y);
                    const bool centre = g.emitter[i] != 0;
                    if (corners != (centre ? 15 : 0) &&
                        kernel::straight_edge_emission(&view, scaled, x, y, corners, centre,
                                                       &straight)) {
                        REQUIRE(split.emission[i] == straight);
                    } else {
                        REQUIRE(
                            split.emission[i] ==
                            kernel::pixel_emission(&view, scaled, x, y, T0_GUIDE_EMISSION_RAYS));
                    }
                    ++changed;
                }
            }
        }
        CHECK(changed > split.lamp_edge_traced / 2);
    }
}

TEST_CASE("the lamp-edge split skips only pixels that no edge crosses", "[guides]") {
    // With the flat list and with the BVH (whose rays over a pixel find
    // their first hits together).
    const Scene scene = slanted_lamp();
    PackOptions options;
    options.accel = GENERATE(Accel::flat, Accel::bvh);
    CAPTURE(static_cast<int>(options.accel));
    const PackedScene packed = pack_scene(scene, options);
    const kernel::CameraRecord camera = make_camera_record(scene.camera, 48, 36);
    const GuideImages g = render_guides(packed, camera);
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord scaled = scaled_camera(camera, packed.scale);
    int crossed = 0;
    int lamp_pixels = 0;
    for (int y = 0; y < 36; ++y) {
        for (int x = 0; x < 48; ++x) {
            CAPTURE(x, y);
            const std::size_t i = static_cast<std::size_t>(y) * 48 + x;
            lamp_pixels += g.emitter[i];
            // Every pixel by the full count of rays, as if no pixel were
            // skipped: the split agrees to within one ray in 16 (a sliver
            // the probes can miss), and where an edge crosses, to what
            // the full count places the edge to (about 1 %; the straight
            // edges' own error is far less: the next test).
            const glm::vec4 all =
                kernel::pixel_emission(&view, scaled, static_cast<std::uint32_t>(x),
                                       static_cast<std::uint32_t>(y), T0_GUIDE_EMISSION_RAYS);
            const glm::vec4 split = g.emission[i];
            CHECK(std::fabs(all.w - split.w) < 1.0f / 16.0f);
            if (all.w > 1.0f / 16.0f && all.w < 15.0f / 16.0f) {
                ++crossed;
                CHECK(std::fabs(all.w - split.w) < 0.02f);
            }
        }
    }
    // The scene is as meant: a lamp in view, and edges across pixels.
    CHECK(lamp_pixels > 50);
    CHECK(crossed > 20);
    // And the skip is taken: every crossed pixel is measured (by its
    // straight edge or the full count), and of the pixels by an edge about
    // half are not (50 of 98 here; without the skip, all 98).
    CAPTURE(g.lamp_edge_pixels, g.lamp_edge_traced, crossed);
    CHECK(g.lamp_edge_traced >= crossed);
    CHECK(4 * g.lamp_edge_traced < 3 * g.lamp_edge_pixels);
}

namespace {

// The area of the convex polygon `poly` (image coordinates) inside the
// square [x, x + 1] x [y, y + 1]: Sutherland and Hodgman's clipping by
// each of its sides, then the shoelace formula.
double clipped_area(std::vector<glm::dvec2> poly, double x, double y) {
    const auto clip = [&](int axis, double bound, bool keep_below) {
        std::vector<glm::dvec2> out;
        for (std::size_t k = 0; k < poly.size(); ++k) {
            const glm::dvec2 a = poly[k];
            const glm::dvec2 b = poly[(k + 1) % poly.size()];
            const bool a_in = keep_below ? a[axis] <= bound : a[axis] >= bound;
            const bool b_in = keep_below ? b[axis] <= bound : b[axis] >= bound;
            if (a_in) {
                out.push_back(a);
            }
            if (a_in != b_in) {
                const double t = (bound - a[axis]) / (b[axis] - a[axis]);
                out.push_back(a + (b - a) * t);
            }
        }
        poly = out;
    };
    clip(0, x, false);
    clip(0, x + 1.0, true);
    clip(1, y, false);
    clip(1, y + 1.0, true);
    double twice = 0.0;
    for (std::size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec2 a = poly[k];
        const glm::dvec2 b = poly[(k + 1) % poly.size()];
        twice += a.x * b.y - b.x * a.y;
    }
    return 0.5 * std::fabs(twice);
}

}  // namespace

TEST_CASE("where a lamp's straight edge crosses a pixel, its share is the area on its side",
          "[guides]") {
    // slanted_lamp's quad, projected into the image: its outline is a
    // quadrilateral, and each pixel's exact share of it the area of their
    // intersection. The split's share: within 2e-3 where only the quad's
    // edges cross the pixel (bisection places each crossing to 2^-11 of a
    // side; the rest is float rounding of the rays), and within 0.02 (the
    // full count's 1 %, twice) in the pixels that hold one of its corners.
    const Scene scene = slanted_lamp();
    const int width = 48;
    const int height = 36;
    const PackedScene packed = pack_scene(scene);
    const kernel::CameraRecord camera = make_camera_record(scene.camera, width, height);
    const GuideImages g = render_guides(packed, camera);
    const Material& lamp = scene.materials[2];
    const glm::vec3 radiance = lamp.color * lamp.emittance;
    // The quad's corners in image coordinates (pixels, y down), in order
    // round its centre.
    std::vector<glm::vec3> corners;
    for (const Triangle& t : scene.shapes[2].triangles) {
        for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
            bool seen = false;
            for (const glm::vec3& c : corners) {
                seen = seen || glm::length(c - v) < 1e-5f;
            }
            if (!seen) {
                corners.push_back(v);
            }
        }
    }
    REQUIRE(corners.size() == 4);
    std::vector<glm::dvec2> quad;
    for (const glm::vec3& c : corners) {
        const glm::dvec3 d = glm::dvec3(c) - glm::dvec3(glm::vec3(camera.position));
        const double z = glm::dot(d, glm::dvec3(glm::vec3(camera.forward)));
        const double sx = glm::dot(d, glm::dvec3(glm::vec3(camera.right))) / z / camera.extent.x;
        const double sy = glm::dot(d, glm::dvec3(glm::vec3(camera.up))) / z / camera.extent.y;
        quad.push_back(glm::dvec2((sx + 1.0) * 0.5 * width, (1.0 - sy) * 0.5 * height));
    }
    glm::dvec2 middle(0.0);
    for (const glm::dvec2& q : quad) {
        middle += q * 0.25;
    }
    std::sort(quad.begin(), quad.end(), [&](const glm::dvec2& a, const glm::dvec2& b) {
        return std::atan2(a.y - middle.y, a.x - middle.x) <
               std::atan2(b.y - middle.y, b.x - middle.x);
    });
    int edge_pixels = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            CAPTURE(x, y);
            const double exact = clipped_area(quad, x, y);
            // A quad corner within half a pixel: two edges may cross it.
            bool holds_corner = false;
            for (const glm::dvec2& q : quad) {
                holds_corner = holds_corner || (q.x >= x - 0.5 && q.x <= x + 1.5 &&
                                                q.y >= y - 0.5 && q.y <= y + 1.5);
            }
            const glm::vec4 e = g.emission[static_cast<std::size_t>(y) * width + x];
            const float share = e.w;
            CAPTURE(exact, share, holds_corner);
            CHECK(std::fabs(share - exact) <= (holds_corner ? 0.02 : 2e-3));
            // The lamp's light over the pixel: its radiance times the share.
            CHECK(glm::length(glm::vec3(e) - radiance * share) <= 1e-5f * glm::length(radiance));
            edge_pixels += exact > 0.02 && exact < 0.98 && !holds_corner ? 1 : 0;
        }
    }
    // Edges across many pixels, and most of them placed as straight edges.
    CAPTURE(edge_pixels, g.lamp_edge_traced, g.lamp_edge_straight);
    CHECK(edge_pixels > 30);
    CHECK(g.lamp_edge_straight >= edge_pixels * 9 / 10);
}

TEST_CASE("an edge between two lamps' light is not taken for one lamp's edge", "[guides]") {
    // Two lamps of different colours side by side above the same
    // horizontal edge, 0.3 of row 6 below its top; the line between them
    // runs down the middle of column 8. Column 7 sees one lamp's edge: a
    // straight edge, its share 0.3 and its light 0.3 of that lamp's. In
    // column 8 the rays above the edge meet two radiances, so its share
    // is not the line's but the full count's (pixel_emission).
    Scene scene = planes_and_lamp_material(glm::vec3(1.0f, 0.5f, 0.25f));
    Material other = scene.materials[2];
    other.name = "other lamp";
    other.color = glm::vec3(0.25f, 0.5f, 1.0f);
    scene.materials.push_back(other);
    const float pixel = 2.0f * 1.9f * std::tan(glm::radians(30.0f)) * (16.0f / 12.0f) / 16.0f;
    const float b = -0.5f * pixel;  // the lamps' boundary (image right is -x)
    const float e = -0.3f * pixel;  // their lower edge (row 6's top is y = 0)
    scene.shapes.push_back(make_plane(glm::vec3(50.0f + b, 50.0f + e, 1.9f),
                                      glm::vec3(-half_pi, 0.0f, 0.0f), glm::vec2(100.0f), 2));
    scene.shapes.push_back(make_plane(glm::vec3(-50.0f + b, 50.0f + e, 1.9f),
                                      glm::vec3(-half_pi, 0.0f, 0.0f), glm::vec2(100.0f), 3));
    const PackedScene packed = pack_scene(scene);
    const kernel::CameraRecord camera = make_camera_record(scene.camera, 16, 12);
    const GuideImages g = render_guides(packed, camera);
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord scaled = scaled_camera(camera, packed.scale);
    const glm::vec3 first = scene.materials[2].color * scene.materials[2].emittance;
    const std::size_t one = 6 * 16 + 7;
    const std::size_t both = 6 * 16 + 8;
    CAPTURE(g.emission[one].w, g.emission[both].w, g.lamp_edge_straight);
    CHECK(std::fabs(g.emission[one].w - 0.3f) < 2e-3f);
    CHECK(glm::length(glm::vec3(g.emission[one]) - first * g.emission[one].w) <
          1e-5f * glm::length(first));
    CHECK(g.emission[both] == kernel::pixel_emission(&view, scaled, 8, 6, T0_GUIDE_EMISSION_RAYS));
    CHECK(std::fabs(g.emission[both].w - 0.3f) < 0.02f);
    // The straight path is taken along the rest of the edge.
    CHECK(g.lamp_edge_straight >= 14);
}
