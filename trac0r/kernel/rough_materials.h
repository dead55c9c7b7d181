// The microfacet materials: conductor, rough glass, plastic and glTF's
// principled metallic-roughness BRDF, each as an evaluation (f cos and the
// density its sampling has) and a sample, in the local frame of the
// normal that faces the incoming ray (wo.z > 0; microfacet.h).
//
// No energy compensation for multiple scattering between microfacets:
// single scattering only, as pbrt-v4 and Mitsuba 3's rough plugins, so a
// rough white metal reflects a little less than all (test_rough_materials
// computes how much). Refraction carries no 1/eta^2 radiance factor, as
// the thesis' smooth glass: it cancels on the way out of a closed object.
#ifndef TRAC0R_KERNEL_ROUGH_MATERIALS_H
#define TRAC0R_KERNEL_ROUGH_MATERIALS_H

#include "microfacet.h"
#include "sampling.h"
#include "scatter.h"
#include "types.h"

T0_NAMESPACE_BEGIN

T0_INLINE float mean3(float3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

// wo mirrored about the microfacet normal mn.
T0_INLINE float3 reflect_about(float3 wo, float3 mn) { return mn * (2.0f * dot(wo, mn)) - wo; }

T0_INLINE MaterialEval make_eval(float3 f_cos, float pdf) {
    MaterialEval e;
    e.f_cos = f_cos;
    e.pdf = pdf;
    return e;
}

// ---- Conductor --------------------------------------------------------------

// A named metal's complex index (type.w) times the colour, or Schlick's
// Fresnel with the colour as F0.
T0_INLINE float3 conductor_fresnel(T0_GLOBAL const MaterialRecord* m, Surface s, float cos_i) {
    if (m->type.w != 0u) {
        return s.base * fresnel_conductor(cos_i, xyz(m->eta), xyz(m->k));
    }
    return fresnel_schlick(s.base, cos_i);
}

T0_INLINE MaterialEval eval_conductor(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo,
                                      float3 wi) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) {
        return eval_failed();
    }
    const float3 mn = normalize(wo + wi);
    const float d = ggx_d(s.alpha, mn);
    const float3 f = conductor_fresnel(m, s, dot(wo, mn));
    return make_eval(f * (d * ggx_g2(s.alpha, wo, wi) / (4.0f * wo.z)),
                     ggx_reflection_pdf(s.alpha, wo, mn));
}

T0_INLINE ScatterSample scatter_conductor_local(T0_GLOBAL const MaterialRecord* m, Surface s,
                                                float3 wo, float2 u) {
    if (!(wo.z > 0.0f)) {
        return scatter_failed();
    }
    const float3 mn = ggx_sample_visible(s.alpha, wo, u);
    const float3 wi = reflect_about(wo, mn);
    const float pdf = ggx_reflection_pdf(s.alpha, wo, mn);
    if (!(wi.z > 0.0f) || !(pdf > 0.0f)) {
        return scatter_failed();
    }
    ScatterSample r;
    r.direction = wi;
    r.weight =
        conductor_fresnel(m, s, dot(wo, mn)) * (ggx_g2(s.alpha, wo, wi) / ggx_g1(s.alpha, wo));
    r.pdf = pdf;
    r.is_delta = 0;
    return r;
}

// ---- Rough glass (Walter et al. 2007) ---------------------------------------

// eta_i / eta_t for a ray arriving on the side `front` says.
T0_INLINE float glass_eta(T0_GLOBAL const MaterialRecord* m, Surface s) {
    return s.front ? 1.0f / m->params.z : m->params.z;
}

