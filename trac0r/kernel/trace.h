// The camera, the trace loop and one pixel's sample: the whole per-pixel
// work of a frame, shared by the OpenMP backend and the OpenCL program.
#ifndef TRAC0R_KERNEL_TRACE_H
#define TRAC0R_KERNEL_TRACE_H

#include "accumulate.h"
#include "intersect.h"
#include "material.h"
#include "rng.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// A primary ray through pixel (x, y) (row 0 at the top) at sub-pixel
// position (jitter_x, jitter_y) in [0, 1)^2.
T0_INLINE Ray camera_ray(CameraRecord cam, float x, float y, float jitter_x, float jitter_y) {
    const float width = (float)cam.size.x;
    const float height = (float)cam.size.y;
    const float sx = (2.0f * (x + jitter_x) / width - 1.0f) * cam.extent.x;
    const float sy = (1.0f - 2.0f * (y + jitter_y) / height) * cam.extent.y;
    const float3 d = xyz(cam.forward) + xyz(cam.right) * sx + xyz(cam.up) * sy;
    return make_ray(xyz(cam.position), normalize(d));
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

// One path from the camera; returns its radiance estimate.
T0_INLINE float3 trace_path(const SceneView* scene, Ray ray, int max_depth, Rng* rng) {
    float3 radiance = float3_splat(0.0f);
    float3 throughput = float3_splat(1.0f);
    for (int depth = 0; depth < max_depth; ++depth) {
        // Intersect: the nearest triangle, or the black background.
        const Hit hit = intersect_scene(scene, ray);
        if (hit.triangle < 0) {
            break;
        }
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[hit.triangle];
        T0_GLOBAL const MaterialRecord* m = &scene->materials[tri->ids.x];
        const float3 geometric_normal = xyz(tri->normal);
        // Two-sided surfaces: the shading normal faces the incoming ray.
        const float3 facing_normal =
            dot(ray.direction, geometric_normal) < 0.0f ? geometric_normal : -geometric_normal;

        // Emit.
        if (T0_HAS_FEATURE(scene, T0_FEATURE_EMITTANCE)) {
            radiance += throughput * material_emission(m);
        }
        if (m->type.x == T0_MATERIAL_EMISSIVE) {
            break;
        }

        // Russian roulette.
        const float q = continuation_probability(depth, max_depth, throughput);
        if (!(rng_float(rng) < q)) {
            break;
        }
        throughput /= q;

        // Sample the material.
        const ScatterSample s =
            scatter_material(scene, m, ray.direction, geometric_normal, facing_normal, rng);
        if (!(s.weight.x > 0.0f || s.weight.y > 0.0f || s.weight.z > 0.0f)) {
            break;
        }
        throughput *= s.weight;

        // Continue from just off the surface, on the side the new ray leaves.
        const float3 position = hit_position(tri, hit);
        const float3 side = dot(s.direction, geometric_normal) > 0.0f ? geometric_normal : -geometric_normal;
        ray = make_ray(offset_ray_origin(position, side, hit_magnitude(tri, position)), s.direction);
    }
    return radiance;
}

// One sample of one pixel in one frame, accumulated.
T0_INLINE void render_pixel(const SceneView* scene, CameraRecord cam, T0_GLOBAL AccumPixel* accum,
                            t0_u32 pixel, t0_u64 seed, t0_u32 frame, int max_depth) {
    Rng rng;
    rng_seed_pixel(&rng, seed, pixel, frame);
    const t0_u32 x = pixel % cam.size.x;
    const t0_u32 y = pixel / cam.size.x;
    const float jitter_x = rng_float(&rng);
    const float jitter_y = rng_float(&rng);
    const Ray ray = camera_ray(cam, (float)x, (float)y, jitter_x, jitter_y);
    accumulate_sample(&accum[pixel], trace_path(scene, ray, max_depth, &rng));
}

T0_NAMESPACE_END

#endif
