// The camera, the trace loop and one pixel's sample: the whole per-pixel
// work of a frame, shared by the OpenMP backend and the OpenCL program.
#ifndef TRAC0R_KERNEL_TRACE_H
#define TRAC0R_KERNEL_TRACE_H

#include "accumulate.h"
#include "bundle.h"
#include "light_sampling.h"
#include "material.h"
#include "normal_map.h"
#include "ray.h"
#include "ray_offset.h"
#include "sampler.h"
#include "texture.h"
#include "traverse.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// The point of the image plane at distance one along forward that pixel
// (x, y) (row 0 at the top) shows at sub-pixel position (jitter_x,
// jitter_y) in [0, 1)^2, relative to the camera: forward component 1. For
// an orthographic camera, the offset of the ray's origin from the
// camera's position, plus forward.
T0_INLINE float3 camera_plane_point(CameraRecord cam, float x, float y, float jitter_x,
                                    float jitter_y) {
    const float width = (float)cam.size.x;
    const float height = (float)cam.size.y;
    const float sx = (2.0f * (x + jitter_x) / width - 1.0f) * cam.extent.x;
    const float sy = (1.0f - 2.0f * (y + jitter_y) / height) * cam.extent.y;
    return xyz(cam.forward) + xyz(cam.right) * sx + xyz(cam.up) * sy;
}

// A primary ray of the pinhole through pixel (x, y) at (jitter_x, jitter_y).
T0_INLINE Ray pinhole_ray(CameraRecord cam, float x, float y, float jitter_x, float jitter_y) {
    return make_ray(xyz(cam.position),
                    normalize(camera_plane_point(cam, x, y, jitter_x, jitter_y)));
}

// A primary ray of an orthographic camera: along forward from pixel (x, y)'s
// point (at (jitter_x, jitter_y)) of the image plane through the camera's
// position.
T0_INLINE Ray orthographic_ray(CameraRecord cam, float x, float y, float jitter_x, float jitter_y) {
    const float3 d = camera_plane_point(cam, x, y, jitter_x, jitter_y);
    return make_ray(xyz(cam.position) + (d - xyz(cam.forward)), xyz(cam.forward));
}

// The camera's primary ray through pixel (x, y) at (jitter_x, jitter_y),
// without a lens: a pinhole's or an orthographic camera's.
T0_INLINE Ray camera_ray(CameraRecord cam, float x, float y, float jitter_x, float jitter_y) {
    return camera_is_orthographic(cam) ? orthographic_ray(cam, x, y, jitter_x, jitter_y)
                                       : pinhole_ray(cam, x, y, jitter_x, jitter_y);
}

// A thin lens (pbrt's): the ray from a point on the aperture through the
// point where the pinhole ray of the same pixel position meets the plane in
// focus, cam.extent.w along forward; so what lies on that plane is sharp,
// and a point at depth z blurs to a disc of radius
// aperture * |z - focus| / (z * focus) on the image plane at distance one.
// `lens` in [0, 1)^2 picks the aperture point (polar: uniform on the disc).
// An orthographic camera's lens is centred on each pixel's point of the
// image plane and focuses its parallel ray (pbrt's OrthographicCamera).
T0_INLINE Ray camera_lens_ray(CameraRecord cam, float x, float y, float jitter_x, float jitter_y,
                              float2 lens) {
    const float3 d = camera_plane_point(cam, x, y, jitter_x, jitter_y);
    const float r = cam.extent.z * sqrt(lens.x);
    const float2_cs turn = turn_cos_sin(lens.y);
    const float3 on_lens = xyz(cam.right) * (r * turn.c) + xyz(cam.up) * (r * turn.s);
    if (camera_is_orthographic(cam)) {
        const float3 centre = xyz(cam.position) + (d - xyz(cam.forward));
        return make_ray(centre + on_lens, normalize(xyz(cam.forward) * cam.extent.w - on_lens));
    }
    return make_ray(xyz(cam.position) + on_lens, normalize(d * cam.extent.w - on_lens));
}

// The thesis' rule, 1 - 1/(max_depth - depth), caps paths at max_depth
// vertices; taking the minimum with the throughput's largest component also
// ends paths that can no longer carry much light. Unbiased either way: a
// survivor's throughput is divided by the probability.
T0_INLINE float continuation_probability(int depth, int max_depth, float3 throughput) {
    const float by_depth = 1.0f - 1.0f / (float)(max_depth - depth);
    const float by_throughput = fmax(throughput.x, fmax(throughput.y, throughput.z));
    return fmin(by_depth, by_throughput);
}

