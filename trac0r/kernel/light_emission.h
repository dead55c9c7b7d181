// The lights as sources of light subpaths (bidirectional path tracing,
// bdpt.h): a point and a direction in which light leaves, and the
// densities of both, for every kind of light (pbrt-v4's SampleLe and
// PDF_Le). A light is picked by power from the light list's CDF.
// - An emitting triangle: a uniform point, a cosine-weighted direction on
//   its emitting side (a two-sided emitter picks a side with probability
//   1/2).
// - A point lamp: a uniform direction; a spot: uniform in its outer cone.
// - The environment and the sun: a direction towards the light as
//   next-event estimation samples it (a delta sun: its direction), and a
//   point uniform on the disc of the scene's bounding sphere that faces
//   it (SceneView.sphere), from which the light comes in parallel.
#ifndef TRAC0R_KERNEL_LIGHT_EMISSION_H
#define TRAC0R_KERNEL_LIGHT_EMISSION_H

#include "lamps.h"
#include "light_sampling.h"
#include "material.h"
#include "sampling.h"
#include "texture.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// Whether the light is a delta: a point or spot lamp, or a sun of angle 0.
T0_INLINE int light_is_delta(T0_GLOBAL const LightRecord* light) {
    const t0_u32 kind = light->ids.y;
    return kind == T0_LIGHT_POINT || kind == T0_LIGHT_SPOT ||
           (kind == T0_LIGHT_SUN && !(light->c.x > 0.0f));
}

// Whether an emitting triangle's material emits from its front only.
T0_INLINE int triangle_light_one_sided(const SceneView* scene,
                                       T0_GLOBAL const TriangleRecord* tri) {
    return T0_HAS_FEATURE(scene, T0_FEATURE_ONE_SIDED) &&
           material_one_sided(&scene->materials[tri->ids.x]);
}

// A uniform point of emitting triangle `triangle` (its barycentrics b1, b2
// from u, sample_triangle_barycentrics).
T0_INLINE float3 triangle_light_point(const SceneView* scene, t0_u32 triangle, float2 u, float* b1,
                                      float* b2) {
    T0_GLOBAL const TriangleRecord* tri = &scene->triangles[triangle];
    sample_triangle_barycentrics(u.x, u.y, b1, b2);
    const float3 v0 = xyz(tri->v0);
    return v0 + (xyz(tri->v1) - v0) * *b1 + (xyz(tri->v2) - v0) * *b2;
}

// The radiance emitting triangle `triangle` sends from the point of
// barycentrics (b1, b2): its material's emission times its texture there.
T0_INLINE float3 triangle_light_radiance(const SceneView* scene, t0_u32 triangle, float b1,
                                         float b2) {
    T0_GLOBAL const MaterialRecord* m = &scene->materials[scene->triangles[triangle].ids.x];
    float3 le = material_emission(m);
    if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
        Hit at;
        at.t = 0.0f;
        at.u = b1;
        at.v = b2;
        at.triangle = (int)triangle;
        le *= emission_texture(scene, m, at);
    }
    return le;
}

// The density per solid angle with which light leaves a light that is not
// distant in unit direction w from its point (on a triangle, its normal
// n): pbrt-v4's PDF_Le's pdfDir.
T0_INLINE float light_pdf_direction(const SceneView* scene, T0_GLOBAL const LightRecord* light,
                                    float3 w) {
    const t0_u32 kind = light->ids.y;
    if (kind == T0_LIGHT_POINT) {
        return 0.25f * T0_INV_PI;
    }
    if (kind == T0_LIGHT_SPOT) {
        const float cos_outer = light->a.w;
        return dot(w, xyz(light->c)) >= cos_outer ? 0.5f * T0_INV_PI / (1.0f - cos_outer) : 0.0f;
    }
    if (kind != T0_LIGHT_TRIANGLE) {
        return 0.0f;
    }
    T0_GLOBAL const TriangleRecord* tri = &scene->triangles[light->ids.x];
    const float c = dot(w, xyz(tri->normal));
    if (triangle_light_one_sided(scene, tri)) {
        return c > 0.0f ? c * T0_INV_PI : 0.0f;
    }
    return fabs(c) * 0.5f * T0_INV_PI;
}

// The density per solid angle with which the distant lights together send
// a light subpath from unit direction `towards` (towards the light): each
// light's pick times its own density; zero for a delta sun.
T0_INLINE float distant_light_density(const SceneView* scene, float3 towards) {
    float sum = 0.0f;
    for (t0_u32 i = 0u; i < scene->distant_count; ++i) {
        T0_GLOBAL const LightRecord* light = &scene->lights[i];
        if (T0_HAS_FEATURE(scene, T0_FEATURE_ENVIRONMENT) && light->ids.y == T0_LIGHT_ENVIRONMENT) {
            sum += light->cdf.y * environment_pdf(scene, light, towards);
        } else if (light->c.x > 0.0f && in_sun_disc(light, towards)) {
            sum += light->cdf.y / light->c.y;
        }
    }
    return sum;
}

// The density per area with which a light subpath from a distant light
// starts at a point of the disc facing it: one over the disc's area.
T0_INLINE float distant_disc_density(const SceneView* scene) {
    const float r = scene->sphere.w;
    return 1.0f / (T0_PI * r * r);
}

