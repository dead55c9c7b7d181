// Textures beyond the base colour (kernel/normal_map.h, texture.h): a
// tangent-space normal map turns the shading normal as a tilted plane's,
// an emission texture scales what an emitter sends (seen and sampled),
// and metallic-roughness textures scale those factors; on both backends,
// and from an OBJ's MTL statements.
#include "test_support.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/renderer.h"

#include <cmath>
#include <fstream>
#include <memory>

using namespace trac0r;

namespace {

const double pi = 3.14159265358979323846;
const int side = 16;

std::uint32_t rgba(unsigned r, unsigned g, unsigned b) {
    return r | g << 8 | b << 16 | 0xff000000u;
}

// A texture of w x h texels, row by row from the top.
Texture texture_of(int w, int h, const std::vector<std::uint32_t>& texels) {
    Texture t;
    t.source = "test";
    t.width = w;
    t.height = h;
    t.texels = texels;
    return t;
}

// A 4 m floor (y = 0) of material 0 with texture coordinates u = x / 4 +
// 0.5, v = 0.5 - z / 4 (u along +x, v along -z), seen from straight above
// (image right +x, image up -z), its direct light alone (max_depth 2).
Scene floor_scene(const Material& floor) {
    Scene scene;
    scene.materials = {floor};
    Shape plane = make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(4.0f), 0);
    for (const Triangle& t : plane.triangles) {
        TriangleUv uv;
        uv.present = true;
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k) {
            uv.uv[k] = glm::vec2(v[k].x / 4.0f + 0.5f, 0.5f - v[k].z / 4.0f);
        }
        plane.uvs.push_back(uv);
    }
    scene.shapes.push_back(plane);
    scene.camera.position = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.camera.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    scene.camera.world_up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = side;
    scene.render.height = side;
    scene.render.max_depth = 2;
    return scene;
}

Lamp sun_towards(glm::vec3 towards, float irradiance) {
    Lamp sun;
    sun.type = LampType::sun;
    sun.direction = glm::normalize(towards);
    sun.power = irradiance;
    sun.angle = 0.0f;
    return sun;
}

Image render(const Scene& scene, int frames, bool opencl = false) {
    PackOptions options;
    options.integrator = Integrator::nee;
    options.sampler = SamplerKind::sobol;
    std::unique_ptr<Backend> backend;
    if (opencl) {
        backend = std::make_unique<OpenClBackend>(0);
    } else {
        backend = std::make_unique<CpuBackend>();
    }
    Renderer r(scene, std::move(backend), 7, options);
    for (int i = 0; i < frames; ++i) {
        r.render_frame();
    }
    REQUIRE(r.stats().samples_dropped == 0);
    return r.image();
}

double mean_red(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels) {
        sum += p.x;
    }
    return sum / static_cast<double>(image.pixels.size());
}

// A normal-map texel for the tangent-space normal n (unit, z > 0).
std::uint32_t normal_texel(glm::dvec3 n) {
    const auto byte = [](double c) {
        return static_cast<unsigned>(std::lround((c + 1.0) * 127.5));
    };
    return rgba(byte(n.x), byte(n.y), byte(n.z));
}

