// The four materials: what they emit and how they scatter.
//
// A scatter sample returns the new direction, the weight f cos / pdf, the
// pdf, and says when it failed (weight zero), never a NaN. It is made from
// two uniforms in [0, 1)^2 (sampler.h's T0_DIM_MATERIAL draw).
#ifndef TRAC0R_KERNEL_MATERIAL_H
#define TRAC0R_KERNEL_MATERIAL_H

#include "sampling.h"
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

// A material as the kernels read it. Roughness r (0..1) makes the glossy
// lobe a cone of half-angle r pi/2 about the mirror direction.
T0_INLINE MaterialRecord make_material_record(t0_u32 type, float3 color, float emittance,
                                              float roughness, float ior) {
    MaterialRecord r;
    r.color = make_float4(color.x, color.y, color.z, 0.0f);
    r.params = make_float4(emittance, roughness, ior, cone_sin2(roughness * 0.5f * T0_PI));
    r.type = make_uint4(type, 0u, 0u, 0u);
    return r;
}

// sin^2 of the half-angle of a glossy material's cone, made when the
// record is (make_material_record): not a sine at every glossy bounce.
T0_INLINE float glossy_cone_sin2(T0_GLOBAL const MaterialRecord* m) { return m->params.w; }

// Emitted radiance: colour x emittance, on both sides (as in the thesis)
// or, for a one-sided emitter, from its front only (material_emission_seen).
T0_INLINE float3 material_emission(T0_GLOBAL const MaterialRecord* m) {
    return xyz(m->color) * m->params.x;
}

// Whether the material emits from its front only (the side its triangles'
// counter-clockwise winding faces; type.z).
T0_INLINE int material_one_sided(T0_GLOBAL const MaterialRecord* m) { return m->type.z != 0u; }

// The radiance a ray meets on the material from its front (front != 0) or
// its back.
T0_INLINE float3 material_emission_seen(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                        int front) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_ONE_SIDED) && !front && material_one_sided(m)) {
        return float3_splat(0.0f);
    }
    return material_emission(m);
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

// Lambertian: BRDF colour/pi, cosine-weighted sampling, so the weight is the
// colour itself.
T0_INLINE ScatterSample scatter_diffuse(T0_GLOBAL const MaterialRecord* m, float3 facing_normal,
                                        float2 u) {
    const DirectionSample d = sample_cosine_hemisphere(facing_normal, u.x, u.y);
    ScatterSample s;
    s.direction = d.direction;
    s.weight = xyz(m->color);
    s.pdf = d.pdf;
    s.is_delta = 0;
    return s;
}

// The thesis' glossy model: a cosine-weighted cone of half-angle
// roughness * pi/2 around the mirror direction; the lobe is its own
// sampling density, so the weight is the colour. Roughness 0 is a mirror.
// Directions below the surface are absorbed (a failed sample).
T0_INLINE ScatterSample scatter_glossy(T0_GLOBAL const MaterialRecord* m, float3 incoming,
                                       float3 facing_normal, float2 u) {
    const float3 mirror = reflect_direction(incoming, facing_normal);
    const DirectionSample d = sample_cosine_cone_sin2(mirror, glossy_cone_sin2(m), u.x, u.y);
    if (!(dot(d.direction, facing_normal) > 0.0f)) {
        return scatter_failed();
    }
    ScatterSample s;
    s.direction = d.direction;
    s.weight = xyz(m->color);
    s.pdf = d.pdf;
    s.is_delta = d.pdf == 0.0f ? 1 : 0;
    return s;
}

