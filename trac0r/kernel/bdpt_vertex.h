// The vertices of bidirectional path tracing's subpaths (bdpt.h) and what
// is asked of them: the material's value and densities between two
// neighbours, and each vertex's densities per area for the MIS weights
// (Veach 1997, chapter 10; pbrt-v4's Vertex).
//
// The integrand the connections estimate is the one the path tracer's
// (trace.h) estimates, so that both converge to the same image: along a
// path from the camera x0, x1, ..., xk (a light), the product of
// - each surface vertex's f cos toward the light's side, its material's
//   evaluation with the ray from the camera's side as `incoming` and the
//   shading normal's cosine (vertex_eval, the path tracer's
//   eval_material), and
// - each edge's geometric cosine at its end on the light's side over the
//   squared distance,
// times the emitted radiance and the camera's importance. A camera
// subpath's throughput is the path tracer's; a light subpath's `beta` is
// pbrt's (per solid angle at its last vertex), so a connection divides by
// that vertex's geometric cosine toward the vertex it came from
// (light_beta_area).
#ifndef TRAC0R_KERNEL_BDPT_VERTEX_H
#define TRAC0R_KERNEL_BDPT_VERTEX_H

#include "camera_importance.h"
#include "light_emission.h"
#include "material.h"
#include "normal_map.h"
#include "texture.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// The longest path bidirectional path tracing takes, in vertices besides
// the camera (max_depth): its subpaths are arrays of this many.
#define T0_BDPT_MAX_DEPTH 64

#define T0_VERTEX_CAMERA 0
#define T0_VERTEX_LIGHT 1  // a light subpath's first vertex, or a sampled light
#define T0_VERTEX_SURFACE 2

typedef struct PathVertex {
    float3 p;         // the point (a distant light's: on its disc)
    float3 ng;        // the triangle's unit normal (its outer side); a distant
                      // light's: the unit direction towards it
    float3 ns;        // the shading normal, on the triangle's outer side
    float3 beta;      // the subpath's throughput at this vertex
    float3 arrival;   // the unit direction of the ray that reached the vertex
                      // along its subpath
    float pdf_fwd;    // the density per area with which its subpath reached it
    float pdf_rev;    // the same, had the other subpath reached it
    float nee_ratio;  // a light subpath's first vertex, a light sample's: the
                      // density per area with which a light sample (s = 1)
                      // from the next vertex picks it, over that of a light
                      // subpath's start (bdpt_mis.h, light_sample_ratio);
                      // 1 on any other vertex
    float u;          // the hit's barycentrics (textures)
    float v;
    int kind;         // T0_VERTEX_*
    int delta;        // a surface's delta lobe (glass, a mirror); the camera: an
                      // orthographic one's delta direction
    int delta_light;  // a light vertex: a delta light (light_is_delta)
    int distant;      // a light vertex: at infinity (the environment, a sun)
    int index;        // a surface: the triangle; a light: the light list's index
} PathVertex;

// Whether the vertex lies on a surface, where a density per area gets the
// cosine of the ray arriving: surfaces and emitting triangles.
T0_INLINE int vertex_on_surface(const SceneView* scene, const PathVertex* v) {
    if (v->kind == T0_VERTEX_SURFACE) {
        return 1;
    }
    return v->kind == T0_VERTEX_LIGHT && !v->distant &&
           scene->lights[v->index].ids.y == T0_LIGHT_TRIANGLE;
}

// The unit direction from vertex `from` to vertex `to` (to a distant light:
// towards it; from one: its light's way).
T0_INLINE float3 vertex_direction(const PathVertex* from, const PathVertex* to) {
    if (to->distant) {
        return to->ng;
    }
    if (from->distant) {
        return -from->ng;
    }
    return normalize(to->p - from->p);
}

// A density per solid angle at `from` as one per area at `to`: times the
// cosine at `to` (on a surface) over the squared distance; unchanged
// toward a distant light, whose vertices' densities are per solid angle.
T0_INLINE float convert_density(const SceneView* scene, float pdf, const PathVertex* from,
                                const PathVertex* to) {
    if (to->distant) {
        return pdf;
    }
    if (from->distant) {
        // Parallel light from a disc: the disc's density, per area across
        // the rays (distant_pdf_light's), at the cosine.
        return vertex_on_surface(scene, to) ? pdf * fabs(dot(to->ng, from->ng)) : pdf;
    }
    const float3 d = to->p - from->p;
    const float inv_d2 = 1.0f / dot(d, d);
    if (vertex_on_surface(scene, to)) {
        pdf *= fabs(dot(to->ng, d)) * sqrt(inv_d2);
    }
    return pdf * inv_d2;
}

// A surface vertex's material inputs, as trace_path_from makes them.
typedef struct VertexMaterial {
    T0_GLOBAL const MaterialRecord* m;
    float3 texture;
    float3 tint;
    float2 rm;
} VertexMaterial;