// `tangent`: the floor's tangents at every corner (as a file gives them),
// or nullptr for those computed from its texture coordinates (T = +x, the
// direction of u, and sign 1: B = cross(N, T) = -z, the direction of v).
void require_tilted_normal_map(bool opencl, const glm::vec4* tangent = nullptr) {
    // A diffuse floor under a sun from the direction (0.5, 1, 0) (normalised):
    // flat, it reflects rho/pi E cos. Its normal map tilts the normal by
    // 30 degrees towards +u (+x): it then reflects rho/pi E cos(theta')
    // with theta' the angle between the sun and the tilted normal, as a
    // plane tilted so would. The map's texel holds the normal to 1/255, so
    // the tilt is 30 +- 0.3 degrees: 1 % on the expected radiance.
    const double tilt = 30.0 * pi / 180.0;
    const glm::dvec3 tangent_normal(std::sin(tilt), 0.0, std::cos(tilt));
    const std::uint32_t texel = normal_texel(tangent_normal);
    // The normal the texel holds, decoded as the kernel does.
    const glm::dvec3 held = glm::normalize(glm::dvec3((texel & 255u) / 255.0 * 2.0 - 1.0,
                                                      ((texel >> 8) & 255u) / 255.0 * 2.0 - 1.0,
                                                      ((texel >> 16) & 255u) / 255.0 * 2.0 - 1.0));
    const glm::dvec3 normal(0.0, 1.0, 0.0);
    const glm::dvec3 t = tangent != nullptr ? glm::dvec3(*tangent) : glm::dvec3(1.0, 0.0, 0.0);
    const double sign = tangent != nullptr ? tangent->w : 1.0;
    const glm::dvec3 b = sign * glm::cross(normal, t);
    const glm::dvec3 world_normal = held.x * t + held.y * b + held.z * normal;
    const glm::dvec3 towards = glm::normalize(glm::dvec3(0.5, 1.0, 0.0));
    const double irradiance = 2.0;
    const double albedo = 0.5;
    Material floor;
    floor.name = "floor";
    floor.color = glm::vec3(static_cast<float>(albedo));
    Scene flat = floor_scene(floor);
    flat.lamps.push_back(sun_towards(glm::vec3(towards), static_cast<float>(irradiance)));
    Scene mapped = flat;
    mapped.materials[0].normal_texture = 0;
    mapped.textures.push_back(texture_of(2, 2, {texel, texel, texel, texel}));
    if (tangent != nullptr) {
        Shape& floor_shape = mapped.shapes[0];
        floor_shape.tangents.assign(floor_shape.triangles.size(), {*tangent, *tangent, *tangent});
    }
    REQUIRE((pack_scene(mapped).materials[0].maps.z) == 1u);
    const double flat_expected = albedo / pi * irradiance * towards.y;
    const double mapped_expected = albedo / pi * irradiance * glm::dot(world_normal, towards);
    const double flat_got = mean_red(render(flat, 4, opencl));
    const double mapped_got = mean_red(render(mapped, 4, opencl));
    CAPTURE(flat_got, flat_expected, mapped_got, mapped_expected);
    // The sun is a direction and the floor's light direct: every sample is
    // the closed form, to float rounding.
    REQUIRE(flat_got == Approx(flat_expected).epsilon(1e-4));
    REQUIRE(mapped_got == Approx(mapped_expected).epsilon(1e-4));
    if (tangent == nullptr) {
        REQUIRE(mapped_got > 1.1 * flat_got);  // tilted towards the sun: brighter (1.116)
    }
}

}  // namespace

TEST_CASE("a tilted normal map shades a flat floor as the tilted plane (CPU)", "[texture][maps]") {
    require_tilted_normal_map(false);
}

TEST_CASE("a tilted normal map shades a flat floor as the tilted plane (OpenCL)",
          "[texture][maps][opencl]") {
    require_tilted_normal_map(true);
}

TEST_CASE("a normal map turns with the file's tangents, not the coordinates' (CPU, OpenCL)",
          "[texture][maps][opencl]") {
    // Tangents along -z (where u does not go) with sign -1 (B = +x): the
    // map's tilt towards +T is then one away from the sun's side, and its
    // y towards +x. Either backend shading with the coordinates' tangents
    // (T = +x) instead would miss the closed form by over 20 %.
    const glm::vec4 file_tangent(0.0f, 0.0f, -1.0f, -1.0f);
    require_tilted_normal_map(false, &file_tangent);
    require_tilted_normal_map(true, &file_tangent);
}

