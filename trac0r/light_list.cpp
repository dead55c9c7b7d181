#include "trac0r/light_list.h"

#include "trac0r/kernel/accumulate.h"
#include "trac0r/light_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace trac0r {

namespace {

const double pi = 3.14159265358979323846;

// A light and its power, in the list's unit: watts over 2 pi, so that a
// two-sided emitting triangle's is its radiance's luminance times its area
// (the unit the list had when it held triangles alone).
struct Candidate {
    kernel::LightRecord record;
    double power;
    // The light tree's weight (light_tree.h): its peak intensity, W/sr
    // (a surface's along its normal, radiance x area, on either side).
    double intensity = 0.0;
};

double luminance(const glm::vec3& c) { return kernel::luminance(c); }

// The radius of a sphere around everything packed: distant lights' power
// is what falls on its disc.
double scene_radius(const PackedScene& packed) {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (const kernel::TriangleRecord& t : packed.triangles) {
        for (const glm::vec4* v : {&t.v0, &t.v1, &t.v2}) {
            lo = glm::min(lo, glm::vec3(*v));
            hi = glm::max(hi, glm::vec3(*v));
        }
    }
    const double r = packed.triangles.empty() ? 0.0 : 0.5 * glm::length(glm::dvec3(hi - lo));
    return r > 0.0 && std::isfinite(r) ? r : 1.0;
}

// The environment's texels times its strength (xyz) with each row's CDF
// (w), then its rows' CDF (x), into packed.environment; each texel weighted
// by its luminance times the sine of its row's centre's polar angle, its
// share of solid angle. Returns its power (W / 2 pi for a sphere of
// radius 1): the integral of its luminance over the sphere, over 2. A
// constant environment is a map of one column of 64 rows, so that the
// rows' sines make its sampling close to uniform over the sphere.
double pack_environment(const Environment& e, PackedScene& packed, std::uint32_t* width,
                        std::uint32_t* height) {
    const bool constant = e.texels.empty();
    const int w = constant ? 1 : e.width;
    const int h = constant ? 64 : e.height;
    packed.environment.assign(static_cast<std::size_t>(w) * h + h, glm::vec4(0.0f));
    std::vector<double> row_weight(static_cast<std::size_t>(h), 0.0);
    double integral = 0.0;
    for (int r = 0; r < h; ++r) {
        const double sin_theta = std::sin(pi * (r + 0.5) / h);
        std::vector<double> weight(static_cast<std::size_t>(w));
        double row_total = 0.0;
        for (int c = 0; c < w; ++c) {
            const std::size_t i = static_cast<std::size_t>(r) * w + c;
            const glm::vec3 radiance = (constant ? e.color : e.texels[i]) * e.strength;
            packed.environment[i] = glm::vec4(radiance, 0.0f);
            weight[static_cast<std::size_t>(c)] = luminance(radiance) * sin_theta;
            row_total += weight[static_cast<std::size_t>(c)];
        }
        // The row's CDF; uniform in a row that is never picked.
        double running = 0.0;
        for (int c = 0; c < w; ++c) {
            running += weight[static_cast<std::size_t>(c)];
            const float cdf = c + 1 == w        ? 1.0f
                              : row_total > 0.0 ? static_cast<float>(running / row_total)
                                                : static_cast<float>(c + 1) / w;
            packed.environment[static_cast<std::size_t>(r) * w + c].w = cdf;
        }
        row_weight[static_cast<std::size_t>(r)] = row_total;
        integral += row_total;
    }
    const std::size_t rows_at = static_cast<std::size_t>(w) * h;
    double running = 0.0;
    for (int r = 0; r < h; ++r) {
        running += row_weight[static_cast<std::size_t>(r)];
        const float cdf = r + 1 == h       ? 1.0f
                          : integral > 0.0 ? static_cast<float>(running / integral)
                                           : static_cast<float>(r + 1) / h;
        packed.environment[rows_at + static_cast<std::size_t>(r)].x = cdf;
    }
    *width = static_cast<std::uint32_t>(w);
    *height = static_cast<std::uint32_t>(h);
    // Each texel spans (2 pi / w) (pi / h) of u and v, times sin theta of
    // solid angle: the sum of the weights times that is the integral.
    return integral * (2.0 * pi / w) * (pi / h) / 2.0;
}

Candidate environment_light(const Scene& scene, PackedScene& packed, double radius) {
    Candidate c;
    c.record = kernel::LightRecord{};
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    // Power: the radiance integrated over the sphere, on the scene's disc.
    c.power = pack_environment(scene.environment, packed, &width, &height) * radius * radius;
    const double rotation = scene.environment.rotation * pi / 180.0;
    c.record.ids = glm::uvec4(0u, T0_LIGHT_ENVIRONMENT, width, height);
    c.record.a = glm::vec4(static_cast<float>(std::cos(rotation)),
                           static_cast<float>(std::sin(rotation)), 0.0f, 0.0f);
    return c;
}

Candidate lamp_light(const Lamp& lamp, float scale, double radius) {
    Candidate c;
    c.record = kernel::LightRecord{};
    const glm::vec3 amount = lamp.color * lamp.power;
    if (lamp.type == LampType::sun) {
        const double half_angle = 0.5 * lamp.angle * pi / 180.0;
        const double sin2 = std::sin(half_angle) * std::sin(half_angle);
        const double one_minus_cos = 2.0 * std::sin(0.5 * half_angle) * std::sin(0.5 * half_angle);
        c.record.ids = glm::uvec4(0u, T0_LIGHT_SUN, 0u, 0u);
        c.record.a = glm::vec4(lamp.direction, 0.0f);
        c.record.b = glm::vec4(sin2 > 0.0 ? amount / static_cast<float>(pi * sin2) : amount, 0.0f);
        c.record.c =
            glm::vec4(static_cast<float>(sin2), static_cast<float>(2.0 * pi * one_minus_cos),
                      static_cast<float>(one_minus_cos), 0.0f);
        // The irradiance on the scene's disc.
        c.power = luminance(amount) * pi * radius * radius / (2.0 * pi);
        return c;
    }
    // A point lamp's irradiance, intensity / r^2, stays the same in the
    // packed scene's coordinates, r times scale, with the intensity times
    // scale^2.
    const double scale2 = static_cast<double>(scale) * scale;
    c.record.a = glm::vec4(lamp.position * scale, 0.0f);
    c.record.b = glm::vec4(amount * static_cast<float>(scale2), 0.0f);
    c.power = luminance(amount) * scale2 * 2.0;  // 4 pi I / 2 pi
    c.intensity = luminance(amount) * scale2;
    if (lamp.type == LampType::point) {
        c.record.ids = glm::uvec4(0u, T0_LIGHT_POINT, 0u, 0u);
        return c;
    }
    const double outer = 0.5 * lamp.angle * pi / 180.0;
    const double inner = outer * (1.0 - lamp.blend);
    c.record.ids = glm::uvec4(0u, T0_LIGHT_SPOT, 0u, 0u);
    c.record.a.w = static_cast<float>(std::cos(outer));
    c.record.c = glm::vec4(lamp.direction, static_cast<float>(std::cos(inner)));
    // pbrt-v4's estimate: 2 pi I (1 - (cos inner + cos outer) / 2), over 2 pi.
    c.power = luminance(amount) * scale2 * (1.0 - 0.5 * (std::cos(inner) + std::cos(outer)));
    return c;
}

}  // namespace