// Reflection (wi above) and refraction (wi below), each with its Fresnel
// share; refraction tinted by the colour.
T0_INLINE MaterialEval eval_rough_glass(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo,
                                        float3 wi) {
    if (!(wo.z > 0.0f) || wi.z == 0.0f) {
        return eval_failed();
    }
    const float eta = glass_eta(m, s);
    if (wi.z > 0.0f) {
        const float3 mn = normalize(wo + wi);
        const float c = dot(wo, mn);
        const float f = fresnel_dielectric(c, eta);
        const float d = ggx_d(s.alpha, mn);
        return make_eval(float3_splat(f * d * ggx_g2(s.alpha, wo, wi) / (4.0f * wo.z)),
                         f * ggx_reflection_pdf(s.alpha, wo, mn));
    }
    // The generalised half vector: eta_i wo + eta_t wi, on the normal's side.
    float3 h = -(wo * eta + wi);
    const float h2 = dot(h, h);
    if (!(h2 > 0.0f)) {
        return eval_failed();
    }
    h = h / sqrt(h2);
    if (h.z < 0.0f) {
        h = -h;
    }
    const float c = dot(wo, h);
    const float ci = dot(wi, h);
    if (!(c > 0.0f) || !(ci < 0.0f)) {
        return eval_failed();  // the microfacet faces away from one of them
    }
    const float f = fresnel_dielectric(c, eta);
    // (wi.h + eta wo.h)^2 is |eta wo + wi|^2: the square before the
    // normalisation, free of the sum's cancellation.
    const float denom = h2;
    if (!(f < 1.0f)) {
        return eval_failed();
    }
    const float jacobian = -ci / denom;  // |dh/dwi|
    const float d = ggx_d(s.alpha, h);
    const float f_cos = (1.0f - f) * d * ggx_g2(s.alpha, wo, wi) * c * jacobian / wo.z;
    return make_eval(s.base * f_cos, (1.0f - f) * ggx_visible_pdf(s.alpha, wo, h) * jacobian);
}

// A visible microfacet normal, then reflection or refraction about it with
// the Fresnel probability (u_lobe chooses); the weight is G2 / G1 either
// way (times the colour through).
T0_INLINE ScatterSample scatter_rough_glass_local(T0_GLOBAL const MaterialRecord* m, Surface s,
                                                  float3 wo, float2 u, float u_lobe) {
    if (!(wo.z > 0.0f)) {
        return scatter_failed();
    }
    const float eta = glass_eta(m, s);
    const float3 mn = ggx_sample_visible(s.alpha, wo, u);
    const float c = dot(wo, mn);
    const float f = fresnel_dielectric(c, eta);
    ScatterSample r;
    r.is_delta = 0;
    if (u_lobe < f) {
        r.direction = reflect_about(wo, mn);
        if (!(r.direction.z > 0.0f)) {
            return scatter_failed();
        }
        r.pdf = f * ggx_reflection_pdf(s.alpha, wo, mn);
        r.weight = float3_splat(ggx_g2(s.alpha, wo, r.direction) / ggx_g1(s.alpha, wo));
    } else {
        const float cos2_t = refracted_cos2(c, eta);
        if (!(cos2_t > 0.0f)) {
            return scatter_failed();
        }
        r.direction = normalize(wo * (-eta) + mn * (eta * c - sqrt(cos2_t)));
        const float ci = dot(r.direction, mn);
        const float denom = (ci + eta * c) * (ci + eta * c);
        if (!(r.direction.z < 0.0f) || !(denom > 0.0f)) {
            return scatter_failed();
        }
        r.pdf = (1.0f - f) * ggx_visible_pdf(s.alpha, wo, mn) * (-ci / denom);
        r.weight = s.base * (ggx_g2(s.alpha, wo, r.direction) / ggx_g1(s.alpha, wo));
    }
    if (!(r.pdf > 0.0f)) {
        return scatter_failed();
    }
    return r;
}

// ---- Two lobes: a diffuse one and a GGX reflection ----------------------------

// Plastic (Mitsuba 3's roughplastic with the smooth coat's transmittance):
// the coat's GGX reflection with dielectric Fresnel, plus the colour as a
// Lambertian base seen through the coat twice,
// colour (1 - F(cos_o)) (1 - F(cos_i)) / (pi ior^2 (1 - F_dr,internal)),
// whose scale eta.w the host computes (packed_scene.cpp).
T0_INLINE float3 plastic_f_cos(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo, float3 wi,
                               float* spec_pdf) {
    const float eta = 1.0f / m->params.z;
    const float3 mn = normalize(wo + wi);
    const float d = ggx_d(s.alpha, mn);
    const float spec =
        fresnel_dielectric(dot(wo, mn), eta) * d * ggx_g2(s.alpha, wo, wi) / (4.0f * wo.z);
    const float through =
        (1.0f - fresnel_dielectric(wo.z, eta)) * (1.0f - fresnel_dielectric(wi.z, eta));
    *spec_pdf = ggx_reflection_pdf(s.alpha, wo, mn);
    return float3_splat(spec) + s.base * (through * m->eta.w * T0_INV_PI * wi.z);
}

// The probability of sampling the GGX lobe rather than the diffuse one:
// the coat's reflectance against what the base sends back, at wo.
T0_INLINE float plastic_specular_share(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo) {
    const float f = fresnel_dielectric(wo.z, 1.0f / m->params.z);
    const float diffuse = (1.0f - f) * mean3(s.base);
    return f + diffuse > 0.0f ? f / (f + diffuse) : 1.0f;
}