namespace {

// A 1 m emitter at height 0.5 over the floor, facing down, with an
// emission texture of one black and one white column (or none): half
// its light, on average over it, both where the camera sees it and where
// the floor's light samples land on it. `principled`: the lamp is a
// principled material (white, metallic 0, roughness 0.5) that emits the
// same, with its emission texture.
Scene emitter_over_floor(bool textured, bool principled = false) {
    Material floor;
    floor.name = "floor";
    floor.color = glm::vec3(0.5f);
    Scene scene = floor_scene(floor);
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = glm::vec3(1.0f);
    lamp.emittance = 3.0f;
    if (principled) {
        lamp.type = MaterialType::principled;
        lamp.emittance = 0.0f;
        lamp.emission = glm::vec3(3.0f);
        lamp.metallic = 0.0f;
        lamp.roughness = 0.5f;
    }
    scene.materials.push_back(lamp);
    Shape quad = make_plane(glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(3.14159265f, 0.0f, 0.0f),
                            glm::vec2(1.0f), 1);
    for (const Triangle& t : quad.triangles) {
        TriangleUv uv;
        uv.present = true;
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k) {
            uv.uv[k] = glm::vec2(v[k].x + 0.5f, v[k].z + 0.5f);
        }
        quad.uvs.push_back(uv);
    }
    scene.shapes.push_back(quad);
    if (textured) {
        (principled ? scene.materials[1].emission_texture : scene.materials[1].texture) = 0;
        scene.textures.push_back(texture_of(2, 1, {rgba(0, 0, 0), rgba(255, 255, 255)}));
    }
    scene.camera.position = glm::vec3(0.0f, 0.4f, 1.2f);
    scene.camera.direction = glm::vec3(0.0f, -0.2f, -1.0f);
    scene.camera.world_up = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.render.width = 24;
    scene.render.height = 16;
    return scene;
}

}  // namespace

namespace {

void require_half_emission(bool principled) {
    // Bilinear between the two texel centres and repeating, the texture
    // averages exactly 1/2 over the quad; the floor under it gets half the
    // light. Tolerance: 5 standard errors of the block means (the floor's
    // light samples land on black or white).
    const Scene plain = emitter_over_floor(false, principled);
    const Scene textured = emitter_over_floor(true, principled);
    REQUIRE((pack_scene(textured).features & T0_FEATURE_TEXTURE) != 0u);
    if (principled) {
        REQUIRE(pack_scene(textured).materials[1].emission.w == 1.0f);
    } else {
        REQUIRE(pack_scene(textured).materials[1].type.y == 1u);
    }
    PackOptions options;
    options.integrator = Integrator::nee;
    options.sampler = SamplerKind::sobol;
    Renderer a(plain, std::make_unique<CpuBackend>(), 3, options);
    Renderer b(textured, std::make_unique<CpuBackend>(), 3, options);
    const int frames = 256;
    for (int i = 0; i < frames; ++i) {
        a.render_frame();
        b.render_frame();
    }
    double sum_a = 0.0, sum_b = 0.0, var_b = 0.0;
    const auto& moments = b.accumulator();
    for (std::size_t i = 0; i < a.image().pixels.size(); ++i) {
        sum_a += kernel::luminance(a.image().pixels[i]);
        sum_b += kernel::luminance(b.image().pixels[i]);
        var_b += moments[i].moments.y / (frames - 1) / frames;
    }
    const double n = static_cast<double>(a.image().pixels.size());
    const double se = std::sqrt(var_b) / n;
    CAPTURE(sum_a / n, sum_b / n, se);
    REQUIRE(std::fabs(sum_b / n - 0.5 * sum_a / n) <= 5.0 * se + 1e-6);
}

}  // namespace

TEST_CASE("an emission texture scales what an emitter sends, seen and sampled", "[texture][maps]") {
    require_half_emission(false);
}

TEST_CASE("a principled material's emission texture scales what it sends, seen and sampled",
          "[texture][maps]") {
    require_half_emission(true);
}

TEST_CASE("a principled material's emission lights the floor as an emitter's (CPU, OpenCL)",
          "[maps][emission][opencl]") {
    // Direct light alone (max_depth 2): the camera sees the lamp's
    // emission, and the floor the light it sends, by the same light
    // samples and the same MIS; that the principled lamp also reflects
    // would take a third vertex. So the two images are the same, to float
    // rounding (the emitter's radiance is colour x emittance, the other's
    // given: 1e-6).
    for (bool opencl : {false, true}) {
        CAPTURE(opencl);
        Scene emitter = emitter_over_floor(false, false);
        Scene principled = emitter_over_floor(false, true);
        emitter.render.max_depth = 2;
        principled.render.max_depth = 2;
        const PackedScene packed = pack_scene(principled);
        REQUIRE((packed.features & T0_FEATURE_EMITTANCE) != 0u);
        REQUIRE(packed.lights.size() == 2);  // the lamp's two triangles
        const Image a = render(emitter, 8, opencl);
        const Image b = render(principled, 8, opencl);
        REQUIRE(mean_red(a) > 0.1);
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
            CAPTURE(i);
            REQUIRE(b.pixels[i].x == Approx(a.pixels[i].x).epsilon(1e-6).margin(1e-7));
            REQUIRE(b.pixels[i].y == Approx(a.pixels[i].y).epsilon(1e-6).margin(1e-7));
        }
    }
}

