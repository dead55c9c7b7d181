// Bidirectional path tracing (Veach 1997, chapter 10; pbrt-v4's BDPT
// integrator): each pixel's sample traces a subpath from the camera and
// one from a light, then joins every prefix of the one to every prefix of
// the other, each join (s light vertices, t camera vertices) a strategy,
// weighted by multiple importance sampling over all the strategies that
// could have made the same path (the power heuristic, computed from the
// densities each vertex keeps, in time linear in the path's length).
// - s = 0: the camera subpath finds emission by itself (the path tracer).
// - s = 1: a light sampled for the camera vertex (next-event estimation).
// - t = 1: a light subpath's vertex joined to the camera, splatted into
//   the pixel it lands in (splat.h): light tracing, which finds the
//   caustics that the other strategies miss.
// The path is at most max_depth vertices besides the camera, as the path
// tracer's (at most T0_BDPT_MAX_DEPTH).
//
// Each pixel traces one light subpath a frame, so a frame has as many
// light subpaths as pixels (the camera's importance, camera_importance.h,
// is normalised so); the subpaths and their sampler dimensions:
// bdpt_subpath.h; the weights: bdpt_mis.h.
#ifndef TRAC0R_KERNEL_BDPT_H
#define TRAC0R_KERNEL_BDPT_H

#include "bdpt_mis.h"
#include "bdpt_subpath.h"
#include "bdpt_vertex.h"
#include "camera_importance.h"
#include "light_emission.h"
#include "light_sampling.h"
#include "splat.h"

T0_NAMESPACE_BEGIN

// Which strategies a sample adds: all, weighted by MIS (the renderer's);
// those of paths of one length, weighted (the tests': their weights add
// up to one, so they make all the light of those paths); or one (s, t)
// alone and unweighted (the tests': each is an unbiased estimator of the
// paths it can make, pbrt-v4's way of checking them).
typedef struct BdptStrategies {
    int only_s;  // -1: all, weighted
    int only_t;
    int length;  // with only_s -1 and above 0: only paths of s + t vertices
} BdptStrategies;

T0_INLINE BdptStrategies bdpt_all_strategies(void) {
    BdptStrategies b;
    b.only_s = -1;
    b.only_t = -1;
    b.length = 0;
    return b;
}

T0_INLINE int bdpt_takes(BdptStrategies b, int s, int t) {
    if (b.only_s < 0) {
        return b.length <= 0 || s + t == b.length;
    }
    return b.only_s == s && b.only_t == t;
}

// ---- Strategies -------------------------------------------------------------

// A light subpath's throughput per area at its vertex v, as the
// connections' integrand takes it: over the geometric cosine of the ray
// that reached it (bdpt_vertex.h).
T0_INLINE float3 light_beta_area(const PathVertex* v) {
    const float c = fabs(dot(v->ng, v->arrival));
    return c > 0.0f ? v->beta / c : float3_splat(0.0f);
}

// s = 0: the emission camera vertex t - 1 found.
T0_INLINE float3 connect_emission(const SceneView* scene, CameraRecord cam,
                                  const PathVertex* camera, int t, const PathVertex* light,
                                  int weighted) {
    const PathVertex* pt = &camera[t - 1];
    float3 le;
    if (pt->distant) {
        le = escaped_radiance(scene, pt->ng, 0, 0.0f);
    } else {
        if (!T0_HAS_FEATURE(scene, T0_FEATURE_EMITTANCE)) {
            return float3_splat(0.0f);
        }
        T0_GLOBAL const MaterialRecord* m = &scene->materials[scene->triangles[pt->index].ids.x];
        le = material_emission_seen(scene, m, dot(pt->arrival, pt->ng) < 0.0f);
        if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE) && any3(le)) {
            le *= emission_texture(scene, m, vertex_hit(pt));
        }
    }
    if (!any3(le)) {
        return float3_splat(0.0f);
    }
    const float3 l = pt->beta * le;
    return weighted ? l * mis_weight(scene, cam, camera, light, 0, t, 0, -1.0f, -1.0f) : l;
}