// glTF 2.0, Appendix B: mix(dielectric, metal, metallic), where the
// dielectric is fresnel_mix(ior, specular; Lambert(base), V D) and the
// metal conductor_fresnel(base, V D), all with Schlick's Fresnel at the
// half vector; V D = G2 D / (4 |n.l| |n.v|).
T0_INLINE float3 principled_f_cos(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo,
                                  float3 wi, float* spec_pdf) {
    const float3 mn = normalize(wo + wi);
    const float w = schlick_weight(dot(wo, mn));
    const float ior = m->params.z;
    const float f0 = fmin((ior - 1.0f) * (ior - 1.0f) / ((ior + 1.0f) * (ior + 1.0f)), 1.0f);
    const float specular = m->eta.x;
    const float fr = f0 + (1.0f - f0) * w;
    const float vd_cos = ggx_d(s.alpha, mn) * ggx_g2(s.alpha, wo, wi) / (4.0f * wo.z);
    const float3 dielectric =
        s.base * ((1.0f - specular * fr) * T0_INV_PI * wi.z) + float3_splat(specular * fr * vd_cos);
    const float3 metal = (s.base + (float3_splat(1.0f) - s.base) * w) * vd_cos;
    *spec_pdf = ggx_reflection_pdf(s.alpha, wo, mn);
    return dielectric * (1.0f - s.metallic) + metal * s.metallic;
}

T0_INLINE float principled_specular_share(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo) {
    const float ior = m->params.z;
    const float f0 = (ior - 1.0f) * (ior - 1.0f) / ((ior + 1.0f) * (ior + 1.0f));
    const float fr = m->eta.x * (f0 + (1.0f - f0) * schlick_weight(wo.z));
    const float spec = s.metallic + (1.0f - s.metallic) * fr;
    const float diffuse = (1.0f - s.metallic) * (1.0f - fr) * mean3(s.base);
    return spec + diffuse > 0.0f ? spec / (spec + diffuse) : 1.0f;
}

T0_INLINE float3 two_lobe_f_cos(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo, float3 wi,
                                float* spec_pdf) {
    if (m->type.x == T0_MATERIAL_PLASTIC) {
        return plastic_f_cos(m, s, wo, wi, spec_pdf);
    }
    return principled_f_cos(m, s, wo, wi, spec_pdf);
}

T0_INLINE float two_lobe_specular_share(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo) {
    if (m->type.x == T0_MATERIAL_PLASTIC) {
        return plastic_specular_share(m, s, wo);
    }
    return principled_specular_share(m, s, wo);
}

T0_INLINE MaterialEval eval_two_lobe(T0_GLOBAL const MaterialRecord* m, Surface s, float3 wo,
                                     float3 wi) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) {
        return eval_failed();
    }
    float spec_pdf = 0.0f;
    const float3 f_cos = two_lobe_f_cos(m, s, wo, wi, &spec_pdf);
    const float p = two_lobe_specular_share(m, s, wo);
    return make_eval(f_cos, p * spec_pdf + (1.0f - p) * wi.z * T0_INV_PI);
}

// The GGX lobe with the specular share's probability (u_lobe chooses),
// else the cosine; the weight is the whole f cos over the mixture's
// density.
T0_INLINE ScatterSample scatter_two_lobe_local(T0_GLOBAL const MaterialRecord* m, Surface s,
                                               float3 wo, float2 u, float u_lobe) {
    if (!(wo.z > 0.0f)) {
        return scatter_failed();
    }
    const float p = two_lobe_specular_share(m, s, wo);
    float3 wi;
    if (u_lobe < p) {
        wi = reflect_about(wo, ggx_sample_visible(s.alpha, wo, u));
    } else {
        wi = sample_cosine_hemisphere(make_float3(0.0f, 0.0f, 1.0f), u.x, u.y).direction;
    }
    if (!(wi.z > 0.0f)) {
        return scatter_failed();
    }
    const MaterialEval e = eval_two_lobe(m, s, wo, wi);
    if (!(e.pdf > 0.0f)) {
        return scatter_failed();
    }
    ScatterSample r;
    r.direction = wi;
    r.weight = e.f_cos / e.pdf;
    r.pdf = e.pdf;
    r.is_delta = 0;
    return r;
}

T0_NAMESPACE_END

#endif