TEST_CASE("a principled material that emits also reflects", "[maps][emission]") {
    // The camera under the lamp, looking up at the side it emits from
    // (all it sees), with a point light beside the camera that the lamp
    // reflects, over a black floor (which sends none of the lamp's own
    // light back to it): it shows its emission plus what it reflects, the
    // emission alone added to what the same material without it shows.
    // Tolerance: 5 standard errors of the difference of the two means.
    Scene lit = emitter_over_floor(false, true);
    lit.camera.position = glm::vec3(0.0f, 0.1f, 0.0f);
    lit.camera.direction = glm::vec3(0.0f, 1.0f, 0.0f);
    lit.camera.world_up = glm::vec3(0.0f, 0.0f, -1.0f);
    lit.render.max_depth = 3;
    lit.materials[0].color = glm::vec3(0.0f);
    Lamp bulb;
    bulb.position = glm::vec3(0.2f, 0.2f, 0.1f);
    bulb.power = 0.05f;
    lit.lamps.push_back(bulb);
    Scene dark = lit;
    dark.materials[1].emission = glm::vec3(0.0f);
    PackOptions options;
    options.integrator = Integrator::nee;
    options.sampler = SamplerKind::sobol;
    Renderer a(lit, std::make_unique<CpuBackend>(), 3, options);
    Renderer b(dark, std::make_unique<CpuBackend>(), 3, options);
    const int frames = 64;
    for (int i = 0; i < frames; ++i) {
        a.render_frame();
        b.render_frame();
    }
    double sum_a = 0.0, sum_b = 0.0, var = 0.0;
    const std::size_t count = a.image().pixels.size();
    for (std::size_t i = 0; i < count; ++i) {
        sum_a += a.image().pixels[i].x;
        sum_b += b.image().pixels[i].x;
        var +=
            (a.accumulator()[i].moments.y + b.accumulator()[i].moments.y) / (frames - 1) / frames;
    }
    const double reflected = sum_b / count;
    const double difference = (sum_a - sum_b) / count;
    const double se = std::sqrt(var) / count;
    CAPTURE(reflected, difference, se);
    REQUIRE(reflected > 0.05);  // it reflects
    REQUIRE(std::fabs(difference - 3.0) <= 5.0 * se + 1e-5);
}

TEST_CASE("metallic-roughness textures scale the factors (green roughness, blue metallic)",
          "[texture][maps]") {
    // A principled floor of metallic factor 1 under the sun: a texture of
    // blue 0 makes it a dielectric (as metallic 0 would), blue 255 keeps
    // it metal; green scales roughness alike.
    Material floor;
    floor.name = "floor";
    floor.type = MaterialType::principled;
    floor.color = glm::vec3(0.9f, 0.6f, 0.3f);
    floor.metallic = 1.0f;
    floor.roughness = 0.6f;
    Scene base = floor_scene(floor);
    base.lamps.push_back(sun_towards(glm::vec3(0.3f, 1.0f, 0.2f), 2.0f));
    base.camera.position = glm::vec3(0.0f, 0.3f, 0.0f);
    const auto with_texture = [&](std::uint32_t texel) {
        Scene s = base;
        s.materials[0].roughness_texture = 0;
        s.materials[0].metallic_texture = 0;
        s.textures.push_back(texture_of(1, 1, {texel}));
        return s;
    };
    const auto as_factors = [&](float metallic, float roughness) {
        Scene s = base;
        s.materials[0].metallic = metallic;
        s.materials[0].roughness = roughness;
        return s;
    };
    const Image metal = render(with_texture(rgba(0, 255, 255)), 8);
    const Image dielectric = render(with_texture(rgba(0, 255, 0)), 8);
    const Image half_rough = render(with_texture(rgba(0, 128, 255)), 8);
    const int n = side * side;
    // Close: the same paths, the factors through a bilinear lookup (float
    // rounding of a 1 x 1 texture's weights).
    CHECK(close_pixel_count(metal, render(as_factors(1.0f, 0.6f), 8)) >= n * 95 / 100);
    CHECK(close_pixel_count(dielectric, render(as_factors(0.0f, 0.6f), 8)) >= n * 95 / 100);
    CHECK(close_pixel_count(half_rough, render(as_factors(1.0f, 0.6f * 128.0f / 255.0f), 8)) >=
          n * 95 / 100);
    CHECK(close_pixel_count(metal, dielectric) < n / 2);
}