// s = 1: a light sampled for camera vertex t - 1 as next-event estimation
// samples it (the light picked by choose_light, with the light tree where
// the scene has one), with the numbers of the light dimensions of its
// depth.
T0_INLINE float3 connect_light_sample(const SceneView* scene, CameraRecord cam,
                                      const PathVertex* camera, int t, const PathVertex* light,
                                      Sampler* sampler, int weighted) {
    const PathVertex* pt = &camera[t - 1];
    if (pt->kind != T0_VERTEX_SURFACE || pt->delta || scene->light_count == 0u) {
        return float3_splat(0.0f);
    }
    const int depth = t - 2;
    const float u_pick = sample_1d(sampler, T0_DIM(depth, T0_DIM_LIGHT_PICK));
    const float2 u = sample_2d(sampler, T0_DIM(depth, T0_DIM_LIGHT_POINT));
    const float u_tree = T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE)
                             ? sample_1d(sampler, T0_DIM_LIGHT_TREE(depth))
                             : 0.0f;
    // (The tree's importance takes the triangle's normal here, as the
    // weights take it at every vertex: the shading normal can depend on
    // the side a subpath arrives from.)
    const LightChoice choice = choose_light(scene, pt->p, pt->ng, u_pick, u_tree);
    if (!(choice.pick > 0.0f)) {
        return float3_splat(0.0f);
    }
    const t0_u32 index = choice.light;
    T0_GLOBAL const LightRecord* record = &scene->lights[index];
    const t0_u32 kind = record->ids.y;
    PathVertex q;
    q.kind = T0_VERTEX_LIGHT;
    q.index = (int)index;
    q.delta = 0;
    q.delta_light = light_is_delta(record);
    q.distant = light_is_distant(record);
    q.pdf_rev = 0.0f;
    q.u = 0.0f;
    q.v = 0.0f;
    q.ns = float3_splat(0.0f);
    q.ng = float3_splat(0.0f);
    float3 arriving;
    float pdf;  // per solid angle at pt, with the pick; 1 x the pick for a delta
    float3 direction;
    // Over a light subpath's start, whose pick is by power
    // (light_sample_ratio).
    q.nee_ratio = choice.pick / record->cdf.y;
    if (kind == T0_LIGHT_TRIANGLE) {
        // By solid angle where the triangle looks large, as next-event
        // estimation picks it (sample_light), else by area.
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[record->ids.x];
        const SphericalTriangle seen = emitter_seen_from(tri, pt->p);
        const int by_solid_angle = sample_by_solid_angle(seen.solid_angle);
        if (by_solid_angle) {
            const float3 v0 = xyz(tri->v0);
            if (!sample_spherical_triangle(seen, pt->p, v0, xyz(tri->v1), xyz(tri->v2), u, &q.u,
                                           &q.v)) {
                return float3_splat(0.0f);
            }
            q.p = v0 + (xyz(tri->v1) - v0) * q.u + (xyz(tri->v2) - v0) * q.v;
        } else {
            q.p = triangle_light_point(scene, record->ids.x, u, &q.u, &q.v);
        }
        q.ng = xyz(tri->normal);
        const float3 d = q.p - pt->p;
        const float d2 = dot(d, d);
        if (!(d2 > 0.0f)) {
            return float3_splat(0.0f);
        }
        direction = d / sqrt(d2);
        const float c = dot(direction, q.ng);
        if (!(fabs(c) > 0.0f) || (triangle_light_one_sided(scene, tri) && !(c < 0.0f))) {
            return float3_splat(0.0f);
        }
        arriving = triangle_light_radiance(scene, record->ids.x, q.u, q.v);
        if (by_solid_angle) {
            pdf = choice.pick / seen.solid_angle;
            q.nee_ratio *= light_sample_area_ratio(tri, fabs(c), d2, seen.solid_angle);
        } else {
            pdf = choice.pick_per_area * d2 / fabs(c);
        }
    } else if (kind == T0_LIGHT_POINT || kind == T0_LIGHT_SPOT) {
        const LightSample ls = sample_point_lamp(record, pt->p);
        q.p = xyz(record->a);
        direction = ls.direction;
        arriving = ls.radiance;
        pdf = choice.pick;
    } else {
        const LightSample ls = sample_distant_light(scene, record, u);
        if (kind == T0_LIGHT_ENVIRONMENT && !(ls.pdf > 0.0f)) {
            return float3_splat(0.0f);
        }
        q.p = pt->p;
        q.ng = ls.direction;
        direction = ls.direction;
        arriving = ls.radiance;
        pdf = choice.pick * (ls.pdf > 0.0f ? ls.pdf : 1.0f);
    }
    q.arrival = -direction;
    if (!any3(arriving) || !(pdf > 0.0f)) {
        return float3_splat(0.0f);
    }
    const MaterialEval e = vertex_eval(scene, pt, pt->arrival, direction);
    if (!any3(e.f_cos) || !vertices_see(scene, pt, &q)) {
        return float3_splat(0.0f);
    }
    q.beta = arriving / pdf;
    q.pdf_fwd = vertex_pdf_light_origin(scene, &q) * q.nee_ratio;
    const float3 l = pt->beta * e.f_cos * q.beta;
    // The join's own evaluation gives the light vertex's reverse density.
    const float q_rev = convert_density(scene, e.pdf, pt, &q);
    return weighted ? l * mis_weight(scene, cam, camera, light, 1, t, &q, q_rev, -1.0f) : l;
}

