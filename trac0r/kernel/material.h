// The materials: what they emit and how they scatter; the thesis' four
// here, the microfacet ones in rough_materials.h.
//
// A scatter sample returns the new direction, the weight f cos / pdf, the
// pdf, and says when it failed (weight zero), never a NaN. It is made from
// two uniforms in [0, 1)^2 (sampler.h's T0_DIM_MATERIAL draw).
#ifndef TRAC0R_KERNEL_MATERIAL_H
#define TRAC0R_KERNEL_MATERIAL_H

#include "rough_materials.h"
#include "sampling.h"
#include "scatter.h"
#include "texture.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// A material as the kernels read it. Roughness r (0..1) makes the glossy
// lobe a cone of half-angle r pi/2 about the mirror direction, and the
// microfacet types' GGX alpha r^2. A conductor's index, plastic's diffuse
// scale and principled's specular factor the host sets (packed_scene.cpp).
T0_INLINE MaterialRecord make_material_record(t0_u32 type, float3 color, float emittance,
                                              float roughness, float ior) {
    MaterialRecord r;
    r.color = make_float4(color.x, color.y, color.z, 0.0f);
    const float shape = type == T0_MATERIAL_GLOSSY || type <= T0_MATERIAL_GLASS
                            ? cone_sin2(roughness * 0.5f * T0_PI)
                            : ggx_alpha(roughness);
    r.params = make_float4(emittance, roughness, ior, shape);
    r.type = make_uint4(type, 0u, 0u, 0u);
    r.eta = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    r.k = make_float4(0.0f, 0.0f, 0.0f, 1.0f);
    r.maps = make_uint4(0u, 0u, 0u, 0u);
    r.alpha = make_float4(1.0f, 0.5f, 0.0f, 3.0f);
    r.emission = make_float4(color.x * emittance, color.y * emittance, color.z * emittance, 0.0f);
    return r;
}

// sin^2 of the half-angle of a glossy material's cone, made when the
// record is (make_material_record): not a sine at every glossy bounce.
T0_INLINE float glossy_cone_sin2(T0_GLOBAL const MaterialRecord* m) { return m->params.w; }

// Emitted radiance: colour x emittance (or a principled material's
// emission), on both sides (as in the thesis) or, for a one-sided emitter,
// from its front only (material_emission_seen).
T0_INLINE float3 material_emission(T0_GLOBAL const MaterialRecord* m) { return xyz(m->emission); }

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

// What a hit's emission is multiplied by: an emitter's texture (type.y,
// which is its emission's), a principled material's emission texture
// (emission.w); one where it has none or the triangle no coordinates.
T0_INLINE float3 emission_texture(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                  Hit hit) {
    if (m->type.x == T0_MATERIAL_EMISSIVE) {
        return surface_texture(scene, m, hit);
    }
    const t0_u32 texture = (t0_u32)m->emission.w;
    float2 uv;
    if (texture == 0u || !hit_uv(scene, hit, &uv)) {
        return float3_splat(1.0f);
    }
    return texture_bilinear(scene->texels, scene->textures[texture - 1u], uv.x, uv.y);
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

// Whether the type is one of rough_materials.h's (a GGX lobe).
T0_INLINE int material_is_microfacet(t0_u32 type) {
    return type >= T0_MATERIAL_CONDUCTOR && type <= T0_MATERIAL_ROUGH_GLASS;
}

// Any microfacet type in the scene.
#define T0_FEATURES_MICROFACET                                                                     \
    (T0_FEATURE_CONDUCTOR | T0_FEATURE_PLASTIC | T0_FEATURE_PRINCIPLED | T0_FEATURE_ROUGH_GLASS)

// The inputs of a hit's material (scatter.h): the texture, where the
// material has one, is the base colour's factor for the microfacet types.
// rm: the factors of the roughness and metallic textures at the hit
// (texture.h's hit_roughness_metallic; one where there are none).
T0_INLINE Surface make_surface(T0_GLOBAL const MaterialRecord* m, float3 texture, float2 rm,
                               int front) {
    Surface s;
    s.base = xyz(m->color) * texture;
    s.alpha = rm.x == 1.0f ? m->params.w : ggx_alpha(m->params.y * rm.x);
    s.metallic = m->color.w * rm.y;
    s.front = front;
    return s;
}

// The factor a hit's texture puts on the whole sample: the thesis' four
// take it so (bit for bit as before the microfacet types); those take it
// in their base colour instead (make_surface).
T0_INLINE float3 texture_outside(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                 float3 texture) {
    if (T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(m->type.x)) {
        return float3_splat(1.0f);
    }
    return texture;
}

// Whether the material picks between lobes with a number of its own
// (sampler.h's T0_DIM_LOBE): rough glass, plastic, principled.
T0_INLINE int material_draws_lobe(const SceneView* scene, T0_GLOBAL const MaterialRecord* m) {
    const t0_u32 type = m->type.x;
    return T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(type) &&
           type != T0_MATERIAL_CONDUCTOR;
}

// Whether next-event estimation samples lights at a hit on this material:
// diffuse, rough glossy and the microfacet surfaces; not emitters (paths
// end there), glass or mirror-like glossy (delta lobes that a light sample
// never lands in).
T0_INLINE int material_samples_lights(const SceneView* scene, T0_GLOBAL const MaterialRecord* m) {
    const t0_u32 type = m->type.x;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_DIFFUSE) && type == T0_MATERIAL_DIFFUSE) {
        return 1;
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_GLOSSY) && type == T0_MATERIAL_GLOSSY) {
        return glossy_cone_sin2(m) >= T0_GLOSSY_LIGHT_SAMPLING_MIN_SIN2;
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(type)) {
        return 1;
    }
    return 0;
}

