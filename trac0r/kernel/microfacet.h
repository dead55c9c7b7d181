// The GGX (Trowbridge-Reitz) microfacet model, isotropic, in a local
// frame whose z axis is the surface normal: its distribution of normals,
// Smith's height-correlated masking-shadowing, the sampling of visible
// normals (Dupuy and Benyoub 2023, "Sampling Visible GGX Normals with
// Spherical Caps"), and the Fresnel terms the materials put on it.
//
// Roughness is glTF's and Disney's: alpha = roughness^2, held at least
// T0_MIN_ALPHA so that a "roughness 0" lobe stays a finite function that
// light sampling and MIS can evaluate (a mirror to the eye).
#ifndef TRAC0R_KERNEL_MICROFACET_H
#define TRAC0R_KERNEL_MICROFACET_H

#include "sampling.h"
#include "types.h"

T0_NAMESPACE_BEGIN

#define T0_MIN_ALPHA 1e-3f

T0_INLINE float ggx_alpha(float roughness) { return fmax(roughness * roughness, T0_MIN_ALPHA); }

// D(m): the density of microfacet normals m per unit projected area
// (integrates to one against m.z over the hemisphere).
T0_INLINE float ggx_d(float alpha, float3 m) {
    if (!(m.z > 0.0f)) {
        return 0.0f;
    }
    const float a2 = alpha * alpha;
    const float t = (m.x * m.x + m.y * m.y) / a2 + m.z * m.z;
    return 1.0f / (T0_PI * a2 * t * t);
}

// Smith's Lambda for a direction w: (sqrt(1 + alpha^2 tan^2) - 1) / 2.
T0_INLINE float ggx_lambda(float alpha, float3 w) {
    const float z2 = w.z * w.z;
    if (!(z2 > 0.0f)) {
        return 1e30f;
    }
    const float tan2 = (w.x * w.x + w.y * w.y) / z2;
    return 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

// Masking of one direction, and masking-shadowing of a pair, height
// correlated (Heitz 2014): 1 / (1 + Lambda(o) + Lambda(i)).
T0_INLINE float ggx_g1(float alpha, float3 w) { return 1.0f / (1.0f + ggx_lambda(alpha, w)); }

T0_INLINE float ggx_g2(float alpha, float3 wo, float3 wi) {
    return 1.0f / (1.0f + ggx_lambda(alpha, wo) + ggx_lambda(alpha, wi));
}

// A normal m visible from wo (wo.z > 0), with density
// G1(wo) max(0, wo.m) D(m) / wo.z (ggx_visible_pdf): the spherical-cap
// form, which needs no frame about wo.
T0_INLINE float3 ggx_sample_visible(float alpha, float3 wo, float2 u) {
    const float3 wo_std = normalize(make_float3(wo.x * alpha, wo.y * alpha, wo.z));
    const float2_cs turn = turn_cos_sin(u.x);
    const float z = (1.0f - u.y) * (1.0f + wo_std.z) - wo_std.z;
    const float sin_theta = sqrt(fmin(fmax(1.0f - z * z, 0.0f), 1.0f));
    const float3 m_std =
        make_float3(sin_theta * turn.c + wo_std.x, sin_theta * turn.s + wo_std.y, z + wo_std.z);
    return normalize(make_float3(m_std.x * alpha, m_std.y * alpha, fmax(m_std.z, 0.0f)));
}

T0_INLINE float ggx_visible_pdf(float alpha, float3 wo, float3 m) {
    const float wo_m = dot(wo, m);
    if (!(wo.z > 0.0f) || !(wo_m > 0.0f)) {
        return 0.0f;
    }
    return ggx_g1(alpha, wo) * wo_m * ggx_d(alpha, m) / wo.z;
}

// The density over directions of reflecting wo about a visible normal:
// the normal's density times |dm/dwi| = 1 / (4 wo.m).
T0_INLINE float ggx_reflection_pdf(float alpha, float3 wo, float3 m) {
    const float wo_m = dot(wo, m);
    if (!(wo_m > 0.0f)) {
        return 0.0f;
    }
    return ggx_visible_pdf(alpha, wo, m) / (4.0f * wo_m);
}

// Schlick's approximation: f0 + (1 - f0)(1 - cos)^5.
T0_INLINE float schlick_weight(float cos_theta) {
    const float c = 1.0f - fmin(fmax(cos_theta, 0.0f), 1.0f);
    const float c2 = c * c;
    return c2 * c2 * c;
}

T0_INLINE float3 fresnel_schlick(float3 f0, float cos_theta) {
    const float w = schlick_weight(cos_theta);
    return f0 + (float3_splat(1.0f) - f0) * w;
}

// Unpolarised reflectance of a conductor of complex index eta + i k, one
// channel (the closed form of Mitsuba 3's fresnel_conductor).
T0_INLINE float fresnel_conductor_channel(float cos_i, float eta, float k) {
    const float c2 = fmin(fmax(cos_i * cos_i, 0.0f), 1.0f);
    const float s2 = 1.0f - c2;
    const float t1 = eta * eta - k * k - s2;
    const float a2_b2 = sqrt(fmax(t1 * t1 + 4.0f * eta * eta * k * k, 0.0f));
    const float a = sqrt(fmax(0.5f * (a2_b2 + t1), 0.0f));
    const float term1 = a2_b2 + c2;
    const float term2 = 2.0f * sqrt(c2) * a;
    const float rs = (term1 - term2) / fmax(term1 + term2, 1e-30f);
    const float term3 = a2_b2 * c2 + s2 * s2;
    const float term4 = term2 * s2;
    const float rp = rs * (term3 - term4) / fmax(term3 + term4, 1e-30f);
    return fmin(fmax(0.5f * (rs + rp), 0.0f), 1.0f);
}

T0_INLINE float3 fresnel_conductor(float cos_i, float3 eta, float3 k) {
    return make_float3(fresnel_conductor_channel(cos_i, eta.x, k.x),
                       fresnel_conductor_channel(cos_i, eta.y, k.y),
                       fresnel_conductor_channel(cos_i, eta.z, k.z));
}

// A direction in the frame of f (local z = f.normal), and back.
T0_INLINE float3 frame_to_local(Frame f, float3 w) {
    return make_float3(dot(w, f.tangent), dot(w, f.bitangent), dot(w, f.normal));
}

T0_NAMESPACE_END

#endif
