// Alpha (T0_FEATURE_ALPHA): surfaces that rays pass through where their
// material's alpha says so, glTF's alphaMode. MASK cuts out where alpha
// (the factor times its texture's channel) is below the cutoff; BLEND is
// stochastic opacity: a ray stops there with probability alpha, else
// passes on, so that on average a surface of alpha a hides a of what is
// behind it. Camera rays, scattered rays and shadow rays all pass through
// alike: the test sits in the traversal (traverse.h), where a hit is
// accepted.
//
// BLEND's number is a hash of the ray and the triangle: the same ray meets
// the same answer (traversals are deterministic and may test a triangle
// twice), a new ray a new one.
#ifndef TRAC0R_KERNEL_ALPHA_H
#define TRAC0R_KERNEL_ALPHA_H

#include "ray.h"
#include "sampler.h"
#include "texture.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// MaterialRecord.alpha.z
#define T0_ALPHA_OPAQUE 0.0f
#define T0_ALPHA_MASK 1.0f
#define T0_ALPHA_BLEND 2.0f

// A number in [0, 1) for the ray and the triangle.
T0_INLINE float alpha_number(const Ray* ray, int triangle) {
    t0_u32 h = hash32((t0_u32)triangle ^ 0x9E3779B9u);
    h = hash32(h ^ (t0_u32)float_bits(ray->origin.x));
    h = hash32(h ^ (t0_u32)float_bits(ray->origin.y));
    h = hash32(h ^ (t0_u32)float_bits(ray->origin.z));
    h = hash32(h ^ (t0_u32)float_bits(ray->direction.x));
    h = hash32(h ^ (t0_u32)float_bits(ray->direction.y));
    h = hash32(h ^ (t0_u32)float_bits(ray->direction.z));
    return unit_float(h);
}

// Whether `ray` passes through the triangle at barycentrics (u, v).
T0_INLINE int passes_through(const SceneView* scene, const Ray* ray, int triangle, float u,
                             float v) {
    T0_GLOBAL const MaterialRecord* m = &scene->materials[scene->triangles[triangle].ids.x];
    const float mode = m->alpha.z;
    if (mode == T0_ALPHA_OPAQUE) {
        return 0;
    }
    float a = m->alpha.x;
    if (m->maps.w != 0u) {
        Hit at;
        at.t = 0.0f;
        at.u = u;
        at.v = v;
        at.triangle = triangle;
        float2 uv;
        if (hit_uv(scene, at, &uv)) {
            a *= texture_channel(scene->texels, scene->textures[m->maps.w - 1u], uv.x, uv.y,
                                 (int)m->alpha.w);
        }
    }
    if (mode == T0_ALPHA_MASK) {
        return !(a >= m->alpha.y);
    }
    return !(alpha_number(ray, triangle) < a);
}

T0_NAMESPACE_END

#endif