// With next-event estimation every vertex adds a light sample of low
// variance, so a path is worth more the longer it goes on: roulette starts
// only once the throughput has fallen below 1/2 (the rule above with the
// throughput doubled). On cornell_diffuse.json, thresholds of 1, 1/2, 1/3,
// 1/4 and 1/8 gave 4.2, 5.3, 5.3, 5.2 and 4.9 times the naive integrator's
// efficiency (variance ratio over cost ratio; docs/noise.md, "Next-event
// estimation").
#define T0_NEE_ROULETTE_THRESHOLD 0.5f

T0_INLINE float nee_continuation_probability(int depth, int max_depth, float3 throughput) {
    return continuation_probability(depth, max_depth, throughput / T0_NEE_ROULETTE_THRESHOLD);
}

// Russian roulette: whether the path goes on, with probability q (u is
// uniform in [0, 1)); a survivor's throughput is divided by q.
T0_INLINE int survives_roulette(float q, float3* throughput, float u) {
    if (!(u < q)) {
        return 0;
    }
    *throughput /= q;
    return 1;
}

// The shading normal of a hit, on the same side of the triangle as its
// geometric normal: with T0_FEATURE_SMOOTH, the triangle's vertex normals
// interpolated at the hit's barycentrics, where it has them; else, or where
// they cancel, the geometric normal itself. A hit whose incoming ray is
// on one side of the triangle but on the other of the shading normal would
// be shaded from behind: it is shaded flat. The geometric normal still
// decides which side a ray is on and where it leaves from, so no ray
// passes through a surface.
T0_INLINE float3 shading_normal(const SceneView* scene, Hit hit, float3 incoming,
                                float3 geometric_normal) {
    if (!T0_HAS_FEATURE(scene, T0_FEATURE_SMOOTH)) {
        return geometric_normal;
    }
    T0_GLOBAL const VertexNormals* vn = &scene->normals[hit.triangle];
    if (!(vn->n0.w > 0.0f)) {
        return geometric_normal;
    }
    const float3 n =
        xyz(vn->n0) * (1.0f - hit.u - hit.v) + xyz(vn->n1) * hit.u + xyz(vn->n2) * hit.v;
    const float length2 = dot(n, n);
    if (!(length2 > 1e-12f)) {
        return geometric_normal;
    }
    float3 unit = n / sqrt(length2);
    if (dot(unit, geometric_normal) < 0.0f) {
        unit = -unit;
    }
    if ((dot(incoming, unit) < 0.0f) != (dot(incoming, geometric_normal) < 0.0f)) {
        return geometric_normal;
    }
    return unit;
}

// On a GPU (T0_SHADOW_RAY_LAST), a vertex's light sample's shadow ray is
// traced last, once the vertex is shaded, as the path goes on or ends: what
// the shading needed is then no longer held in registers across the
// traversal (docs/gpu.md). Its light still counts before the next vertex's
// emission, as it does when traced straight after sampling (the CPU's
// order, where an occluded sample's MIS weight is never computed): the same
// sums, for a finite throughput (the CPU adds an occluded sample's zero).
T0_INLINE void add_light_last(const SceneView* scene, const ShadowedLight* light,
                              float3* radiance) {
    if (T0_SHADOW_RAY_LAST && shadow_ray_clear(scene, light)) {
        *radiance += light->sent;
    }
}

