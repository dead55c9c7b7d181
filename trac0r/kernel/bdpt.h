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
// is normalised so). Its numbers (sampler.h), besides the camera subpath's
// own (the same dimensions as the path tracer's, T0_DIM(depth, ...) for
// its vertex `depth`, with s = 1 at that vertex drawing the light
// dimensions), come from a second sampler of the pixel, seeded apart:
//   T0_DIM_EMISSION_PICK, _POINT, _DIRECTION   the light, the point on it
//                     (or its disc) and the direction (1-D, 2-D, 2-D);
//   T0_DIM_LIGHT_SUBPATH(depth, T0_DIM_ROULETTE and T0_DIM_MATERIAL) and
//   T0_DIM_LIGHT_LOBE(depth)   its vertex `depth`'s scattering, as a
//                     camera vertex's;
//   T0_DIM_LIGHT_SUBPATH(depth, T0_DIM_LIGHT_PICK)   the point on the lens
//                     that its vertex `depth` is joined to (2-D).
#ifndef TRAC0R_KERNEL_BDPT_H
#define TRAC0R_KERNEL_BDPT_H

#include "bdpt_vertex.h"
#include "camera_importance.h"
#include "light_emission.h"
#include "light_sampling.h"
#include "splat.h"
#include "trace.h"

T0_NAMESPACE_BEGIN

#define T0_DIM_LIGHT_SUBPATH(depth, slot) ((1 << 22) + (depth)*T0_DIMS_PER_VERTEX + (slot))
#define T0_DIM_EMISSION_PICK ((1 << 22) - 3)
#define T0_DIM_EMISSION_POINT ((1 << 22) - 2)
#define T0_DIM_EMISSION_DIRECTION ((1 << 22) - 1)
#define T0_DIM_LIGHT_LOBE(depth) (-(1 << 21) - (depth))

// What the light subpath's sampler's seed differs from the camera's by.
#define T0_LIGHT_SUBPATH_SEED 0x9E3779B97F4A7C15ul

// Which strategies a sample adds: all, weighted by MIS (the renderer's),
// or one (s, t) alone and unweighted (the tests': each is an unbiased
// estimator of the paths it can make, pbrt-v4's way of checking them).
typedef struct BdptStrategies {
    int only_s;  // -1: all
    int only_t;
} BdptStrategies;

T0_INLINE BdptStrategies bdpt_all_strategies(void) {
    BdptStrategies b;
    b.only_s = -1;
    b.only_t = -1;
    return b;
}

T0_INLINE int bdpt_takes(BdptStrategies b, int s, int t) {
    return b.only_s < 0 || (b.only_s == s && b.only_t == t);
}

T0_INLINE int any3(float3 c) { return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f; }

// The triangle a vertex lies on (a surface's, an emitting triangle's), or -1.
T0_INLINE int vertex_triangle(const SceneView* scene, const PathVertex* v) {
    if (v->kind == T0_VERTEX_SURFACE) {
        return v->index;
    }
    if (v->kind == T0_VERTEX_LIGHT && !v->distant &&
        scene->lights[v->index].ids.y == T0_LIGHT_TRIANGLE) {
        return (int)scene->lights[v->index].ids.x;
    }
    return -1;
}

// Where a ray between v and a point in unit direction `toward` leaves v:
// off its triangle on that side, or the point itself.
T0_INLINE float3 vertex_ray_point(const SceneView* scene, const PathVertex* v, float3 toward) {
    const int triangle = vertex_triangle(scene, v);
    if (triangle < 0) {
        return v->p;
    }
    T0_GLOBAL const TriangleRecord* tri = &scene->triangles[triangle];
    const float3 side = dot(toward, v->ng) > 0.0f ? v->ng : -v->ng;
    return offset_ray_origin(v->p, side, hit_magnitude(tri, v->p));
}

// Whether nothing lies between vertices a and b (b may be distant).
T0_INLINE int vertices_see(const SceneView* scene, const PathVertex* a, const PathVertex* b) {
    const float3 w = vertex_direction(a, b);
    const float3 from = vertex_ray_point(scene, a, w);
    if (b->distant) {
        const Ray ray = make_ray(from, w);
        return !occluded(scene, &ray, T0_NO_HIT);
    }
    const float3 to = vertex_ray_point(scene, b, -w);
    const float3 d = to - from;
    const float len = length(d);
    if (!(len > 0.0f)) {
        return 0;
    }
    const Ray ray = make_ray(from, d / len);
    return !occluded(scene, &ray, len);
}

// ---- Subpaths ----------------------------------------------------------------

