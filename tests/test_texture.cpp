// Base-colour textures (kernel/texture.h): texels made linear from sRGB,
// looked up bilinearly at the hit's texture coordinates, repeating; they
// multiply a diffuse or glossy surface's colour, on both backends.
#include "test_support.h"
#include "viewer_process.h"

#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/guides.h"
#include "trac0r/kernel/texture.h"
#include "trac0r/renderer.h"

#include <glm/glm.hpp>

#include <cmath>
#include <memory>

using namespace trac0r;

namespace {

std::uint32_t rgba(unsigned r, unsigned g, unsigned b) {
    return r | g << 8 | b << 16 | 0xff000000u;
}

float srgb_linear(unsigned c) {
    const double v = c / 255.0;
    return static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

glm::vec3 linear(std::uint32_t texel) {
    return glm::vec3(srgb_linear(texel & 255u), srgb_linear((texel >> 8) & 255u),
                     srgb_linear((texel >> 16) & 255u));
}

bool near(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) < 1e-6f; }

// A 10 x 10 floor at y = 0 (texture coordinates u = x + 0.5, v = z + 0.5)
// of `floor` colour under a lamp at y = 1, seen from above (image right
// is +x); with `texture` (if it has texels) on the floor.
Scene textured_floor(const glm::vec3& floor_colour, const Texture& texture) {
    Scene scene;
    Material floor;
    floor.name = "floor";
    floor.color = floor_colour;
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = glm::vec3(1.0f);
    lamp.emittance = 10.0f;
    if (!texture.texels.empty()) {
        floor.texture = 0;
        scene.textures.push_back(texture);
    }
    scene.materials = {floor, lamp};
    Shape plane = make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(10.0f), 0);
    for (const Triangle& t : plane.triangles) {
        TriangleUv uv;
        uv.present = true;
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k) {
            uv.uv[k] = glm::vec2(v[k].x + 0.5f, v[k].z + 0.5f);
        }
        plane.uvs.push_back(uv);
    }
    scene.shapes.push_back(plane);
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 1.0f, 0.0f),
                                      glm::vec3(3.14159265f, 0.0f, 0.0f), glm::vec2(1.0f), 1));
    scene.camera.position = glm::vec3(0.0f, 0.5f, 0.0f);
    scene.camera.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    scene.camera.world_up = glm::vec3(0.0f, 0.0f, -1.0f);  // image right: +x
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = 32;
    scene.render.height = 24;
    scene.render.max_depth = 4;
    return scene;
}

std::unique_ptr<Backend> make_backend(bool opencl) {
    if (opencl) {
        return std::make_unique<OpenClBackend>(0);
    }
    return std::make_unique<CpuBackend>();
}

// The mean colour of the columns [x0, x1) after `frames` frames.
glm::dvec3 render_columns(const Scene& scene, bool opencl, int x0, int x1, int frames = 32) {
    PackOptions options;
    options.integrator = Integrator::nee;
    Renderer r(scene, make_backend(opencl), 7, options);
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    const Image image = r.image();
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            sum += glm::dvec3(image.pixels[static_cast<std::size_t>(y) * image.width + x]);
            ++n;
        }
    }
    return sum / static_cast<double>(n);
}

// 64 x 1 texels: the left half red, the right half blue.
Texture red_blue() {
    Texture t;
    t.source = "red_blue";
    t.width = 64;
    t.height = 1;
    for (int x = 0; x < 64; ++x) {
        t.texels.push_back(x < 32 ? rgba(200, 0, 0) : rgba(0, 0, 200));
    }
    return t;
}

void require_texture_in_image(bool opencl) {
    const Scene scene = textured_floor(glm::vec3(1.0f), red_blue());
    REQUIRE((pack_scene(scene).features & T0_FEATURE_TEXTURE) != 0u);
    // The camera sees x in about +-0.29: u = x + 0.5 in [0.21, 0.79].
    const glm::dvec3 left = render_columns(scene, opencl, 0, 10);
    const glm::dvec3 right = render_columns(scene, opencl, 22, 32);
    CAPTURE(left.x, left.y, left.z, right.x, right.y, right.z);
    CHECK(left.x > 0.05);
    CHECK(left.z == 0.0);
    CHECK(left.y == 0.0);
    CHECK(right.z > 0.05);
    CHECK(right.x == 0.0);
    CHECK(std::fabs(left.x - right.z) < 0.05 * left.x);  // the same light, mirrored
    // A uniform texture of value c gives what a colour of its linear value
    // gives (the same paths, within rounding).
    Texture grey;
    grey.width = 3;
    grey.height = 2;
    grey.texels.assign(6, rgba(188, 188, 188));
    const glm::vec3 colour(0.9f, 0.6f, 0.3f);
    const glm::dvec3 textured = render_columns(textured_floor(colour, grey), opencl, 0, 32);
    const glm::dvec3 plain =
        render_columns(textured_floor(colour * srgb_linear(188), Texture()), opencl, 0, 32);
    CAPTURE(textured.x, plain.x, textured.z, plain.z);
    for (int c = 0; c < 3; ++c) {
        CHECK(std::fabs(textured[c] / plain[c] - 1.0) < 1e-3);
    }
}

}  // namespace

