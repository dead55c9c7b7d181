// Bidirectional path tracing's multiple importance sampling (bdpt.h): a
// strategy's weight among all those that make the same path, from the
// densities its vertices keep (Veach 1997, section 10.2; pbrt-v4's
// MISWeight), with the power heuristic.
#ifndef TRAC0R_KERNEL_BDPT_MIS_H
#define TRAC0R_KERNEL_BDPT_MIS_H

#include "bdpt_vertex.h"
#include "light_sampling.h"

T0_NAMESPACE_BEGIN

// One step of the weight's sum: (rev / fwd)^2, a zero density (a delta
// vertex's) counting as one (pbrt-v4's remap0), for the power heuristic.
T0_INLINE float mis_ratio(float rev, float fwd) {
    const float r = (rev != 0.0f ? rev : 1.0f) / (fwd != 0.0f ? fwd : 1.0f);
    return r * r;
}

// The running product of the ratios, held finite: squared densities span
// twice float's exponents, and an infinite product times a ratio that
// underflowed to zero would be a NaN (a weight of zero is what a product
// that large means).
T0_INLINE float mis_product(float ri, float ratio) { return fmin(ri * ratio, 3.0e38f); }

// Light tracing's direct light (s = 2, t = 1) takes no share of the
// weights: the camera's own hits and the light samples (s = 0 and 1 with
// t = 3 and 2), weighted as the path tracer weighs them, make that light
// (docs/bdpt.md, "Direct light"). mis_weight leaves it out of the sums,
// bdpt_sample does not trace it.
T0_INLINE int bdpt_left_out(int s, int t) { return s == 2 && t == 1; }

// The density per area with which a light sample picks a point of an
// emitting triangle by solid angle omega, seen at squared distance d2 and
// cosine cos_light to the triangle, over that of a light subpath's start
// (uniform over the triangle's area), the pick of the light aside.
T0_INLINE float light_sample_area_ratio(T0_GLOBAL const TriangleRecord* tri, float cos_light,
                                        float d2, float omega) {
    return 0.5f * tri->normal.w * cos_light / (omega * d2);
}

// A light sample (s = 1, connect_light_sample) picks the light as
// next-event estimation does (choose_light: with the light tree where
// the scene has one, else by power, as a light subpath's start), and a
// point on an emitting triangle by solid angle where the triangle looks
// large from `from` (emitter_seen_from), else by area, as a light subpath
// starts. Its density per area at light vertex lv, seen from `from` with
// normal from_normal, over the light subpath's start (1 for a distant
// light).
T0_INLINE float light_sample_ratio(const SceneView* scene, const PathVertex* lv, float3 from,
                                   float3 from_normal) {
    if (lv->distant) {
        return 1.0f;
    }
    T0_GLOBAL const LightRecord* light = vertex_light(scene, lv);
    if (light == 0) {
        return 1.0f;
    }
    float ratio = 1.0f;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE)) {
        ratio = light_pick_pmf(scene, light, from, from_normal) / light->cdf.y;
    }
    if (light->ids.y != T0_LIGHT_TRIANGLE) {
        return ratio;
    }
    T0_GLOBAL const TriangleRecord* tri = &scene->triangles[light->ids.x];
    const float omega = emitter_seen_from(tri, from).solid_angle;
    if (!sample_by_solid_angle(omega)) {
        return ratio;
    }
    const float3 d = lv->p - from;
    const float d2 = dot(d, d);
    const float cos_light = fabs(dot(d, xyz(tri->normal))) / sqrt(d2);
    return ratio * light_sample_area_ratio(tri, cos_light, d2, omega);
}

