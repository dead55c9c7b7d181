// Extreme random numbers (issue 5, docs/stability.md): uniforms of exactly
// 0 and 1 - 2^-24, the ends of what both samplers draw (sampler.h), fed
// into every material, light sampling, camera jitter and Russian roulette.
#include <catch2/catch.hpp>

#include "stability_support.h"

#include <cstdint>
#include <limits>
#include <vector>

using namespace trac0r;
using namespace trac0r::stability;

namespace {

const float largest_uniform = 1.0f - 1.0f / 16777216.0f;  // 1 - 2^-24

bool finite_sample(const kernel::ScatterSample& s) {
    if (!finite(s.direction) || !finite(s.weight) || !std::isfinite(s.pdf) || s.pdf < 0.0f) {
        return false;
    }
    if (s.weight.x < 0.0f || s.weight.y < 0.0f || s.weight.z < 0.0f) {
        return false;
    }
    // A failed sample (weight zero) may carry any finite direction.
    const bool failed = s.weight == glm::vec3(0.0f);
    return failed || std::fabs(glm::length(s.direction) - 1.0f) < 1e-5f;
}

}  // namespace

TEST_CASE(
    "uniforms of exactly 0 and 1 - 2^-24 give every material finite directions and "
    "weights",
    "[stability][sampling]") {
    // The direction samplers alone are checked in test_sampling.cpp; here
    // the material routines that draw their own numbers, for every
    // combination of extremes, at normal, oblique, grazing and exactly
    // tangent incidence, from both sides.
    const float extremes[] = {0.0f, largest_uniform};
    std::vector<kernel::MaterialRecord> materials;
    auto add = [&materials](unsigned type, float roughness, float ior) {
        materials.push_back(
            kernel::make_material_record(type, glm::vec3(0.8f, 0.5f, 0.2f), 0.0f, roughness, ior));
    };
    add(T0_MATERIAL_DIFFUSE, 0.0f, 1.5f);
    for (float roughness : {0.0f, 0.5f, 1.0f}) {
        add(T0_MATERIAL_GLOSSY, roughness, 1.5f);
    }
    for (float ior : {1.0f, 1.5f, 3.0f}) {
        add(T0_MATERIAL_GLASS, 0.0f, ior);
    }
    kernel::SceneView scene = {};
    scene.features = T0_FEATURE_DIFFUSE | T0_FEATURE_GLOSSY | T0_FEATURE_GLASS;
    const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f));
    const glm::vec3 tangent = glm::normalize(glm::cross(normal, glm::vec3(1.0f, 0.0f, 0.0f)));
    // Angles from the normal: 0, 45, 89.99 degrees, and exactly 90.
    std::vector<glm::vec3> incoming;
    for (float cos_theta : {1.0f, 0.70710678f, 1.7e-4f}) {
        const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
        incoming.push_back(glm::normalize(-cos_theta * normal + sin_theta * tangent));
    }
    incoming.push_back(tangent);
    int checked = 0;
    for (const kernel::MaterialRecord& m : materials) {
        for (const glm::vec3& in : incoming) {
            for (float side : {1.0f, -1.0f}) {  // hitting the front or the back
                const glm::vec3 geometric = side * normal;
                const glm::vec3 facing = glm::dot(in, geometric) < 0.0f ? geometric : -geometric;
                for (float u1 : extremes) {
                    for (float u2 : extremes) {
                        CAPTURE(m.type.x, m.params.y, m.params.z, in.x, in.y, in.z, side, u1, u2);
                        const kernel::ScatterSample s = kernel::scatter_material(
                            &scene, &m, glm::vec3(1.0f), glm::vec2(1.0f), 1, in,
                            geometric, facing, glm::vec2(u1, u2), u1);
                        REQUIRE(finite_sample(s));
                        ++checked;
                    }
                }
            }
        }
    }
    CHECK(checked == 7 * 4 * 2 * 4);
}