// s >= 2, t >= 2: light vertex s - 1 joined to camera vertex t - 1.
T0_INLINE float3 connect_vertices(const SceneView* scene, CameraRecord cam,
                                  const PathVertex* camera, int t, const PathVertex* light, int s,
                                  int weighted) {
    const PathVertex* pt = &camera[t - 1];
    const PathVertex* qs = &light[s - 1];
    if (pt->kind != T0_VERTEX_SURFACE || pt->delta || qs->kind != T0_VERTEX_SURFACE || qs->delta) {
        return float3_splat(0.0f);
    }
    const float3 d = qs->p - pt->p;
    const float d2 = dot(d, d);
    if (!(d2 > 0.0f)) {
        return float3_splat(0.0f);
    }
    const float3 w = d / sqrt(d2);
    const MaterialEval at_camera = vertex_eval(scene, pt, pt->arrival, w);
    if (!any3(at_camera.f_cos)) {
        return float3_splat(0.0f);
    }
    const MaterialEval at_light = vertex_eval(scene, qs, w, -qs->arrival);
    const float3 l = pt->beta * at_camera.f_cos * at_light.f_cos * light_beta_area(qs) *
                     (fabs(dot(qs->ng, w)) / d2);
    if (!any3(l) || !vertices_see(scene, pt, qs)) {
        return float3_splat(0.0f);
    }
    if (!weighted) {
        return l;
    }
    // The join's two evaluations give the light side's reverse densities.
    const float qs_rev = convert_density(scene, at_camera.pdf, pt, qs);
    const float qs_minus_rev = convert_density(scene, at_light.pdf, qs, &light[s - 2]);
    return l * mis_weight(scene, cam, camera, light, s, t, 0, qs_rev, qs_minus_rev);
}

// t = 1: light vertex s - 1 (s >= 2) joined to a point of the camera's
// lens, added to the pixel it lands in.
T0_INLINE void connect_camera(const SceneView* scene, CameraRecord cam, const PathVertex* light,
                              int s, Sampler* sampler, int weighted, T0_GLOBAL t0_i64* splats) {
    const PathVertex* qs = &light[s - 1];
    if (qs->kind != T0_VERTEX_SURFACE || qs->delta || camera_is_orthographic(cam)) {
        return;
    }
    float2 u = make_float2(0.0f, 0.0f);
    if (cam.extent.z > 0.0f) {
        u = sample_2d(sampler, T0_DIM_LIGHT_SUBPATH(s - 2, T0_DIM_LIGHT_PICK));
    }
    PathVertex c;
    c.kind = T0_VERTEX_CAMERA;
    c.p = camera_lens_point(cam, u);
    c.ng = xyz(cam.forward);
    c.ns = c.ng;
    c.beta = float3_splat(1.0f);
    c.arrival = c.ng;
    c.pdf_fwd = 1.0f;
    c.pdf_rev = 0.0f;
    c.nee_ratio = 1.0f;
    c.u = 0.0f;
    c.v = 0.0f;
    c.delta = 0;
    c.delta_light = 0;
    c.distant = 0;
    c.index = 0;
    float2 raster;
    const float cos_theta = camera_raster(cam, c.p, qs->p, &raster);
    const int pixel = cos_theta > 0.0f ? camera_pixel(cam, raster) : -1;
    if (pixel < 0) {
        return;
    }
    const float3 d = c.p - qs->p;
    const float d2 = dot(d, d);
    const float3 w = d / sqrt(d2);  // towards the camera
    const MaterialEval at_light = vertex_eval(scene, qs, -w, -qs->arrival);
    const float importance = 1.0f / (camera_film_area(cam) * cos_theta * cos_theta * cos_theta);
    float3 l = at_light.f_cos * light_beta_area(qs) * (fabs(dot(qs->ng, w)) / d2 * importance);
    if (!any3(l) || !vertices_see(scene, qs, &c)) {
        return;
    }
    if (weighted) {
        const float qs_minus_rev = convert_density(scene, at_light.pdf, qs, &light[s - 2]);
        l *= mis_weight(scene, cam, 0, light, s, 1, &c, -1.0f, qs_minus_rev);
    }
    splat_add(splats, (t0_u32)pixel, l);
}