// The weight of strategy (s, t): its density over the sum of all the
// strategies' that make the same path, each relative to the next, from
// the densities the vertices keep, with those of the joined vertices and
// their neighbours as the join makes them (pbrt-v4's MISWeight).
// `sampled` is the light vertex for s = 1, or the camera's for t = 1.
// known_qs_rev and known_qs_minus_rev are the reverse densities of the
// light's joined vertex and the one before it where the caller has them
// (from the material evaluations of the join itself), else negative.
// The densities of strategy s = 1 are those of its light sample
// (light_sample_ratio); strategies bdpt_left_out are left out of the sum.
T0_INLINE float mis_weight(const SceneView* scene, CameraRecord cam, const PathVertex* camera,
                           const PathVertex* light, int s, int t, const PathVertex* sampled,
                           float known_qs_rev, float known_qs_minus_rev) {
    if (s + t == 2) {
        return 1.0f;
    }
    const PathVertex* qs = s > 0 ? (s == 1 ? sampled : &light[s - 1]) : 0;
    const PathVertex* pt = t == 1 ? sampled : &camera[t - 1];
    const PathVertex* qs_minus = s > 1 ? &light[s - 2] : 0;
    const PathVertex* pt_minus = t > 1 ? &camera[t - 2] : 0;
    float pt_rev;
    float pt_minus_rev = 0.0f;
    float qs_rev = 0.0f;
    float qs_minus_rev = 0.0f;
    // (For t = 1 the camera's own densities, and for t = 2 pt_minus's,
    // take no part: the sum has no strategy t = 0.)
    if (t == 1) {
        pt_rev = 0.0f;
    } else if (s > 0) {
        pt_rev = vertex_pdf(scene, cam, qs_minus, qs, pt);
    } else {
        pt_rev = vertex_pdf_light_origin(scene, pt);
    }
    if (t > 2) {
        if (s > 0) {
            pt_minus_rev = vertex_pdf(scene, cam, qs, pt, pt_minus);
        } else {
            T0_GLOBAL const LightRecord* l = pt->distant ? 0 : vertex_light(scene, pt);
            pt_minus_rev = vertex_pdf_light(scene, pt, l, pt_minus);
        }
    }
    if (qs != 0) {
        qs_rev = known_qs_rev >= 0.0f ? known_qs_rev : vertex_pdf(scene, cam, pt_minus, pt, qs);
    }
    if (qs_minus != 0) {
        qs_minus_rev = known_qs_minus_rev >= 0.0f ? known_qs_minus_rev
                                                  : vertex_pdf(scene, cam, pt, qs, qs_minus);
    }
    // Where strategy s = 1 makes the path, the squared ratio of the
    // densities with which it and a light subpath's start pick the light
    // vertex (R = nee_ratio): for s = 0 and s >= 2, R^2 (zero where s = 1
    // cannot pick that point), on the term of s = 1 alone; for s = 1 itself, 1 / R^2, on the terms
    // of s >= 2 (its own light vertex's pdf_fwd is already the sample's).
    float sample_ratio = 1.0f;
    if (s == 1) {
        sample_ratio = mis_ratio(1.0f, sampled->nee_ratio);
    } else if (s == 0 && pt_minus != 0 && !pt_minus->delta &&
               T0_HAS_FEATURE(scene, T0_FEATURE_EMITTANCE)) {
        const float r = light_sample_ratio(scene, pt, pt_minus->p, pt_minus->ng);
        sample_ratio = mis_product(r, r);
    } else if (s >= 2) {
        sample_ratio = mis_product(light[0].nee_ratio, light[0].nee_ratio);
    }
    float sum = 0.0f;
    float ri = s == 1 ? sample_ratio : 1.0f;
    for (int i = t - 1; i > 0; --i) {
        const float rev = i == t - 1 ? pt_rev : (i == t - 2 ? pt_minus_rev : camera[i].pdf_rev);
        ri = mis_product(ri, mis_ratio(rev, camera[i].pdf_fwd));
        const int delta = i == t - 1 ? 0 : camera[i].delta;
        if (!delta && !camera[i - 1].delta && !bdpt_left_out(s + t - i, i)) {
            sum += s == 0 && i == t - 1 ? mis_product(ri, sample_ratio) : ri;
        }
    }
    ri = 1.0f;
    for (int i = s - 1; i >= 0; --i) {
        const PathVertex* v = i == s - 1 ? qs : &light[i];
        const float rev = i == s - 1 ? qs_rev : (i == s - 2 ? qs_minus_rev : light[i].pdf_rev);
        ri = mis_product(ri, mis_ratio(rev, v->pdf_fwd));
        const int delta = i == s - 1 ? 0 : v->delta;
        const int delta_before =
            i > 0 ? light[i - 1].delta : (s == 1 ? sampled : light)->delta_light;
        if (!delta && !delta_before) {
            sum += i == 1 ? mis_product(ri, sample_ratio) : ri;
        }
    }
    return 1.0f / (1.0f + sum);
}

T0_NAMESPACE_END

#endif
