// The environment: the radiance that arrives from every direction a ray
// leaves the scene in, from an equirectangular map (a constant environment
// is a map of one column), looked up by direction and sampled in
// proportion to luminance x sin(theta), the map's share of solid angle.
//
// For a direction d (y up), turned by the map's rotation about +y:
// u = 0.5 + atan2(d.x, -d.z) / 2 pi across, v = acos(d.y) / pi down from
// the top row; so the map's middle is what a camera looking along -z sees,
// and its right half lies towards +x.
#ifndef TRAC0R_KERNEL_ENVIRONMENT_H
#define TRAC0R_KERNEL_ENVIRONMENT_H

#include "sampling.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// A world direction in the map's frame: turned by -rotation about +y
// (light->a.x, a.y: the rotation's cosine and sine).
T0_INLINE float3 environment_from_world(T0_GLOBAL const LightRecord* light, float3 d) {
    const float c = light->a.x;
    const float s = light->a.y;
    return make_float3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

// A direction in the map's frame turned back into the world's.
T0_INLINE float3 environment_to_world(T0_GLOBAL const LightRecord* light, float3 d) {
    const float c = light->a.x;
    const float s = light->a.y;
    return make_float3(c * d.x + s * d.z, d.y, c * d.z - s * d.x);
}

// The map's texel (its index) that direction d of the map's frame falls in.
T0_INLINE t0_u32 environment_texel(T0_GLOBAL const LightRecord* light, float3 d) {
    const t0_u32 width = light->ids.z;
    const t0_u32 height = light->ids.w;
    const float u = 0.5f + atan2(d.x, -d.z) * (0.5f * T0_INV_PI);
    const float v = acos(fmin(fmax(d.y, -1.0f), 1.0f)) * T0_INV_PI;
    const t0_u32 column = (t0_u32)fmin(fmax(u * (float)width, 0.0f), (float)(width - 1u));
    const t0_u32 row = (t0_u32)fmin(fmax(v * (float)height, 0.0f), (float)(height - 1u));
    return row * width + column;
}

// The rows' CDF through row r (0 before the first row).
T0_INLINE float environment_row_cdf(const SceneView* scene, T0_GLOBAL const LightRecord* light,
                                    t0_u32 r) {
    return scene->environment[light->ids.z * light->ids.w + r].x;
}

// The density, per unit of u and v, with which environment_sample picks
// texel `texel`: the row's probability times the texel's within its row,
// per the texel's share of the map's area.
T0_INLINE float environment_texel_density(const SceneView* scene,
                                          T0_GLOBAL const LightRecord* light, t0_u32 texel) {
    const t0_u32 width = light->ids.z;
    const t0_u32 row = texel / width;
    const t0_u32 column = texel - row * width;
    const float row_before = row > 0u ? environment_row_cdf(scene, light, row - 1u) : 0.0f;
    const float column_before = column > 0u ? scene->environment[texel - 1u].w : 0.0f;
    const float p_row = environment_row_cdf(scene, light, row) - row_before;
    const float p_column = scene->environment[texel].w - column_before;
    return p_row * p_column * (float)width * (float)light->ids.w;
}

// The radiance from world direction d.
T0_INLINE float3 environment_radiance(const SceneView* scene, T0_GLOBAL const LightRecord* light,
                                      float3 d) {
    return xyz(scene->environment[environment_texel(light, environment_from_world(light, d))]);
}

// sin(theta) of a unit direction of the map's frame, from x and z (not
// from y: near a pole 1 - y^2 rounds to zero while x and z do not), the
// same for a sampled direction and for one a ray finds.
T0_INLINE float environment_sin_theta(float3 m) { return sqrt(m.x * m.x + m.z * m.z); }

// The density per solid angle with which environment_sample picks world
// direction d: the texel's density per u and v over the solid angle per u
// and v, 2 pi^2 sin(theta).
T0_INLINE float environment_pdf(const SceneView* scene, T0_GLOBAL const LightRecord* light,
                                float3 d) {
    const float3 m = environment_from_world(light, d);
    const float sin_theta = environment_sin_theta(m);
    if (!(sin_theta > 0.0f)) {
        return 0.0f;
    }
    return environment_texel_density(scene, light, environment_texel(light, m)) /
           (2.0f * T0_PI * T0_PI * sin_theta);
}

// The first of the `count` entries from `first` on whose component .x
// (w_component 0) or .w (1) exceeds u: an inverse-CDF search.
T0_INLINE t0_u32 environment_search(const SceneView* scene, t0_u32 first, t0_u32 count,
                                    int w_component, float u) {
    t0_u32 lo = 0u;
    t0_u32 hi = count - 1u;
    while (lo < hi) {
        const t0_u32 mid = lo + (hi - lo) / 2u;
        const float4 entry = scene->environment[first + mid];
        if (u < (w_component ? entry.w : entry.x)) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

typedef struct EnvironmentSample {
    float3 direction;  // world, unit
    float3 radiance;
    float pdf;  // per solid angle; 0: the sample failed (at a pole)
} EnvironmentSample;

// A direction picked by the map's two CDFs (a row, then a texel in it),
// uniform in u and v within the texel; u in [0, 1)^2.
T0_INLINE EnvironmentSample environment_sample(const SceneView* scene,
                                               T0_GLOBAL const LightRecord* light, float2 u) {
    const t0_u32 width = light->ids.z;
    const t0_u32 height = light->ids.w;
    const t0_u32 row = environment_search(scene, width * height, height, 0, u.x);
    const float row_before = row > 0u ? environment_row_cdf(scene, light, row - 1u) : 0.0f;
    const float p_row = environment_row_cdf(scene, light, row) - row_before;
    const t0_u32 column = environment_search(scene, row * width, width, 1, u.y);
    const t0_u32 texel = row * width + column;
    const float column_before = column > 0u ? scene->environment[texel - 1u].w : 0.0f;
    const float p_column = scene->environment[texel].w - column_before;
    const float dv = fmin((u.x - row_before) / p_row, 0.99999994f);
    const float du = fmin((u.y - column_before) / p_column, 0.99999994f);
    const float map_v = ((float)row + dv) / (float)height;
    const float map_u = ((float)column + du) / (float)width;
    // theta = pi v; psi = atan2(x, -z) = 2 pi (u - 1/2), whose cosine and
    // sine are those of 2 pi u negated.
    const float2_cs theta = turn_cos_sin(0.5f * map_v);
    const float2_cs turn = turn_cos_sin(map_u);
    const float3 m = make_float3(-theta.s * turn.s, theta.c, theta.s * turn.c);
    EnvironmentSample s;
    s.direction = environment_to_world(light, m);
    s.radiance = xyz(scene->environment[texel]);
    const float sin_theta = environment_sin_theta(environment_from_world(light, s.direction));
    s.pdf = sin_theta > 0.0f ? p_row * p_column * (float)width * (float)height /
                                   (2.0f * T0_PI * T0_PI * sin_theta)
                             : 0.0f;
    return s;
}

T0_NAMESPACE_END

#endif