// Extends the subpath path[0 .. n-1] along `ray` (from path[n-1], whose
// sampling picked it with density pdf_dir per solid angle, or per area
// across the rays from a distant light) with throughput beta, to at most
// max_vertices vertices; returns the count. A camera subpath
// (adjoint 0) ends on a distant light where its ray leaves the scene; a
// light subpath (adjoint 1) carries light the other way, through the
// adjoint of the camera's integrand (bdpt_vertex.h).
T0_INLINE int bdpt_walk(const SceneView* scene, Ray ray, float3 beta, float pdf_dir,
                        PathVertex* path, int n, int max_vertices, int adjoint, Sampler* sampler) {
    const float reference = fmax(beta.x, fmax(beta.y, beta.z));
    for (int depth = 0; n < max_vertices; ++depth) {
        const Hit hit = intersect_scene(scene, &ray);
        PathVertex* prev = &path[n - 1];
        PathVertex* v = &path[n];
        v->beta = beta;
        v->arrival = ray.direction;
        v->pdf_rev = 0.0f;
        v->delta_light = 0;
        v->u = 0.0f;
        v->v = 0.0f;
        if (hit.triangle < 0) {
            if (!adjoint && scene->distant_count > 0u) {
                v->kind = T0_VERTEX_LIGHT;
                v->distant = 1;
                v->p = ray.origin;
                v->ng = ray.direction;
                v->ns = ray.direction;
                v->pdf_fwd = pdf_dir;
                v->delta = 0;
                v->index = 0;
                ++n;
            }
            break;
        }
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[hit.triangle];
        T0_GLOBAL const MaterialRecord* m = &scene->materials[tri->ids.x];
        const float3 ng = xyz(tri->normal);
        float3 ns = ng;
        if (T0_HAS_FEATURE(scene, T0_FEATURE_SMOOTH)) {
            ns = shading_normal(scene, hit, ray.direction, ng);
        }
        if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE) && m->maps.z != 0u) {
            ns = normal_mapped(scene, m, hit, ray.direction, ng, ns);
        }
        v->kind = T0_VERTEX_SURFACE;
        v->distant = 0;
        v->p = hit_position(tri, hit);
        v->ng = ng;
        v->ns = ns;
        v->u = hit.u;
        v->v = hit.v;
        v->index = hit.triangle;
        v->delta = m->type.x == T0_MATERIAL_GLASS ||
                   (m->type.x == T0_MATERIAL_GLOSSY &&
                    glossy_cone_sin2(m) < T0_GLOSSY_LIGHT_SAMPLING_MIN_SIN2);
        v->pdf_fwd = convert_density(scene, pdf_dir, prev, v);
        ++n;
        if (n >= max_vertices || m->type.x == T0_MATERIAL_EMISSIVE) {
            break;  // the last vertex it may have, or a pure emitter
        }
        float u_roulette;
        float2 u;
        float u_lobe = 0.0f;
        if (adjoint) {
            u_roulette = sample_1d(sampler, T0_DIM_LIGHT_SUBPATH(depth, T0_DIM_ROULETTE));
            u = sample_2d(sampler, T0_DIM_LIGHT_SUBPATH(depth, T0_DIM_MATERIAL));
            if (material_draws_lobe(scene, m)) {
                u_lobe = sample_1d(sampler, T0_DIM_LIGHT_LOBE(depth));
            }
        } else {
            u_roulette = sample_1d(sampler, T0_DIM(depth, T0_DIM_ROULETTE));
            u = sample_2d(sampler, T0_DIM(depth, T0_DIM_MATERIAL));
            if (material_draws_lobe(scene, m)) {
                u_lobe = sample_1d(sampler, T0_DIM_LOBE(depth));
            }
        }
        const int front = dot(ray.direction, ng) < 0.0f;
        const float3 facing = front ? ns : -ns;
        const float3 facing_geometric = front ? ng : -ng;
        const VertexMaterial vm = vertex_material(scene, v);
        const ScatterSample sc = scatter_material(scene, vm.m, vm.texture, vm.rm, front,
                                                  ray.direction, ns, facing, u, u_lobe);
        if (!any3(sc.weight) ||
            (dot(sc.direction, facing_geometric) > 0.0f) != (dot(sc.direction, facing) > 0.0f)) {
            break;
        }
        float3 weight = sc.weight * vm.tint;
        const float3 back = -ray.direction;  // towards prev
        float pdf_fwd_dir = 0.0f;
        float pdf_rev_dir = 0.0f;
        if (v->delta) {
            // Smooth glass is its own adjoint but for refraction's
            // radiance scale, which the camera's integrand leaves out
            // (rough_materials.h): light entering a denser medium is
            // spread over 1/eta^2 as much solid angle.
            if (adjoint && m->type.x == T0_MATERIAL_GLASS &&
                dot(sc.direction, facing_geometric) < 0.0f) {
                const float ior = m->params.z;
                weight *= front ? 1.0f / (ior * ior) : ior * ior;
            }
        } else {
            pdf_fwd_dir = sc.pdf;
            const MaterialEval other = vertex_eval(scene, v, -sc.direction, back);
            pdf_rev_dir = other.pdf;
            if (adjoint) {
                // The camera's f cos toward the light's side, at the
                // sampled direction's geometric cosine over the density
                // and the arriving ray's (bdpt_vertex.h).
                const float arriving = fabs(dot(ng, back));
                if (!(sc.pdf > 0.0f) || !(arriving > 0.0f)) {
                    break;
                }
                weight = other.f_cos * (fabs(dot(ng, sc.direction)) / (sc.pdf * arriving));
            }
        }
        prev->pdf_rev = convert_density(scene, pdf_rev_dir, v, prev);
        beta *= weight;
        // Russian roulette on the throughput against the subpath's first:
        // densities unchanged (the strategies' weights do not see it).
        const float q = fmin(1.0f, 2.0f * fmax(beta.x, fmax(beta.y, beta.z)) / reference);
        if (!survives_roulette(q, &beta, u_roulette)) {
            break;
        }
        pdf_dir = pdf_fwd_dir;
        const float3 side = dot(sc.direction, ng) > 0.0f ? ng : -ng;
        ray = make_ray(offset_ray_origin(v->p, side, hit_magnitude(tri, v->p)), sc.direction);
    }
    return n;
}