// ---- A pixel's sample ----------------------------------------------------------

// One sample of pixel `pixel` in frame `frame`: its light subpath's joins
// to the camera (t = 1) added to the splat image, and every other
// strategy's light written to frame_radiance[pixel]. bdpt_merge adds the
// two once every pixel's sample is done.
T0_INLINE void bdpt_sample(const SceneView* scene, CameraRecord cam, t0_u32 pixel, t0_u64 seed,
                           t0_u32 frame, int max_depth, BdptStrategies which,
                           T0_GLOBAL float4* frame_radiance, T0_GLOBAL t0_i64* splats) {
    const int depth =
        max_depth < 1 ? 1 : (max_depth > T0_BDPT_MAX_DEPTH ? T0_BDPT_MAX_DEPTH : max_depth);
    const int sobol = T0_HAS_FEATURE(scene, T0_FEATURE_SOBOL);
    const int weighted = which.only_s < 0;
    PathVertex light[T0_BDPT_MAX_DEPTH];
    PathVertex camera[T0_BDPT_MAX_DEPTH + 1];
    Sampler light_sampler;
    sampler_start(&light_sampler, sobol, seed ^ T0_LIGHT_SUBPATH_SEED, pixel, frame);
    const int nl = scene->light_count > 0u ? light_subpath(scene, depth, &light_sampler, light) : 0;
    for (int s = 2; s <= nl; ++s) {
        if (bdpt_takes(which, s, 1) && !(weighted && bdpt_left_out(s, 1))) {
            connect_camera(scene, cam, light, s, &light_sampler, weighted, splats);
        }
    }
    PixelSample ps;
    begin_pixel(scene, cam, pixel, seed, frame, &ps);
    const int nc = camera_subpath(scene, cam, ps.ray, depth, &ps.sampler, camera);
    float3 sum = float3_splat(0.0f);
    for (int t = 2; t <= nc; ++t) {
        for (int s = 0; s + t - 1 <= depth; ++s) {
            if (s > 1 && s > nl) {
                break;
            }
            if (!bdpt_takes(which, s, t)) {
                continue;
            }
            if (s == 0) {
                sum += connect_emission(scene, cam, camera, t, light, weighted);
            } else if (s == 1) {
                sum += connect_light_sample(scene, cam, camera, t, light, &ps.sampler, weighted);
            } else {
                sum += connect_vertices(scene, cam, camera, t, light, s, weighted);
            }
        }
    }
    frame_radiance[pixel] = make_float4(sum.x, sum.y, sum.z, 0.0f);
}

// Pixel `pixel`'s sample of the frame, its own light and what the light
// subpaths splatted into it, accumulated; its splat sums cleared for the
// next frame.
T0_INLINE void bdpt_merge(T0_GLOBAL AccumPixel* accum, T0_GLOBAL const float4* frame_radiance,
                          T0_GLOBAL t0_i64* splats, t0_u32 pixel) {
    accumulate_sample(&accum[pixel], xyz(frame_radiance[pixel]) + splat_value(splats, pixel));
    T0_GLOBAL t0_i64* p = splats + 4u * pixel;
    p[0] = 0;
    p[1] = 0;
    p[2] = 0;
}

T0_NAMESPACE_END

#endif
