// What every material's sampling and evaluation return, the inputs a hit
// gives them, and the mirror, refraction and Fresnel formulas they share.
#ifndef TRAC0R_KERNEL_SCATTER_H
#define TRAC0R_KERNEL_SCATTER_H

#include "types.h"

T0_NAMESPACE_BEGIN

typedef struct ScatterSample {
    float3 direction;
    float3 weight;  // f cos / pdf; zero when the sample failed
    float pdf;      // zero for delta (mirror and glass) directions
    int is_delta;
} ScatterSample;

T0_INLINE ScatterSample scatter_failed(void) {
    ScatterSample s;
    s.direction = make_float3(0.0f, 0.0f, 1.0f);
    s.weight = float3_splat(0.0f);
    s.pdf = 0.0f;
    s.is_delta = 0;
    return s;
}

T0_INLINE float3 reflect_direction(float3 d, float3 n) { return d - n * (2.0f * dot(d, n)); }

// cos^2 of the refraction angle (Snell's law); <= 0 is total internal
// reflection. Written (1 - eta^2) + (eta cos_i)^2, not 1 - eta^2 (1 - cos_i^2):
// equal in exact arithmetic, but only this form is exact for eta = 1, where
// 1 - cos_i^2 rounds to 1 below cos_i = 2.4e-4 and an index-matched
// interface would reflect totally near grazing.
T0_INLINE float refracted_cos2(float cos_i, float eta) {
    const float eta_cos_i = eta * cos_i;
    return (1.0f - eta * eta) + eta_cos_i * eta_cos_i;
}

// Unpolarised Fresnel reflectance of a dielectric interface.
// cos_i: cosine of the incident angle (>= 0); eta = eta_incident/eta_transmitted.
// Returns 1 for total internal reflection and at exactly grazing incidence.
T0_INLINE float fresnel_dielectric(float cos_i, float eta) {
    cos_i = fmin(fmax(cos_i, 0.0f), 1.0f);
    const float cos2_t = refracted_cos2(cos_i, eta);
    if (!(cos2_t > 0.0f)) {
        return 1.0f;
    }
    const float cos_t = sqrt(cos2_t);
    const float perp_den = eta * cos_i + cos_t;
    const float parallel_den = cos_i + eta * cos_t;
    if (!(perp_den > 0.0f) || !(parallel_den > 0.0f)) {
        return 1.0f;
    }
    const float r_perp = (eta * cos_i - cos_t) / perp_den;
    const float r_parallel = (cos_i - eta * cos_t) / parallel_den;
    return 0.5f * (r_perp * r_perp + r_parallel * r_parallel);
}

// Next-event estimation asks the other way round: given a direction (to a
// point on a light), how much does the material scatter into it, and how
// likely would its own sampling have been to pick it.
typedef struct MaterialEval {
    float3 f_cos;  // BSDF x cosine toward the direction; zero outside the lobe
    float pdf;     // density (solid angle) of scatter_material picking it
} MaterialEval;

T0_INLINE MaterialEval eval_failed(void) {
    MaterialEval e;
    e.f_cos = float3_splat(0.0f);
    e.pdf = 0.0f;
    return e;
}

// What a hit gives its material besides the record: the base colour (the
// material's colour times its texture, for the microfacet types; the
// thesis' four take their texture as a factor on the whole sample), GGX's
// alpha, the metallic factor, and whether the ray arrived at the
// triangle's outer side (glass: which index is on which side).
typedef struct Surface {
    float3 base;
    float alpha;
    float metallic;
    int front;
} Surface;

T0_NAMESPACE_END

#endif
