// What a denoiser or compositor wants beside the image: per pixel, from the
// ray through its centre, the distance to the first surface and the albedo
// and shading normal of the first surface that is not a mirror or glass
// (through those the ray goes on, as a denoiser's guides do: a mirror's
// own albedo and normal would hide what it shows). One deterministic ray
// per pixel, no sampling.
#ifndef TRAC0R_KERNEL_GUIDES_H
#define TRAC0R_KERNEL_GUIDES_H

#include "trace.h"

T0_NAMESPACE_BEGIN

// Mirror and glass bounces followed before giving up (albedo and normal
// then stay zero).
#define T0_GUIDE_MAX_BOUNCES 8

typedef struct T0_ALIGN16 GuidePixel {
    float4 albedo;  // xyz: the surface's colour, times the tint of any glass
                    // on the way; w: depth, the first hit's distance along the
                    // camera's forward axis (T0_NO_HIT: none)
    float4 normal;  // xyz: unit shading normal facing the ray (zero: none),
                    // w: 1 where the surface is a pure emitter
} GuidePixel;

// The guides of camera ray `ray`, whose nearest hit is `first`; *emitted:
// the radiance it meets where it ends on a pure emitter (times the tint of
// the glass on the way), else zero.
T0_INLINE GuidePixel guide_ray_from(const SceneView* scene, CameraRecord camera, Ray ray, Hit first,
                                    float3* emitted) {
    GuidePixel g;
    g.albedo = make_float4(0.0f, 0.0f, 0.0f, T0_NO_HIT);
    g.normal = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    *emitted = float3_splat(0.0f);
    float3 tint = float3_splat(1.0f);
    for (int bounce = 0; bounce <= T0_GUIDE_MAX_BOUNCES; ++bounce) {
        const Hit hit = bounce == 0 ? first : intersect_scene(scene, &ray);
        if (hit.triangle < 0) {
            return g;
        }
        if (bounce == 0) {
            g.albedo.w = hit.t * dot(ray.direction, xyz(camera.forward));
        }
        T0_GLOBAL const TriangleRecord* tri = &scene->triangles[hit.triangle];
        T0_GLOBAL const MaterialRecord* m = &scene->materials[tri->ids.x];
        const float3 geometric_normal = xyz(tri->normal);
        const int front = dot(ray.direction, geometric_normal) < 0.0f;
        const float3 shading = shading_normal(scene, hit, ray.direction, geometric_normal);
        const float3 facing_normal = front ? shading : -shading;
        const t0_u32 type = m->type.x;
        const int passes_on = type == T0_MATERIAL_GLASS ||
                              (type == T0_MATERIAL_GLOSSY && !material_samples_lights(scene, m));
        if (!passes_on) {
            const float3 colour = xyz(m->color);
            // An emitter's colour scaled into [0, 1]: its albedo as a guide.
            const float peak = fmax(colour.x, fmax(colour.y, colour.z));
            const float3 albedo =
                type == T0_MATERIAL_EMISSIVE && peak > 1.0f ? colour / peak : colour;
            float3 a = tint * albedo;
            if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
                a *= surface_texture(scene, m, hit);
            }
            g.albedo = make_float4(a.x, a.y, a.z, g.albedo.w);
            g.normal = make_float4(facing_normal.x, facing_normal.y, facing_normal.z,
                                   type == T0_MATERIAL_EMISSIVE ? 1.0f : 0.0f);
            if (type == T0_MATERIAL_EMISSIVE) {
                *emitted = tint * material_emission_seen(scene, m, front);
            }
            return g;
        }
        // On through the mirror or the glass: glass refracts (its choice
        // number above any Fresnel reflectance but total reflection's),
        // tinting by its colour; a mirror reflects along its lobe's axis.
        const float2 u =
            type == T0_MATERIAL_GLASS ? make_float2(0.99999994f, 0.0f) : make_float2(0.0f, 0.0f);
        const ScatterSample s =
            scatter_material(scene, m, float3_splat(1.0f), make_float2(1.0f, 1.0f), front,
                             ray.direction, shading, facing_normal, u, 0.0f);
        if (!(s.weight.x > 0.0f || s.weight.y > 0.0f || s.weight.z > 0.0f)) {
            return g;
        }
        tint *= s.weight;
        const float3 position = hit_position(tri, hit);
        const float3 side =
            dot(s.direction, geometric_normal) > 0.0f ? geometric_normal : -geometric_normal;
        ray =
            make_ray(offset_ray_origin(position, side, hit_magnitude(tri, position)), s.direction);
    }
    return g;
}

// The guides of the ray through (x + jx, y + jy) (guide_ray_from).
T0_INLINE GuidePixel guide_ray(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y,
                               float jx, float jy, float3* emitted) {
    const Ray ray = camera_ray(camera, (float)x, (float)y, jx, jy);
    return guide_ray_from(scene, camera, ray, intersect_scene(scene, &ray), emitted);
}

// The guides of the ray through pixel (x, y)'s centre.
T0_INLINE GuidePixel pixel_guides(const SceneView* scene, CameraRecord camera, t0_u32 x, t0_u32 y) {
    float3 emitted;
    return guide_ray(scene, camera, x, y, 0.5f, 0.5f, &emitted);
}

T0_NAMESPACE_END

#endif