// The camera subpath from camera ray `ray` (begin_pixel's): the camera
// and up to max_depth vertices.
T0_INLINE int camera_subpath(const SceneView* scene, CameraRecord cam, Ray ray, int max_depth,
                             Sampler* sampler, PathVertex* path) {
    PathVertex* c = &path[0];
    c->kind = T0_VERTEX_CAMERA;
    c->p = ray.origin;
    c->ng = xyz(cam.forward);
    c->ns = c->ng;
    c->beta = float3_splat(1.0f);
    c->arrival = ray.direction;
    c->pdf_fwd = 1.0f;
    c->pdf_rev = 0.0f;
    c->u = 0.0f;
    c->v = 0.0f;
    c->delta = camera_is_orthographic(cam);  // a direction no light subpath can meet
    c->delta_light = 0;
    c->distant = 0;
    c->index = 0;
    const float pdf_dir = c->delta ? 0.0f : camera_pdf_direction(cam, c->p, ray.direction);
    return bdpt_walk(scene, ray, c->beta, pdf_dir, path, 1, max_depth + 1, 0, sampler);
}

// The light subpath: a light's vertex and up to max_depth - 1 more.
T0_INLINE int light_subpath(const SceneView* scene, int max_depth, Sampler* sampler,
                            PathVertex* path) {
    const float u_pick = sample_1d(sampler, T0_DIM_EMISSION_PICK);
    const float2 u_point = sample_2d(sampler, T0_DIM_EMISSION_POINT);
    const float2 u_direction = sample_2d(sampler, T0_DIM_EMISSION_DIRECTION);
    const EmissionSample e = sample_emission(scene, u_pick, u_point, u_direction);
    if (!e.ok) {
        return 0;
    }
    T0_GLOBAL const LightRecord* light = &scene->lights[e.light];
    PathVertex* l = &path[0];
    l->kind = T0_VERTEX_LIGHT;
    l->p = e.position;
    l->ng = e.normal;
    l->ns = e.normal;
    l->beta = e.beta;
    l->arrival = e.direction;
    l->pdf_fwd = e.pdf_origin;
    l->pdf_rev = 0.0f;
    l->u = e.u;
    l->v = e.v;
    l->delta = 0;
    l->delta_light = light_is_delta(light);
    l->distant = light_is_distant(light);
    l->index = (int)e.light;
    if (max_depth <= 1) {
        return 1;
    }
    const float3 from = vertex_ray_point(scene, l, e.direction);
    const float pdf = l->distant ? distant_disc_density(scene) : e.pdf_direction;
    return bdpt_walk(scene, make_ray(from, e.direction), e.beta, pdf, path, 1, max_depth, 1,
                     sampler);
}

// ---- MIS -----------------------------------------------------------------------

// One step of the weight's sum: (rev / fwd)^2, a zero density (a delta
// vertex's) counting as one (pbrt-v4's remap0), for the power heuristic.
T0_INLINE float mis_ratio(float rev, float fwd) {
    const float r = (rev != 0.0f ? rev : 1.0f) / (fwd != 0.0f ? fwd : 1.0f);
    return r * r;
}