TEST_CASE("a glTF's emissiveTexture becomes its principled material's emission texture",
          "[texture][maps][scene_loader]") {
    TempDir dir;
    // 1 x 1 TGA images (stb_image reads them): uncompressed, 24-bit BGR.
    const unsigned char header[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 24, 0};
    const std::string tga_header(reinterpret_cast<const char*>(header), sizeof header);
    dir.write("base.tga", tga_header + std::string("\x10\x20\x30", 3));
    dir.write("glow.tga", tga_header + std::string("\x00\x00\xff", 3));  // red
    const float values[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    const std::string buffer(reinterpret_cast<const char*>(values), sizeof values);
    const std::string gltf =
        R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "extensionsUsed": ["KHR_materials_emissive_strength"],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
  "materials": [{"name": "screen", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                 "metallicFactor": 0}, "emissiveFactor": [1, 0.5, 1],
                 "emissiveTexture": {"index": 1},
                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}}],
  "textures": [{"source": 0}, {"source": 1}], "images": [{"uri": "base.tga"}, {"uri": "glow.tga"}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
        base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]})";
    dir.write("t.gltf", gltf);
    // Through a scene file: the file's textures are moved into the scene's.
    const std::string json = dir.write("s.json", R"({"materials": {"white": {"type": "diffuse",
                "color": [1, 1, 1]}}, "shapes": [{"type": "mesh", "file": "t.gltf",
                "material": "white"}]})");
    const Scene scene = load_scene_file(json);
    REQUIRE(scene.shapes.size() == 1);
    const Material& m = scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
    CHECK(m.type == MaterialType::principled);
    CAPTURE(m.emission.x, m.emission.y, m.emission.z);
    CHECK(m.emission == glm::vec3(2.0f, 1.0f, 2.0f));
    REQUIRE(m.texture >= 0);
    REQUIRE(m.emission_texture >= 0);
    REQUIRE(m.emission_texture < static_cast<int>(scene.textures.size()));
    CHECK(scene.textures[static_cast<std::size_t>(m.texture)].texels[0] == rgba(0x30, 0x20, 0x10));
    CHECK(scene.textures[static_cast<std::size_t>(m.emission_texture)].texels[0] ==
          rgba(255, 0, 0));
    const PackedScene packed = pack_scene(scene);
    const auto& record = packed.materials[static_cast<std::size_t>(scene.shapes[0].material)];
    CHECK(record.emission.w == static_cast<float>(m.emission_texture + 1));
    CHECK(glm::vec3(record.emission) == glm::vec3(2.0f, 1.0f, 2.0f));
    CHECK(packed.lights.size() == 1);
    // A strength that is no number >= 0: one message naming the file, the
    // material and the key.
    std::string bad = gltf;
    const std::string good = R"("emissiveStrength": 2)";
    REQUIRE(bad.find(good) != std::string::npos);
    bad.replace(bad.find(good), good.size(), R"("emissiveStrength": -1)");
    dir.write("t.gltf", bad);
    REQUIRE_THROWS_WITH(load_scene_file(json),
                        Catch::Contains("t.gltf: material 'screen': "
                                        "KHR_materials_emissive_strength: emissiveStrength -1") &&
                            Catch::Contains("expected a number in [0, 1e30]"));
}