TEST_CASE("sRGB texels are made linear by the exact curve", "[texture]") {
    for (unsigned c = 0; c < 256; ++c) {
        CAPTURE(c);
        CHECK(std::fabs(kernel::t0_srgb_to_linear[c] - srgb_linear(c)) <= 1e-7f * srgb_linear(c));
    }
    CHECK(kernel::t0_srgb_to_linear[0] == 0.0f);
    CHECK(kernel::t0_srgb_to_linear[255] == 1.0f);
}

TEST_CASE("textures are bilinear between texel centres and repeat", "[texture]") {
    // 2 x 2: red, green on the top row; blue, white below.
    const std::uint32_t texels[4] = {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255),
                                     rgba(255, 255, 255)};
    kernel::TextureRecord t;
    t.info = glm::uvec4(0u, 2u, 2u, 0u);
    const auto at = [&](float u, float v) { return kernel::texture_bilinear(texels, t, u, v); };
    // Texel centres: v = 0.75 is the top row.
    CHECK(near(at(0.25f, 0.75f), linear(texels[0])));
    CHECK(near(at(0.75f, 0.75f), linear(texels[1])));
    CHECK(near(at(0.25f, 0.25f), linear(texels[2])));
    CHECK(near(at(0.75f, 0.25f), linear(texels[3])));
    // Halfway between two centres, and at the edge (wrapping round).
    CHECK(near(at(0.5f, 0.75f), 0.5f * (linear(texels[0]) + linear(texels[1]))));
    CHECK(near(at(0.0f, 0.75f), 0.5f * (linear(texels[0]) + linear(texels[1]))));
    CHECK(near(at(0.25f, 0.5f), 0.5f * (linear(texels[0]) + linear(texels[2]))));
    CHECK(near(at(0.5f, 0.5f), 0.25f * (linear(texels[0]) + linear(texels[1]) + linear(texels[2]) +
                                        linear(texels[3]))));
    // A quarter of the way: weights 3/4 and 1/4.
    CHECK(near(at(0.375f, 0.75f), 0.75f * linear(texels[0]) + 0.25f * linear(texels[1])));
    // Repeating, also below zero and far out.
    CHECK(near(at(1.25f, 0.75f), at(0.25f, 0.75f)));
    CHECK(near(at(-0.75f, -1.25f), at(0.25f, 0.75f)));
    CHECK(near(at(1000.25f, 0.75f), at(0.25f, 0.75f)));
    // Not finite: some texel, never outside the texture.
    const glm::vec3 nan_lookup = at(NAN, INFINITY);
    CHECK(std::isfinite(nan_lookup.x));
}