// One path from the camera; returns its radiance estimate. With next-event
// estimation (T0_FEATURE_NEE), each diffuse or rough glossy hit also samples
// a light; emission that the next scattered ray finds is then weighted by
// MIS. Camera rays and rays after a mirror or glass bounce count emission
// in full: nothing else could have found it.
// trace_path_from starts from the camera ray's hit, found by the caller.
// Vertex `depth` draws its numbers from the dimensions T0_DIM(depth, ...).
T0_INLINE float3 trace_path_from(const SceneView* scene, Ray ray, Hit first, int max_depth,
                                 Sampler* sampler) {
    float3 radiance = float3_splat(0.0f);
    float3 throughput = float3_splat(1.0f);
    int lights_sampled = 0;    // whether the vertex this ray leaves sampled a light
    float scatter_pdf = 0.0f;  // the density with which that vertex picked this ray
    // That vertex's position (the point a triangle's solid angle was seen
    // from) and, with the light tree, its normal (its pick depended on both).
    float3 sampled_from = float3_splat(0.0f);
    float3 sampled_normal = float3_splat(0.0f);
    Hit hit = first;
    for (int depth = 0; depth < max_depth; ++depth) {
        // Intersect: the nearest triangle, or the distant lights (the
        // environment, the sun's disc), else the black background.
        if (depth > 0) {
            hit = intersect_scene(scene, &ray);
        }
        if (hit.triangle < 0) {
            if (T0_HAS_FEATURE(scene, T0_FEATURE_ENVIRONMENT) ||
                T0_HAS_FEATURE(scene, T0_FEATURE_LAMPS)) {
                radiance += throughput *
                            escaped_radiance(scene, ray.direction, lights_sampled, scatter_pdf);
            }
            break;
        }
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[hit.triangle];
        T0_GLOBAL const MaterialRecord* m = &scene->materials[tri->ids.x];
        const float3 geometric_normal = xyz(tri->normal);
        // Two-sided surfaces: both normals turned to face the incoming ray.
        const int front = dot(ray.direction, geometric_normal) < 0.0f;
        const float3 facing_geometric = front ? geometric_normal : -geometric_normal;
        float3 shading = geometric_normal;  // on the triangle's outer side
        float3 facing_normal = facing_geometric;
        if (T0_HAS_FEATURE(scene, T0_FEATURE_SMOOTH)) {
            shading = shading_normal(scene, hit, ray.direction, geometric_normal);
            facing_normal = front ? shading : -shading;
        }
        if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE) && m->maps.z != 0u) {
            shading = normal_mapped(scene, m, hit, ray.direction, geometric_normal, shading);
            facing_normal = front ? shading : -shading;
        }

        // Emit.
        if (T0_HAS_FEATURE(scene, T0_FEATURE_EMITTANCE)) {
            float3 emitted = throughput * material_emission_seen(scene, m, front);
            if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
                emitted *= emission_texture(scene, m, hit);
            }
            if (T0_HAS_FEATURE(scene, T0_FEATURE_NEE) && lights_sampled &&
                tri->ids.z != T0_NO_LIGHT) {
                emitted *= power_heuristic(scatter_pdf,
                                           light_pdf_solid_angle(scene, tri, ray.direction, hit.t,
                                                                 sampled_from, sampled_normal));
            }
            radiance += emitted;
        }
        if (m->type.x == T0_MATERIAL_EMISSIVE) {
            break;
        }
        const int nee = T0_HAS_FEATURE(scene, T0_FEATURE_NEE);
        VertexDraws draws;
        sampler_start_vertex(sampler, depth, nee, &draws);

        // Russian roulette, without next-event estimation (the thesis'
        // integrator) right here; with it, after the light sample.
        if (!nee && !survives_roulette(continuation_probability(depth, max_depth, throughput),
                                       &throughput, vertex_1d(sampler, draws.roulette))) {
            break;
        }
        const float3 position = hit_position(tri, hit);
        const float magnitude = hit_magnitude(tri, position);
        // A base-colour texture multiplies the material's colour: for the
        // thesis' four, which both the light sample and the scattered ray's
        // weight are linear in (their densities do not depend on it), as a
        // factor on both; the microfacet types take it in the surface's
        // base colour.
        float3 texture = float3_splat(1.0f);
        if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
            texture = surface_texture(scene, m, hit);
        }
        // The factor on the whole sample (the thesis' four take the
        // texture so; the microfacet types inside, from `texture`).
        float3 tint = texture;
        float2 rm = make_float2(1.0f, 1.0f);
        if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
            tint = texture_outside(scene, m, texture);
            if (T0_HAS_FEATURE(scene, T0_FEATURES_MICROFACET) && material_is_microfacet(m->type.x)) {
                rm = hit_roughness_metallic(scene, m, hit);
            }
        }

        // Sample a light (next-event estimation), before the roulette: the
        // light sample is this vertex's and counts whether or not the path
        // goes on; the emission that the scattered ray finds counts only on
        // paths that survive, divided by the probability. Both are
        // unbiased, and the MIS weights still sum to one.
        // Not at the last vertex a path may have: the light sample stands
        // for the next vertex, which max_depth does not allow.
        lights_sampled = 0;
        ShadowedLight light = no_light_sample();
        if (nee && depth + 1 < max_depth && scene->light_count > 0u &&
            material_samples_lights(scene, m)) {
            const float u_pick = vertex_1d(sampler, draws.light_pick);
            const float2 u_point = vertex_2d(sampler, draws.light_point);
            const float u_tree = T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE)
                                     ? sample_1d(sampler, T0_DIM_LIGHT_TREE(depth))
                                     : 0.0f;
            light = sample_light(scene, m, texture, rm, front, ray.direction, facing_normal,
                                 facing_geometric, position, magnitude, u_pick, u_tree, u_point);
            light.sent = throughput * tint * light.sent;
            if (!T0_SHADOW_RAY_LAST) {
                radiance += light.sent;  // its shadow ray traced (sample_light)
            }
            lights_sampled = 1;
            sampled_from = position;  // what a triangle's solid angle is seen from
            if (T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE)) {
                sampled_normal = facing_normal;
            }
        }

        // Whether the path goes on: the roulette, then the material's sample.
        int goes_on = !nee || survives_roulette(
                                  nee_continuation_probability(depth, max_depth, throughput),
                                  &throughput, vertex_1d(sampler, draws.roulette));
        float3 next_origin = position;
        float3 next_direction = geometric_normal;
        if (goes_on) {
            // Glass needs one number, the others two.
            const float2 u = m->type.x == T0_MATERIAL_GLASS
                                 ? make_float2(vertex_1d(sampler, draws.material.x), 0.0f)
                                 : vertex_2d(sampler, draws.material);
            const float u_lobe =
                material_draws_lobe(scene, m) ? sample_1d(sampler, T0_DIM_LOBE(depth)) : 0.0f;
            const ScatterSample s = scatter_material(scene, m, texture, rm, front, ray.direction,
                                                     shading, facing_normal, u, u_lobe);
            goes_on = s.weight.x > 0.0f || s.weight.y > 0.0f || s.weight.z > 0.0f;
            // With a shading normal, a direction the material scattered to
            // one side of it may lie on the other side of the triangle:
            // absorbed, not let through (a reflection stays on the incoming
            // side).
            if ((T0_HAS_FEATURE(scene, T0_FEATURE_SMOOTH) ||
                 T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) &&
                (dot(s.direction, facing_geometric) > 0.0f) !=
                    (dot(s.direction, facing_normal) > 0.0f)) {
                goes_on = 0;
            }
            if (goes_on) {
                throughput *= s.weight * tint;
                scatter_pdf = s.pdf;
                // Continue from just off the surface, on the side the new
                // ray leaves.
                const float3 side = dot(s.direction, geometric_normal) > 0.0f
                                        ? geometric_normal
                                        : -geometric_normal;
                next_origin = offset_ray_origin(position, side, magnitude);
                next_direction = s.direction;
            }
        }
        add_light_last(scene, &light, &radiance);
        if (!goes_on) {
            break;
        }
        ray = make_ray(next_origin, next_direction);
    }
    return radiance;
}