TEST_CASE("MTL map_Pr, map_Pm, norm and map_Ke become the material's textures",
          "[texture][maps][scene_loader]") {
    TempDir dir;
    // 1 x 1 TGA images (stb_image reads them): uncompressed, 24-bit BGR.
    const auto tga = [&](const std::string& name, unsigned r, unsigned g, unsigned b) {
        const unsigned char header[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 24, 0};
        const unsigned char pixel[3] = {static_cast<unsigned char>(b),
                                        static_cast<unsigned char>(g),
                                        static_cast<unsigned char>(r)};
        dir.write(name, std::string(reinterpret_cast<const char*>(header), sizeof header) +
                            std::string(reinterpret_cast<const char*>(pixel), sizeof pixel));
    };
    tga("r.tga", 0, 200, 0);
    tga("m.tga", 0, 0, 100);
    tga("n.tga", 128, 128, 255);
    tga("e.tga", 255, 0, 0);
    dir.write("m.mtl",
              "newmtl pbr\nKd 0.5 0.5 0.5\nPr 0.5\nPm 1\nmap_Pr r.tga\nmap_Pm m.tga\nnorm n.tga\n"
              "newmtl glow\nKe 2 2 2\nmap_Ke e.tga\n");
    dir.write("m.obj",
              "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
              "usemtl pbr\nf 1/1 2/2 3/3\nusemtl glow\nf 1/1 3/3 2/2\n");
    const std::string json =
        dir.write("s.json", R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
               "shapes": [{"type": "mesh", "file": "m.obj", "material": "white"}]})");
    const Scene scene = load_scene_file(json);
    REQUIRE(scene.shapes.size() == 2);
    const Material& pbr = scene.materials[static_cast<std::size_t>(scene.shapes[0].material)];
    CHECK(pbr.type == MaterialType::principled);
    REQUIRE(pbr.roughness_texture >= 0);
    REQUIRE(pbr.metallic_texture >= 0);
    REQUIRE(pbr.normal_texture >= 0);
    CHECK(scene.textures[static_cast<std::size_t>(pbr.roughness_texture)].texels[0] ==
          rgba(0, 200, 0));
    CHECK(scene.textures[static_cast<std::size_t>(pbr.metallic_texture)].texels[0] ==
          rgba(0, 0, 100));
    CHECK(scene.textures[static_cast<std::size_t>(pbr.normal_texture)].texels[0] ==
          rgba(128, 128, 255));
    const Material& glow = scene.materials[static_cast<std::size_t>(scene.shapes[1].material)];
    CHECK(glow.type == MaterialType::emissive);
    REQUIRE(glow.texture >= 0);
    CHECK(scene.textures[static_cast<std::size_t>(glow.texture)].texels[0] == rgba(255, 0, 0));
    const PackedScene packed = pack_scene(scene);
    const auto& record = packed.materials[static_cast<std::size_t>(scene.shapes[0].material)];
    CHECK(record.maps.x != 0u);
    CHECK(record.maps.y != 0u);
    CHECK(record.maps.z != 0u);
}

namespace {

// A checker of alpha 0 and 255 (2 x 2 texels; bilinear and repeating, it
// is at least 1/2 on exactly half of each period).
Texture alpha_checker() {
    const std::uint32_t clear = 0x00ffffffu;
    const std::uint32_t solid = 0xffffffffu;
    return texture_of(2, 2, {clear, solid, solid, clear});
}

// A square of `side_length` at height y, of material `material`, whose
// texture coordinates repeat `periods` times across it (u along x, v
// along -z).
Shape checker_quad(float y, float side_length, int material, float periods) {
    Shape quad =
        make_plane(glm::vec3(0.0f, y, 0.0f), glm::vec3(0.0f), glm::vec2(side_length), material);
    for (const Triangle& t : quad.triangles) {
        TriangleUv uv;
        uv.present = true;
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k) {
            uv.uv[k] = glm::vec2(v[k].x, -v[k].z) / side_length * periods;
        }
        quad.uvs.push_back(uv);
    }
    return quad;
}