// The light list, picked in proportion to power: the environment, the
// suns, the point and spot lamps, and every triangle that emits, in that
// order (the distant lights first, as the kernel's escaped_radiance reads
// them). A triangle's power is the luminance of its emitted radiance
// (emittance x luminance(colour), or a principled's emission) x area,
// halved where it emits from one side (the radiance is the same over the
// triangle; pi and the two sides are common factors, and the others'
// powers are in the same unit). The CDF is summed in double and stored in
// float, strictly increasing; each probability is the difference of the
// stored floats, so it is exactly what the inverse-CDF pick gives, and
// above zero. The triangles are listed in
// the scene's order (packed_index maps it to the packed triangles), not
// the structure's, so that a light sample picks the same triangle with the
// flat list and with any BVH. Lights of no power are left out.
void pack_lights(const Scene& scene, PackedScene& packed,
                 const std::vector<std::uint32_t>& packed_index, LightSampler sampler) {
    std::vector<Candidate> lights;
    const double radius = scene_radius(packed);
    if (scene.environment.present) {
        const Candidate env = environment_light(scene, packed, radius);
        if (env.power > 0.0 && std::isfinite(env.power)) {
            lights.push_back(env);
            packed.features |= T0_FEATURE_ENVIRONMENT;
        } else {
            packed.environment.clear();  // black: nothing to find
        }
    }
    for (int pass = 0; pass < 2; ++pass) {  // the suns (distant) first
        for (const Lamp& lamp : scene.lamps) {
            if ((lamp.type == LampType::sun) != (pass == 0)) {
                continue;
            }
            const Candidate c = lamp_light(lamp, packed.scale, radius);
            if (c.power > 0.0 && std::isfinite(c.power)) {
                lights.push_back(c);
                packed.features |= T0_FEATURE_LAMPS;
                packed.distant_count += pass == 0 ? 1u : 0u;
            }
        }
    }
    packed.distant_count += (packed.features & T0_FEATURE_ENVIRONMENT) ? 1u : 0u;
    for (std::uint32_t i : packed_index) {
        kernel::TriangleRecord& t = packed.triangles[i];
        const kernel::MaterialRecord& m = packed.materials[t.ids.x];
        const double sides = m.type.z != 0u ? 0.5 : 1.0;
        // colour x emittance, or a principled material's emission.
        const double radiance =
            m.type.x == T0_MATERIAL_PRINCIPLED
                ? luminance(glm::vec3(m.emission))
                : static_cast<double>(m.params.x) * luminance(glm::vec3(m.color));
        const double p = radiance * 0.5 * t.normal.w * sides;
        if (p > 0.0 && std::isfinite(p)) {
            Candidate c;
            c.record = kernel::LightRecord{};
            c.record.ids = glm::uvec4(i, T0_LIGHT_TRIANGLE, 0u, 0u);
            c.power = p;
            c.intensity = p / sides;
            lights.push_back(c);
        }
    }
    double total = 0.0;
    for (const Candidate& c : lights) {
        total += c.power;
    }
    std::vector<float> cdfs(lights.size());
    double running = 0.0;
    for (std::size_t k = 0; k < lights.size(); ++k) {
        running += lights[k].power;
        cdfs[k] = k + 1 == lights.size() ? 1.0f : static_cast<float>(running / total);
    }
    // Strictly increasing: a light whose share rounds to nothing beside
    // the next one's CDF (a small lamp after a bright sky) takes a float's
    // step from the lights above it, so that every listed light can be
    // picked: the light tree may pick any light for a light sample, and
    // bidirectional path tracing weighs that against the light subpaths
    // that start from it.
    for (std::size_t k = lights.size(); k-- > 1;) {
        cdfs[k - 1] = std::min(cdfs[k - 1], std::nextafter(cdfs[k], 0.0f));
    }
    float previous_cdf = 0.0f;
    for (std::size_t k = 0; k < lights.size(); ++k) {
        const float cdf = cdfs[k];
        const float probability = cdf - previous_cdf;
        kernel::LightRecord light = lights[k].record;
        light.cdf = glm::vec4(cdf, probability, 0.0f, 0.0f);
        if (light.ids.y == T0_LIGHT_TRIANGLE) {
            kernel::TriangleRecord& t = packed.triangles[light.ids.x];
            light.cdf.z = probability / (0.5f * t.normal.w);
            t.ids.z = static_cast<std::uint32_t>(k);
        }
        packed.lights.push_back(light);
        previous_cdf = cdf;
    }
    const std::size_t positioned = lights.size() - packed.distant_count;
    if (positioned > 0 &&
        (sampler == LightSampler::tree ||
         (sampler == LightSampler::automatic && positioned >= light_tree_min_lights))) {
        std::vector<double> intensity;
        for (const Candidate& c : lights) {
            intensity.push_back(c.intensity);
        }
        build_light_tree(packed, intensity);
        packed.features |= T0_FEATURE_LIGHT_TREE;
    }
}

}  // namespace trac0r