// The weight of strategy (s, t): its density over the sum of all the
// strategies' that make the same path, each relative to the next, from
// the densities the vertices keep, with those of the joined vertices and
// their neighbours as the join makes them (pbrt-v4's MISWeight).
// `sampled` is the light vertex for s = 1, or the camera's for t = 1.
T0_INLINE float mis_weight(const SceneView* scene, CameraRecord cam, const PathVertex* camera,
                           const PathVertex* light, int s, int t, const PathVertex* sampled) {
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
    if (s > 0) {
        pt_rev = vertex_pdf(scene, cam, qs_minus, qs, pt);
    } else {
        pt_rev = vertex_pdf_light_origin(scene, pt);
    }
    if (pt_minus != 0) {
        if (s > 0) {
            pt_minus_rev = vertex_pdf(scene, cam, qs, pt, pt_minus);
        } else {
            T0_GLOBAL const LightRecord* l = pt->distant ? 0 : vertex_light(scene, pt);
            pt_minus_rev = vertex_pdf_light(scene, pt, l, pt_minus);
        }
    }
    if (qs != 0) {
        qs_rev = vertex_pdf(scene, cam, pt_minus, pt, qs);
    }
    if (qs_minus != 0) {
        qs_minus_rev = vertex_pdf(scene, cam, pt, qs, qs_minus);
    }
    float sum = 0.0f;
    float ri = 1.0f;
    for (int i = t - 1; i > 0; --i) {
        const float rev = i == t - 1 ? pt_rev : (i == t - 2 ? pt_minus_rev : camera[i].pdf_rev);
        ri *= mis_ratio(rev, camera[i].pdf_fwd);
        const int delta = i == t - 1 ? 0 : camera[i].delta;
        if (!delta && !camera[i - 1].delta) {
            sum += ri;
        }
    }
    ri = 1.0f;
    for (int i = s - 1; i >= 0; --i) {
        const PathVertex* v = i == s - 1 ? qs : &light[i];
        const float rev = i == s - 1 ? qs_rev : (i == s - 2 ? qs_minus_rev : light[i].pdf_rev);
        ri *= mis_ratio(rev, v->pdf_fwd);
        const int delta = i == s - 1 ? 0 : v->delta;
        const int delta_before =
            i > 0 ? light[i - 1].delta : (s == 1 ? sampled : light)->delta_light;
        if (!delta && !delta_before) {
            sum += ri;
        }
    }
    return 1.0f / (1.0f + sum);
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
    return weighted ? l * mis_weight(scene, cam, camera, light, 0, t, 0) : l;
}

// s = 1: a light sampled for camera vertex t - 1 (next-event estimation,
// with the numbers of the light dimensions of its depth).
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
    const t0_u32 index = pick_light(scene, u_pick);
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
    if (kind == T0_LIGHT_TRIANGLE) {
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[record->ids.x];
        q.p = triangle_light_point(scene, record->ids.x, u, &q.u, &q.v);
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
        pdf = record->cdf.z * d2 / fabs(c);
    } else if (kind == T0_LIGHT_POINT || kind == T0_LIGHT_SPOT) {
        const LightSample ls = sample_point_lamp(record, pt->p);
        q.p = xyz(record->a);
        direction = ls.direction;
        arriving = ls.radiance;
        pdf = record->cdf.y;
    } else {
        LightSample ls;
        if (T0_HAS_FEATURE(scene, T0_FEATURE_ENVIRONMENT) && kind == T0_LIGHT_ENVIRONMENT) {
            ls = sample_environment_light(scene, record, u);
        } else {
            ls = sample_sun(record, u);
        }
        if (kind == T0_LIGHT_ENVIRONMENT && !(ls.pdf > 0.0f)) {
            return float3_splat(0.0f);
        }
        q.p = pt->p;
        q.ng = ls.direction;
        direction = ls.direction;
        arriving = ls.radiance;
        pdf = record->cdf.y * (ls.pdf > 0.0f ? ls.pdf : 1.0f);
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
    q.pdf_fwd = vertex_pdf_light_origin(scene, &q);
    const float3 l = pt->beta * e.f_cos * q.beta;
    return weighted ? l * mis_weight(scene, cam, camera, light, 1, t, &q) : l;
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
    return weighted ? l * mis_weight(scene, cam, camera, light, s, t, 0) : l;
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
        l *= mis_weight(scene, cam, 0, light, s, 1, &c);
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
        if (bdpt_takes(which, s, 1)) {
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