// The camera at height `height` looking down with a 60-degree view: the
// side of the square it sees at depth d is 2 d tan 30.
void look_down(Scene& scene, float height) {
    scene.camera.position = glm::vec3(0.0f, height, 0.0f);
    scene.camera.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    scene.camera.world_up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.vertical_fov = 60.0f;
    scene.render.width = 32;
    scene.render.height = 32;
    scene.render.max_depth = 2;
}

const float tan30 = 0.57735027f;

// A glowing floor (radiance 1) under a black quad at 0.5 that is a
// cut-out (MASK) checker, or (blend) of uniform alpha 1/4, seen from 1
// above: the camera's rays pass through the cut-outs.
Scene glow_under_quad(bool blend) {
    Scene scene;
    Material glow;
    glow.name = "glow";
    glow.type = MaterialType::emissive;
    glow.color = glm::vec3(1.0f);
    glow.emittance = 1.0f;
    Material black;
    black.name = "black";
    black.color = glm::vec3(0.0f);
    if (blend) {
        black.alpha_mode = AlphaMode::blend;
        black.alpha = 0.25f;
    } else {
        black.alpha_mode = AlphaMode::mask;
        black.alpha_texture = 0;
        scene.textures.push_back(alpha_checker());
    }
    scene.materials = {glow, black};
    scene.shapes.push_back(make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(4.0f), 0));
    // The view at depth 0.5 is 2 x 0.5 x tan 30 wide: 4 periods across it.
    const float seen = 2.0f * 0.5f * tan30;
    scene.shapes.push_back(checker_quad(0.5f, seen * 2.0f, 1, 8.0f));
    look_down(scene, 1.0f);
    return scene;
}

}  // namespace

TEST_CASE("an alpha cut-out lets camera rays through half a checker (CPU and OpenCL)",
          "[texture][maps][alpha]") {
    // The view holds whole periods of the checker: exactly half of it is
    // cut out, so the image's mean is 1/2 (the glow) to the pixels'
    // sampling of the edges: 16 jittered samples a pixel over 32 x 32
    // pixels, 0.01.
    const Scene scene = glow_under_quad(false);
    REQUIRE((pack_scene(scene).features & T0_FEATURE_ALPHA) != 0u);
    for (bool opencl : {false, true}) {
        CAPTURE(opencl);
        const double mean = mean_red(render(scene, 16, opencl));
        REQUIRE(mean == Approx(0.5).margin(0.01));
    }
}

TEST_CASE("alpha BLEND is stochastic opacity: alpha 1/4 shows 3/4 of what is behind",
          "[texture][maps][alpha]") {
    // 64 frames of 32 x 32 pixels, each sample 0 or 1 with probability
    // 3/4: standard error 0.0021; five of them.
    const double mean = mean_red(render(glow_under_quad(true), 64));
    REQUIRE(mean == Approx(0.75).margin(0.011));
}

TEST_CASE("an alpha cut-out lets shadow rays through: half the sun reaches the floor",
          "[texture][maps][alpha]") {
    // The sun straight above, the checker at 0.5 over a diffuse floor, the
    // camera at 0.25 between them (its own rays meet no quad): the floor's
    // shadow is the checker, whole periods of it in the view, so the
    // image's mean is half the lit floor's rho/pi E.
    Scene scene;
    Material floor;
    floor.name = "floor";
    floor.color = glm::vec3(0.5f);
    Material leaf;
    leaf.name = "leaf";
    leaf.color = glm::vec3(0.5f);
    leaf.alpha_mode = AlphaMode::mask;
    leaf.alpha_texture = 0;
    scene.textures.push_back(alpha_checker());
    scene.materials = {floor, leaf};
    scene.shapes.push_back(make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(4.0f), 0));
    const float seen = 2.0f * 0.25f * tan30;
    scene.shapes.push_back(checker_quad(0.5f, seen * 2.0f, 1, 8.0f));
    scene.lamps.push_back(sun_towards(glm::vec3(0.0f, 1.0f, 0.0f), 2.0f));
    look_down(scene, 0.25f);
    const double lit = 0.5 / pi * 2.0;
    const double mean = mean_red(render(scene, 16));
    CAPTURE(mean, lit);
    REQUIRE(mean == Approx(0.5 * lit).margin(0.01 * lit));
}
