// Tangent-space normal maps (MaterialRecord.maps.z): the shading normal a
// map's texel turns the interpolated normal to, in the frame of the
// triangle's tangents (VertexTangents: T along increasing u, B along
// increasing v, the normal N), as glTF's normalTexture, MikkTSpace and
// Blender's Normal Map node read them: T and its sign interpolated, T made
// orthogonal to N, B = sign cross(N, T), and n = normalize(T x s + B y s +
// N z), with (x, y, z) = 2 texel - 1 and s the map's scale.
#ifndef TRAC0R_KERNEL_NORMAL_MAP_H
#define TRAC0R_KERNEL_NORMAL_MAP_H

#include "ray.h"
#include "texture.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// `shading` (the hit's shading normal, on the triangle's outer side)
// turned by the material's normal map at the hit; `shading` itself where
// the triangle has no texture coordinates or tangents, its tangents are
// degenerate, or the mapped normal would put the incoming ray on the
// other side of the surface than the triangle does.
T0_INLINE float3 normal_mapped(const SceneView* scene, T0_GLOBAL const MaterialRecord* m, Hit hit,
                               float3 incoming, float3 geometric_normal, float3 shading) {
    float2 uv;
    if (m->maps.z == 0u || !hit_uv(scene, hit, &uv)) {
        return shading;
    }
    T0_GLOBAL const VertexTangents* t = &scene->tangents[hit.triangle];
    if (t->t0.w == 0.0f) {
        return shading;
    }
    float3 tangent =
        xyz(t->t0) * (1.0f - hit.u - hit.v) + xyz(t->t1) * hit.u + xyz(t->t2) * hit.v;
    tangent = tangent - shading * dot(shading, tangent);
    const float tangent2 = dot(tangent, tangent);
    if (!(tangent2 > 1e-12f) || !is_finite_f(tangent2)) {
        return shading;
    }
    tangent = tangent / sqrt(tangent2);
    const float3 b = cross(shading, tangent) * (t->t0.w < 0.0f ? -1.0f : 1.0f);
    const float3 c =
        texture_bilinear_as(scene->texels, scene->textures[m->maps.z - 1u], uv.x, uv.y, 0) * 2.0f -
        float3_splat(1.0f);
    const float scale = m->k.w;
    const float3 n = tangent * (c.x * scale) + b * (c.y * scale) + shading * c.z;
    const float n2 = dot(n, n);
    if (!(n2 > 1e-12f)) {
        return shading;
    }
    const float3 unit = n / sqrt(n2);
    if (!(dot(unit, geometric_normal) > 0.0f) ||
        (dot(incoming, unit) < 0.0f) != (dot(incoming, geometric_normal) < 0.0f)) {
        return shading;
    }
    return unit;
}

T0_NAMESPACE_END

#endif