// A microfacet material's f cos and density toward `direction`, in the
// frame of the facing normal.
T0_OUT_OF_LINE MaterialEval eval_microfacet(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                       float3 texture, float2 rm, int front,
                                       float3 incoming, float3 facing_normal,
                                       float3 direction) {
    const t0_u32 type = m->type.x;
    const Surface surface = make_surface(m, texture, rm, front);
    const Frame f = frame_from_normal(facing_normal);
    const float3 wo = frame_to_local(f, -incoming);
    const float3 wi = frame_to_local(f, direction);
    if (T0_HAS_FEATURE(scene, T0_FEATURE_CONDUCTOR) && type == T0_MATERIAL_CONDUCTOR) {
        return eval_conductor(m, surface, wo, wi);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_ROUGH_GLASS) && type == T0_MATERIAL_ROUGH_GLASS) {
        return eval_rough_glass(m, surface, wo, wi);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_PLASTIC) && type == T0_MATERIAL_PLASTIC) {
        return eval_two_lobe(m, surface, wo, wi);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_PRINCIPLED) && type == T0_MATERIAL_PRINCIPLED) {
        return eval_two_lobe(m, surface, wo, wi);
    }
    return eval_failed();
}

T0_OUT_OF_LINE ScatterSample scatter_microfacet(const SceneView* scene,
                                           T0_GLOBAL const MaterialRecord* m, float3 texture,
                                           float2 rm, int front, float3 incoming,
                                           float3 facing_normal, float2 u, float u_lobe) {
    const t0_u32 type = m->type.x;
    const Surface surface = make_surface(m, texture, rm, front);
    const Frame f = frame_from_normal(facing_normal);
    const float3 wo = frame_to_local(f, -incoming);
    ScatterSample s = scatter_failed();
    if (T0_HAS_FEATURE(scene, T0_FEATURE_CONDUCTOR) && type == T0_MATERIAL_CONDUCTOR) {
        s = scatter_conductor_local(m, surface, wo, u);
    } else if (T0_HAS_FEATURE(scene, T0_FEATURE_ROUGH_GLASS) && type == T0_MATERIAL_ROUGH_GLASS) {
        s = scatter_rough_glass_local(m, surface, wo, u, u_lobe);
    } else if (T0_HAS_FEATURE(scene, T0_FEATURE_PLASTIC) && type == T0_MATERIAL_PLASTIC) {
        s = scatter_two_lobe_local(m, surface, wo, u, u_lobe);
    } else if (T0_HAS_FEATURE(scene, T0_FEATURE_PRINCIPLED) && type == T0_MATERIAL_PRINCIPLED) {
        s = scatter_two_lobe_local(m, surface, wo, u, u_lobe);
    }
    s.direction = frame_to_world(f, s.direction);
    return s;
}

T0_INLINE MaterialEval eval_material(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                     float3 texture, float2 rm, int front, float3 incoming,
                                     float3 facing_normal, float3 direction) {
    const t0_u32 type = m->type.x;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_DIFFUSE) && type == T0_MATERIAL_DIFFUSE) {
        return eval_diffuse(m, facing_normal, direction);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURE_GLOSSY) && type == T0_MATERIAL_GLOSSY) {
        return eval_glossy(m, incoming, facing_normal, direction);
    }
    if (T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(type)) {
        return eval_microfacet(scene, m, texture, rm, front, incoming, facing_normal, direction);
    }
    return eval_failed();  // delta lobes and emitters
}

// texture is the hit's texture (one where none), rm its roughness and
// metallic factors, and front whether the ray arrived at the triangle's
// outer side: the microfacet types' inputs (make_surface). u picks the direction (glass: u.x reflection or
// refraction), u_lobe the lobe of the materials that draw one
// (material_draws_lobe).
T0_INLINE ScatterSample scatter_material(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                         float3 texture, float2 rm, int front,
                                         float3 incoming, float3 outward_normal,
                                         float3 facing_normal, float2 u, float u_lobe) {
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
    if (T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(type)) {
        return scatter_microfacet(scene, m, texture, rm, front, incoming, facing_normal, u,
                                  u_lobe);
    }
    return scatter_failed();  // emissive: a pure emitter ends the path
}

T0_NAMESPACE_END

#endif
