#include "trac0r/light_list.h"

#include "trac0r/kernel/accumulate.h"

#include <cmath>

namespace trac0r {

// The light list: every triangle that emits, picked in proportion to its
// power, emittance x luminance(colour) x area (the radiance is the same over
// the triangle, and pi and the two sides are common factors). The CDF is
// summed in double and stored in float; each probability is the difference
// of the stored floats, so it is exactly what the inverse-CDF pick gives.
// The lights are listed in the scene's order (packed_index maps it to the
// packed triangles), not the structure's, so that a light sample picks the
// same triangle with the flat list and with any BVH.
void pack_lights(PackedScene& packed, const std::vector<std::uint32_t>& packed_index) {
    std::vector<double> power;
    std::vector<std::uint32_t> emitting;
    double total = 0.0;
    for (std::uint32_t i : packed_index) {
        const kernel::TriangleRecord& t = packed.triangles[i];
        const kernel::MaterialRecord& m = packed.materials[t.ids.x];
        const double p = static_cast<double>(m.params.x) * kernel::luminance(glm::vec3(m.color)) *
                         0.5 * t.normal.w;
        if (p > 0.0 && std::isfinite(p)) {
            emitting.push_back(i);
            power.push_back(p);
            total += p;
        }
    }
    double running = 0.0;
    float previous_cdf = 0.0f;
    for (std::size_t k = 0; k < emitting.size(); ++k) {
        running += power[k];
        const float cdf = k + 1 == emitting.size() ? 1.0f : static_cast<float>(running / total);
        const float probability = cdf - previous_cdf;
        kernel::TriangleRecord& t = packed.triangles[emitting[k]];
        kernel::LightRecord light;
        light.cdf = glm::vec4(cdf, probability, probability / (0.5f * t.normal.w), 0.0f);
        light.triangle = glm::uvec4(emitting[k], 0u, 0u, 0u);
        t.ids.z = static_cast<std::uint32_t>(k);
        packed.lights.push_back(light);
        previous_cdf = cdf;
    }
}

}  // namespace trac0r