T0_INLINE Hit vertex_hit(const PathVertex* v) {
    Hit h;
    h.t = 0.0f;
    h.u = v->u;
    h.v = v->v;
    h.triangle = v->index;
    return h;
}

T0_INLINE VertexMaterial vertex_material(const SceneView* scene, const PathVertex* v) {
    VertexMaterial vm;
    vm.m = &scene->materials[scene->triangles[v->index].ids.x];
    vm.texture = float3_splat(1.0f);
    vm.tint = vm.texture;
    vm.rm = make_float2(1.0f, 1.0f);
    if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
        const Hit hit = vertex_hit(v);
        vm.texture = surface_texture(scene, vm.m, hit);
        vm.tint = texture_outside(scene, vm.m, vm.texture);
        if (T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(vm.m->type.x)) {
            vm.rm = hit_roughness_metallic(scene, vm.m, hit);
        }
    }
    return vm;
}

// The material of surface vertex v between a ray arriving along unit
// `incoming` (from the camera's side) and unit `direction` (toward the
// light's side): f cos (the shading normal's cosine, times the texture's
// tint) and the density with which its sampling, given `incoming`, picks
// `direction`; zero for a delta lobe, which no other direction finds.
T0_INLINE MaterialEval vertex_eval(const SceneView* scene, const PathVertex* v, float3 incoming,
                                   float3 direction) {
    if (v->kind != T0_VERTEX_SURFACE || v->delta) {
        return eval_failed();
    }
    const int front = dot(incoming, v->ng) < 0.0f;
    const float3 facing = front ? v->ns : -v->ns;
    const float3 facing_geometric = front ? v->ng : -v->ng;
    if ((dot(direction, facing_geometric) > 0.0f) != (dot(direction, facing) > 0.0f)) {
        return eval_failed();  // across the triangle from the shading normal's side
    }
    const VertexMaterial vm = vertex_material(scene, v);
    MaterialEval e =
        eval_material(scene, vm.m, vm.texture, vm.rm, front, incoming, facing, direction);
    e.f_cos *= vm.tint;
    return e;
}

// The density per area with which light vertex v (a light subpath's first
// vertex, or a camera subpath's vertex that found emission) sends light to
// vertex `to`: pbrt-v4's Vertex::PdfLight. `light` is its light record.
T0_INLINE float vertex_pdf_light(const SceneView* scene, const PathVertex* v,
                                 T0_GLOBAL const LightRecord* light, const PathVertex* to) {
    if (v->distant) {
        return convert_density(scene, distant_disc_density(scene), v, to);
    }
    if (light == 0) {
        return 0.0f;
    }
    const float3 w = normalize(to->p - v->p);
    return convert_density(scene, light_pdf_direction(scene, light, w), v, to);
}

// The light record of a light vertex, or of the emitter a camera subpath's
// surface vertex lies on (0 where the emitter is not in the light list);
// not for distant vertices.
T0_INLINE T0_GLOBAL const LightRecord* vertex_light(const SceneView* scene, const PathVertex* v) {
    if (v->kind == T0_VERTEX_LIGHT) {
        return &scene->lights[v->index];
    }
    const t0_u32 index = scene->triangles[v->index].ids.z;
    return index == T0_NO_LIGHT ? 0 : &scene->lights[index];
}

// The density with which a light subpath starts at light vertex v (per
// area, or for a distant light per solid angle of its direction), toward
// `to`: pbrt-v4's Vertex::PdfLightOrigin.
T0_INLINE float vertex_pdf_light_origin(const SceneView* scene, const PathVertex* v) {
    if (v->distant) {
        return distant_light_density(scene, v->ng);
    }
    T0_GLOBAL const LightRecord* light = vertex_light(scene, v);
    if (light == 0) {
        return 0.0f;
    }
    return light->ids.y == T0_LIGHT_TRIANGLE ? light->cdf.z : light->cdf.y;
}

// The density per area with which vertex `cur`, reached from `prev` (0 for
// the camera or a light), samples vertex `next`: pbrt-v4's Vertex::Pdf.
T0_INLINE float vertex_pdf(const SceneView* scene, CameraRecord cam, const PathVertex* prev,
                           const PathVertex* cur, const PathVertex* next) {
    if (cur->kind == T0_VERTEX_LIGHT) {
        T0_GLOBAL const LightRecord* light = cur->distant ? 0 : vertex_light(scene, cur);
        return vertex_pdf_light(scene, cur, light, next);
    }
    const float3 wn = vertex_direction(cur, next);
    float pdf = 0.0f;
    if (cur->kind == T0_VERTEX_CAMERA) {
        if (cur->delta) {
            return 0.0f;
        }
        pdf = camera_pdf_direction(cam, cur->p, wn);
    } else {
        // Sampled given the other side's ray: arriving from prev.
        pdf = vertex_eval(scene, cur, -vertex_direction(cur, prev), wn).pdf;
    }
    return convert_density(scene, pdf, cur, next);
}

T0_NAMESPACE_END

#endif
