// Bidirectional path tracing's subpaths (bdpt.h): the random walk that
// makes both, the camera's from its ray, and a light's from a light
// picked by power, and whether two of their vertices see each other.
//
// A light subpath's numbers (sampler.h), besides the camera subpath's
// own (the same dimensions as the path tracer's, T0_DIM(depth, ...) for
// its vertex `depth`, with s = 1 at that vertex drawing the light
// dimensions, T0_DIM_LIGHT_TREE(depth) among them where the scene has a
// light tree), come from a second sampler of the pixel, seeded apart:
//   T0_DIM_EMISSION_PICK, _POINT, _DIRECTION   the light, the point on it
//                     (or its disc) and the direction (1-D, 2-D, 2-D);
//   T0_DIM_LIGHT_SUBPATH(depth, T0_DIM_ROULETTE and T0_DIM_MATERIAL) and
//   T0_DIM_LIGHT_LOBE(depth)   its vertex `depth`'s scattering, as a
//                     camera vertex's;
//   T0_DIM_LIGHT_SUBPATH(depth, T0_DIM_LIGHT_PICK)   the point on the lens
//                     that its vertex `depth` is joined to (2-D).
#ifndef TRAC0R_KERNEL_BDPT_SUBPATH_H
#define TRAC0R_KERNEL_BDPT_SUBPATH_H

#include "bdpt_mis.h"
#include "bdpt_vertex.h"
#include "camera_importance.h"
#include "light_emission.h"
#include "light_sampling.h"
#include "trace.h"

T0_NAMESPACE_BEGIN

#define T0_DIM_LIGHT_SUBPATH(depth, slot) ((1 << 22) + (depth)*T0_DIMS_PER_VERTEX + (slot))
#define T0_DIM_EMISSION_PICK ((1 << 22) - 3)
#define T0_DIM_EMISSION_POINT ((1 << 22) - 2)
#define T0_DIM_EMISSION_DIRECTION ((1 << 22) - 1)
#define T0_DIM_LIGHT_LOBE(depth) (-(1 << 21) - (depth))

// What the light subpath's sampler's seed differs from the camera's by.
#define T0_LIGHT_SUBPATH_SEED 0x9E3779B97F4A7C15ul

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
    // What a light subpath's refractions scaled its throughput by (1/eta^2
    // into glass, eta^2 out): undone for the roulette, so that a subpath
    // inside glass is not ended for a factor its way out restores (pbrt's
    // etaScale).
    float eta_scale = 1.0f;
    for (int depth = 0; n < max_vertices; ++depth) {
        const Hit hit = intersect_scene(scene, &ray);
        PathVertex* prev = &path[n - 1];
        PathVertex* v = &path[n];
        v->beta = beta;
        v->arrival = ray.direction;
        v->pdf_rev = 0.0f;
        v->nee_ratio = 1.0f;
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
        if (adjoint && (m->type.x == T0_MATERIAL_GLASS || m->type.x == T0_MATERIAL_ROUGH_GLASS) &&
            dot(sc.direction, facing_geometric) < 0.0f) {
            // Light entering a denser medium is spread over 1/eta^2 as much
            // solid angle: smooth glass is its own adjoint but for this
            // scale, which the camera's integrand leaves out
            // (rough_materials.h); rough glass's evaluation below has it.
            const float ior = m->params.z;
            const float scale = front ? 1.0f / (ior * ior) : ior * ior;
            if (v->delta) {
                weight *= scale;
            }
            eta_scale /= scale;
        }
        if (!v->delta) {
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
        // Russian roulette once the throughput falls below the subpath's
        // first: densities unchanged (the strategies' weights do not see
        // it).
        const float q = fmin(1.0f, fmax(beta.x, fmax(beta.y, beta.z)) * eta_scale *
                                       (adjoint ? 1.0f : 2.0f) / reference);
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
    c->nee_ratio = 1.0f;
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
    l->nee_ratio = 1.0f;
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
    const int n =
        bdpt_walk(scene, make_ray(from, e.direction), e.beta, pdf, path, 1, max_depth, 1, sampler);
    if (n > 1 && !path[1].delta) {  // (no light sample is taken at a delta vertex)
        l->nee_ratio = light_sample_ratio(scene, l, path[1].p, path[1].ng);
    }
    return n;
}

T0_NAMESPACE_END

#endif