// Smooth dielectric. Reflection or refraction is chosen with the Fresnel
// probability (u_choice < reflectance), so each has weight one; refraction
// is tinted by the colour.
// outward_normal is the triangle's outward normal (or its shading normal,
// which is on the same side of the incoming ray): it tells entering from
// leaving.
T0_INLINE ScatterSample scatter_glass(T0_GLOBAL const MaterialRecord* m, float3 incoming,
                                      float3 outward_normal, float u_choice) {
    const int entering = dot(incoming, outward_normal) < 0.0f;
    const float3 n = entering ? outward_normal : -outward_normal;
    const float ior = m->params.z;
    const float eta = entering ? 1.0f / ior : ior;
    const float cos_i = fmin(fmax(-dot(incoming, n), 0.0f), 1.0f);
    const float reflectance = fresnel_dielectric(cos_i, eta);
    ScatterSample s;
    s.pdf = 0.0f;
    s.is_delta = 1;
    if (u_choice < reflectance) {
        s.direction = reflect_direction(incoming, n);
        s.weight = float3_splat(1.0f);
        return s;
    }
    const float cos_t = sqrt(fmax(0.0f, refracted_cos2(cos_i, eta)));
    s.direction = normalize(incoming * eta + n * (eta * cos_i - cos_t));
    s.weight = xyz(m->color);
    return s;
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

// Glossy cones narrower than this (sin^2 of the half-angle: about 0.6
// degrees, roughness 0.0064) count as mirrors for next-event estimation:
// a light sample would almost never land in them, and the cone test is at
// the limit of float precision. Their paths rely on scattering alone,
// which is unbiased for any roughness.
#define T0_GLOSSY_LIGHT_SAMPLING_MIN_SIN2 1e-4f

// Lambertian: f cos = colour cos / pi; the density is the cosine's, cos / pi.
T0_INLINE MaterialEval eval_diffuse(T0_GLOBAL const MaterialRecord* m, float3 facing_normal,
                                    float3 direction) {
    const float cos_theta = dot(direction, facing_normal);
    if (!(cos_theta > 0.0f)) {
        return eval_failed();
    }
    MaterialEval e;
    e.pdf = cos_theta * T0_INV_PI;
    e.f_cos = xyz(m->color) * e.pdf;
    return e;
}

// The thesis' glossy lobe is its own density (scatter_glossy's weight is
// the colour), so f cos = colour x density, inside the cone and above the
// surface.
T0_INLINE MaterialEval eval_glossy(T0_GLOBAL const MaterialRecord* m, float3 incoming,
                                   float3 facing_normal, float3 direction) {
    if (!(dot(direction, facing_normal) > 0.0f)) {
        return eval_failed();
    }
    const float3 mirror = reflect_direction(incoming, facing_normal);
    MaterialEval e;
    e.pdf = cosine_cone_pdf(mirror, glossy_cone_sin2(m), direction);
    e.f_cos = xyz(m->color) * e.pdf;
    return e;
}

// Whether next-event estimation samples lights at a hit on this material:
// diffuse and rough glossy surfaces; not emitters (paths end there), glass
// or mirror-like glossy (delta lobes that a light sample never lands in).
T0_INLINE int material_samples_lights(const SceneView* scene, T0_GLOBAL const MaterialRecord* m) {
    const t0_u32 type = m->type.x;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_DIFFUSE) && type == T0_MATERIAL_DIFFUSE) {
        return 1;
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_GLOSSY) && type == T0_MATERIAL_GLOSSY) {
        return glossy_cone_sin2(m) >= T0_GLOSSY_LIGHT_SAMPLING_MIN_SIN2;
    }
    return 0;
}

T0_INLINE MaterialEval eval_material(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                     float3 incoming, float3 facing_normal, float3 direction) {
    const t0_u32 type = m->type.x;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_DIFFUSE) && type == T0_MATERIAL_DIFFUSE) {
        return eval_diffuse(m, facing_normal, direction);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_GLOSSY) && type == T0_MATERIAL_GLOSSY) {
        return eval_glossy(m, incoming, facing_normal, direction);
    }
    return eval_failed();  // delta lobes and emitters
}

T0_INLINE ScatterSample scatter_material(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                         float3 incoming, float3 outward_normal,
                                         float3 facing_normal, float2 u) {
    const t0_u32 type = m->type.x;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_DIFFUSE) && type == T0_MATERIAL_DIFFUSE) {
        return scatter_diffuse(m, facing_normal, u);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_GLASS) && type == T0_MATERIAL_GLASS) {
        return scatter_glass(m, incoming, outward_normal, u.x);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_GLOSSY) && type == T0_MATERIAL_GLOSSY) {
        return scatter_glossy(m, incoming, facing_normal, u);
    }
    return scatter_failed();  // emissive: a pure emitter ends the path
}

T0_NAMESPACE_END

#endif