// Where a light subpath starts and where it goes first.
typedef struct EmissionSample {
    float3 position;      // on the light; for a distant light, on the disc
    float3 normal;        // a triangle's (outer) normal; zero for the others
    float3 direction;     // unit: the light's way
    float3 beta;          // Le |cos| / (pick pdf_position pdf_direction): the
                          // throughput of the subpath's first ray
    float pdf_origin;     // the origin's density: pick / area for a triangle,
                          // the pick for a point lamp, distant_light_density
    float pdf_direction;  // per solid angle; 1 for a delta direction
    t0_u32 light;         // its index in the light list
    float u;              // a triangle's barycentrics of the point
    float v;
    int ok;  // 0: no light left (an edge, a failed sample)
} EmissionSample;

T0_INLINE EmissionSample emission_failed(void) {
    EmissionSample e;
    e.position = float3_splat(0.0f);
    e.normal = float3_splat(0.0f);
    e.direction = make_float3(0.0f, 1.0f, 0.0f);
    e.beta = float3_splat(0.0f);
    e.pdf_origin = 0.0f;
    e.pdf_direction = 0.0f;
    e.light = 0u;
    e.u = 0.0f;
    e.v = 0.0f;
    e.ok = 0;
    return e;
}

// A point of the disc of radius r about `centre` facing unit direction
// `axis` (uniform: u.x the squared radius' share).
T0_INLINE float3 disc_point(float3 centre, float3 axis, float r, float2 u) {
    const Frame f = frame_from_normal(axis);
    const float radius = r * sqrt(u.x);
    const float2_cs turn = turn_cos_sin(u.y);
    return centre + f.tangent * (radius * turn.c) + f.bitangent * (radius * turn.s);
}

// A light subpath's start: u_pick picks the light, u_position the point
// (a triangle's, or the disc's), u_direction the direction.
T0_INLINE EmissionSample sample_emission(const SceneView* scene, float u_pick, float2 u_position,
                                         float2 u_direction) {
    EmissionSample e = emission_failed();
    if (scene->light_count == 0u) {
        return e;
    }
    e.light = pick_light(scene, u_pick);
    T0_GLOBAL const LightRecord* light = &scene->lights[e.light];
    const float pick = light->cdf.y;
    const t0_u32 kind = light->ids.y;
    if (!(pick > 0.0f)) {
        return e;
    }
    if (kind == T0_LIGHT_TRIANGLE) {
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[light->ids.x];
        e.position = triangle_light_point(scene, light->ids.x, u_position, &e.u, &e.v);
        e.normal = xyz(tri->normal);
        float3 side = e.normal;
        float side_share = 1.0f;
        float ux = u_direction.x;
        if (!triangle_light_one_sided(scene, tri)) {
            side_share = 0.5f;
            if (ux < 0.5f) {
                ux = 2.0f * ux;
            } else {
                ux = 2.0f * ux - 1.0f;
                side = -side;
            }
        }
        const DirectionSample d = sample_cosine_hemisphere(side, ux, u_direction.y);
        const float c = dot(d.direction, side);
        if (!(c > 0.0f)) {
            return e;
        }
        e.direction = d.direction;
        e.pdf_direction = side_share * c * T0_INV_PI;
        e.pdf_origin = light->cdf.z;
        const float3 le = triangle_light_radiance(scene, light->ids.x, e.u, e.v);
        e.beta = le * (c / (e.pdf_origin * e.pdf_direction));
    } else if (kind == T0_LIGHT_POINT || kind == T0_LIGHT_SPOT) {
        e.position = xyz(light->a);
        e.pdf_origin = pick;
        float3 intensity = xyz(light->b);
        if (kind == T0_LIGHT_POINT) {
            e.direction = sample_uniform_sphere(u_direction.x, u_direction.y).direction;
        } else {
            // Uniform in the outer cone: cos theta uniform in [cos_outer, 1].
            const float cos_outer = light->a.w;
            const float c = 1.0f - u_direction.x * (1.0f - cos_outer);
            const float s = sqrt(fmax(0.0f, 1.0f - c * c));
            const float2_cs turn = turn_cos_sin(u_direction.y);
            e.direction = normalize(frame_to_world(frame_from_normal(xyz(light->c)),
                                                   make_float3(s * turn.c, s * turn.s, c)));
            intensity *= spot_falloff(c, cos_outer, light->c.w);
        }
        e.pdf_direction = light_pdf_direction(scene, light, e.direction);
        if (!(e.pdf_direction > 0.0f)) {
            return e;
        }
        e.beta = intensity / (pick * e.pdf_direction);
    } else {
        const LightSample ls = sample_distant_light(scene, light, u_direction);
        const float pdf = ls.pdf > 0.0f ? ls.pdf : 1.0f;  // a delta sun: its direction
        if (kind == T0_LIGHT_ENVIRONMENT && !(ls.pdf > 0.0f)) {
            return e;
        }
        const float r = scene->sphere.w;
        e.position = disc_point(xyz(scene->sphere) + ls.direction * r, ls.direction, r, u_position);
        e.direction = -ls.direction;
        e.normal = ls.direction;  // towards the light (PathVertex's convention)
        e.pdf_direction = pdf;
        e.pdf_origin = distant_light_density(scene, ls.direction);
        e.beta = ls.radiance / (pick * distant_disc_density(scene) * pdf);
    }
    e.ok = e.beta.x > 0.0f || e.beta.y > 0.0f || e.beta.z > 0.0f;
    return e;
}

T0_NAMESPACE_END

#endif