T0_INLINE float3 trace_path(const SceneView* scene, Ray ray, int max_depth, Sampler* sampler) {
    return trace_path_from(scene, ray, intersect_scene(scene, &ray), max_depth, sampler);
}

// A pixel's sample in two halves, so that a loop over pixels can make the
// next pixel's random numbers and camera ray while this one's path runs:
// begin_pixel starts the pixel's sampler (the scene's features choose
// which) and makes its camera ray, finish_pixel traces the path and
// accumulates it.
typedef struct PixelSample {
    Sampler sampler;
    Ray ray;
} PixelSample;

T0_INLINE void begin_pixel(const SceneView* scene, CameraRecord cam, t0_u32 pixel, t0_u64 seed,
                           t0_u32 frame, PixelSample* s) {
    sampler_start(&s->sampler, T0_HAS_FEATURE(scene, T0_FEATURE_SOBOL), seed, pixel, frame);
    const t0_u32 x = pixel % cam.size.x;
    const t0_u32 y = pixel / cam.size.x;
    const float2 jitter = sample_2d(&s->sampler, T0_DIM_PIXEL);
    if (cam.extent.z > 0.0f) {
        const float2 lens = sample_2d(&s->sampler, T0_DIM_LENS);
        s->ray = camera_lens_ray(cam, (float)x, (float)y, jitter.x, jitter.y, lens);
    } else if (camera_is_orthographic(cam)) {
        s->ray = orthographic_ray(cam, (float)x, (float)y, jitter.x, jitter.y);
    } else {
        s->ray = pinhole_ray(cam, (float)x, (float)y, jitter.x, jitter.y);
    }
}

T0_INLINE void finish_pixel(const SceneView* scene, T0_GLOBAL AccumPixel* accum, t0_u32 pixel,
                            int max_depth, PixelSample* s) {
    accumulate_sample(&accum[pixel], trace_path(scene, s->ray, max_depth, &s->sampler));
}

// A camera ray's nearest hit: among the `count` leaves of its tile
// (count >= 0; a ray parallel to an axis was left out of the bundle), or
// through the scene (count -1).
T0_INLINE Hit camera_hit(const SceneView* scene, const Ray* ray,
                         T0_LOCAL const LeafCandidate* leaves, int count) {
    if (count >= 0 && !ray->any_parallel) {
        return intersect_bundle_leaves(scene, leaves, count, ray);
    }
    return intersect_scene(scene, ray);
}

// One sample of one pixel in one frame, accumulated.
T0_INLINE void render_pixel(const SceneView* scene, CameraRecord cam, T0_GLOBAL AccumPixel* accum,
                            t0_u32 pixel, t0_u64 seed, t0_u32 frame, int max_depth) {
    PixelSample s;
    begin_pixel(scene, cam, pixel, seed, frame, &s);
    finish_pixel(scene, accum, pixel, max_depth, &s);
}

T0_NAMESPACE_END

#endif