TEST_CASE(
    "uniforms of exactly 0 and 1 - 2^-24 into light sampling: a light in the list, a "
    "point on it, a finite contribution",
    "[stability][sampling]") {
    // Next-event estimation draws three numbers per light sample: which
    // light (an inverse-CDF search), and a point on it (the square-root
    // map). Every combination of extremes, from a point of the room's floor,
    // for a diffuse and a glossy floor.
    Scene scene = room(1.0f, glm::vec3(0.0f));
    scene.materials.push_back(make_material(MaterialType::emissive, glm::vec3(0.2f), 3.0f));
    scene.shapes.push_back(make_plane(glm::vec3(-0.5f, 0.0f, 0.9f),
                                      glm::vec3(-1.5707964f, 0.0f, 0.0f), glm::vec2(0.3f), 3));
    PackOptions options;
    options.integrator = Integrator::nee;
    const PackedScene packed = pack_scene(scene, options);
    const kernel::SceneView view = packed.view();
    REQUIRE(view.light_count == 4);  // two lamps of two triangles each
    const float extremes[] = {0.0f, largest_uniform};
    CHECK(kernel::pick_light(&view, 0.0f) == 0u);
    CHECK(kernel::pick_light(&view, largest_uniform) == view.light_count - 1u);
    for (float u1 : extremes) {
        for (float u2 : extremes) {
            float b1 = -1.0f;
            float b2 = -1.0f;
            kernel::sample_triangle_barycentrics(u1, u2, &b1, &b2);
            CAPTURE(u1, u2, b1, b2);
            CHECK(b1 >= 0.0f);
            CHECK(b2 >= 0.0f);
            CHECK(b1 + b2 <= 1.0f);
        }
    }
    // The second floor glossy, with a lobe wide enough to sample lights.
    const kernel::MaterialRecord floors[2] = {
        packed.materials[0],
        kernel::make_material_record(T0_MATERIAL_GLOSSY, glm::vec3(packed.materials[0].color), 0.0f,
                                     0.5f, 1.5f)};
    kernel::SceneView glossy_view = view;
    glossy_view.features |= T0_FEATURE_GLOSSY;
    const glm::vec3 position(-0.6f, -1.0f, -0.5f);  // beside the block, under the lamp
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 incoming = glm::normalize(glm::vec3(0.3f, -1.0f, 0.4f));
    int lit = 0;
    for (const kernel::MaterialRecord& m : floors) {
        for (float pick : extremes) {
            for (float u1 : extremes) {
                for (float u2 : extremes) {
                    CAPTURE(m.type.x, pick, u1, u2);
                    const kernel::ShadowedLight sample =
                        kernel::sample_light(&glossy_view, &m, glm::vec3(1.0f), glm::vec2(1.0f), 1,
                                             incoming, up, up, position, 1.0f,
                                             pick, 0.0f, glm::vec2(u1, u2));
                    const glm::vec3 radiance = sample.sent;  // its shadow ray traced
                    REQUIRE(finite(radiance));
                    REQUIRE(radiance.x >= 0.0f);
                    REQUIRE(radiance.y >= 0.0f);
                    REQUIRE(radiance.z >= 0.0f);
                    lit += radiance.x > 0.0f;
                }
            }
        }
    }
    CHECK(lit > 0);  // the control: some extreme points are seen and lit
}

TEST_CASE("extreme jitter and roulette inputs stay finite", "[stability][sampling]") {
    Camera c;
    c.direction = glm::vec3(0.3f, -0.2f, 1.0f);
    const kernel::CameraRecord cam = make_camera_record(c, 16, 16);
    for (float jx : {0.0f, largest_uniform}) {
        for (float jy : {0.0f, largest_uniform}) {
            for (float corner : {0.0f, 15.0f}) {
                const kernel::Ray ray = kernel::camera_ray(cam, corner, corner, jx, jy);
                REQUIRE(finite(ray.direction));
                REQUIRE(std::fabs(glm::length(ray.direction) - 1.0f) < 1e-6f);
                REQUIRE(finite(ray.inv_direction));
            }
        }
    }
    // The probability is in [0, 1] for throughputs from 0 to the largest
    // float, at the first and the last depth of short and long paths.
    const float throughputs[] = {0.0f, 1e-38f, 1.0f, 1e6f, std::numeric_limits<float>::max()};
    for (int max_depth : {1, 2, 1000, 100000}) {
        for (int depth : {0, max_depth - 1}) {
            for (float t : throughputs) {
                const float q = kernel::continuation_probability(depth, max_depth, glm::vec3(t));
                CAPTURE(max_depth, depth, t, q);
                REQUIRE(q >= 0.0f);
                REQUIRE(q <= 1.0f);
            }
        }
    }
}