TEST_CASE("textures clamp to the edge or mirror as their wrap modes say", "[texture]") {
    // 2 x 2 as above: red, green on the top row; blue, white below.
    const std::uint32_t texels[4] = {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255),
                                     rgba(255, 255, 255)};
    const auto sampler = [&](TextureWrap u, TextureWrap v) {
        kernel::TextureRecord t;
        t.info = glm::uvec4(0u, 2u, 2u, static_cast<unsigned>(u) | static_cast<unsigned>(v) << 2);
        return [=, &texels](float x, float y) { return kernel::texture_bilinear(texels, t, x, y); };
    };
    const auto clamp = sampler(TextureWrap::clamp, TextureWrap::clamp);
    // Past an edge, and between the edge and the last centre: the edge texel
    // alone (repeat would blend in the other side's).
    CHECK(near(clamp(1.25f, 0.75f), linear(texels[1])));
    CHECK(near(clamp(0.9f, 0.75f), linear(texels[1])));
    CHECK(near(clamp(-3.0f, 0.75f), linear(texels[0])));
    CHECK(near(clamp(0.0f, 0.75f), linear(texels[0])));
    CHECK(near(clamp(0.25f, 7.0f), linear(texels[0])));  // v above 1: the top row
    CHECK(near(clamp(0.25f, -7.0f), linear(texels[2])));
    // Inside, as repeat.
    CHECK(near(clamp(0.375f, 0.75f), 0.75f * linear(texels[0]) + 0.25f * linear(texels[1])));

    const auto mirror = sampler(TextureWrap::mirror, TextureWrap::mirror);
    CHECK(near(mirror(1.25f, 0.75f), mirror(0.75f, 0.75f)));
    CHECK(near(mirror(1.25f, 0.75f), linear(texels[1])));
    CHECK(near(mirror(-0.25f, 0.75f), linear(texels[0])));
    CHECK(near(mirror(2.25f, 0.75f), linear(texels[0])));
    CHECK(near(mirror(0.25f, 1.25f), linear(texels[0])));  // v mirrored at the top
    CHECK(near(mirror(1.0f, 0.75f), linear(texels[1])));   // the edge: no blend with red

    // u and v each their own: u clamps, v repeats.
    const auto mixed = sampler(TextureWrap::clamp, TextureWrap::repeat);
    CHECK(near(mixed(1.25f, 1.75f), linear(texels[1])));
    CHECK(near(mixed(1.25f, 0.0f), 0.5f * (linear(texels[1]) + linear(texels[3]))));
    const glm::vec3 nan_lookup = mirror(NAN, -INFINITY);
    CHECK(std::isfinite(nan_lookup.x));
}

TEST_CASE("a hit's texture coordinates come from its barycentrics", "[texture]") {
    Texture checker;
    checker.width = 2;
    checker.height = 2;
    checker.texels = {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255), rgba(255, 255, 255)};
    Scene scene = textured_floor(glm::vec3(0.5f), checker);
    scene.shapes[0].triangles.resize(1);
    scene.shapes[0].uvs.resize(1);
    scene.shapes[0].uvs[0].uv = {glm::vec2(0.0f, 0.0f), glm::vec2(1.0f, 0.0f),
                                 glm::vec2(0.0f, 1.0f)};
    const PackedScene packed = pack_scene(scene);
    REQUIRE((packed.features & T0_FEATURE_TEXTURE) != 0u);
    const kernel::SceneView view = packed.view();
    kernel::Hit hit;
    hit.t = 1.0f;
    hit.u = 0.25f;  // weight of v1: u = 0.25
    hit.v = 0.75f;  // weight of v2: v = 0.75, the top row
    hit.triangle = 0;
    const std::uint32_t floor = packed.triangles[0].ids.x;
    REQUIRE(packed.materials[floor].type.y == 1u);
    CHECK(near(kernel::surface_texture(&view, &view.materials[floor], hit),
               linear(checker.texels[0])));
    // The lamp has no texture: one.
    CHECK(kernel::surface_texture(&view, &view.materials[1 - floor], hit) == glm::vec3(1.0f));
    // Without coordinates the triangle is untextured.
    scene.shapes[0].uvs[0].present = false;
    const PackedScene no_uv = pack_scene(scene);
    CHECK((no_uv.features & T0_FEATURE_TEXTURE) == 0u);
}

TEST_CASE("a texture colours the image (CPU)", "[texture]") { require_texture_in_image(false); }

TEST_CASE("a texture colours the image (OpenCL)", "[texture][opencl]") {
    require_texture_in_image(true);
}

TEST_CASE("--verbose names a mesh's texture; the feature is on", "[texture][cli]") {
    const std::string dir = std::string(TRAC0R_SOURCE_DIR) + "/scenes";
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        dir +
        "/texture_demo.json --headless --width 16 --height 12 --spp 1 "
        "--verbose --output cli_texture.pfm");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("material crate, texture " + dir +
                     "/meshes/textured_cube.png (256x256), 0 smooth\n") != std::string::npos);
    CHECK(r.err.find("texture (mask") != std::string::npos);
    std::remove("cli_texture.pfm");
}

TEST_CASE("the albedo guide is the textured colour", "[texture][guides]") {
    const Scene scene = textured_floor(glm::vec3(0.5f), red_blue());
    const GuideImages g =
        render_guides(pack_scene(scene),
                      make_camera_record(scene.camera, scene.render.width, scene.render.height));
    // Row 12, columns 2 and 29: x about -0.25 and +0.25, u 0.25 and 0.75.
    const glm::vec3 left = g.albedo[12 * 32 + 2];
    const glm::vec3 right = g.albedo[12 * 32 + 29];
    CHECK(near(left, 0.5f * linear(rgba(200, 0, 0))));
    CHECK(near(right, 0.5f * linear(rgba(0, 0, 200))));
}
