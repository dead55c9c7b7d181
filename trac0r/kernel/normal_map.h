// Tangent-space normal maps (MaterialRecord.maps.z): the shading normal a
// map's texel turns the interpolated normal to, in the frame of the
// triangle's texture directions (T along increasing u, B along increasing
// v, the normal N), as glTF's normalTexture and Blender's Normal Map node
// read them: n = normalize(T x s + B y s + N z), with (x, y, z) = 2 texel
// - 1 and s the map's scale.
//
// The tangent frame is the triangle's own (its positions' derivatives
// with respect to u and v, Gram-Schmidt against the shading normal):
// where a mesh's UV layout is smooth across its triangles it is the frame
// MikkTSpace interpolates, and where a file gives no tangents it is what
// there is to go on.
#ifndef TRAC0R_KERNEL_NORMAL_MAP_H
#define TRAC0R_KERNEL_NORMAL_MAP_H

#include "ray.h"
#include "texture.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// `shading` (the hit's shading normal, on the triangle's outer side)
// turned by the material's normal map at the hit; `shading` itself where
// the triangle has no texture coordinates, its coordinates are
// degenerate, or the mapped normal would put the incoming ray on the
// other side of the surface than the triangle does.
T0_INLINE float3 normal_mapped(const SceneView* scene, T0_GLOBAL const MaterialRecord* m, Hit hit,
                               float3 incoming, float3 geometric_normal, float3 shading) {
    float2 uv;
    if (m->maps.z == 0u || !hit_uv(scene, hit, &uv)) {
        return shading;
    }
    T0_GLOBAL const TriangleUVs* t = &scene->uvs[hit.triangle];
    T0_GLOBAL const TriangleRecord* tri = &scene->triangles[hit.triangle];
    const float3 dp1 = xyz(tri->v1) - xyz(tri->v0);
    const float3 dp2 = xyz(tri->v2) - xyz(tri->v0);
    const float du1 = t->uv01.z - t->uv01.x;
    const float dv1 = t->uv01.w - t->uv01.y;
    const float du2 = t->uv2.x - t->uv01.x;
    const float dv2 = t->uv2.y - t->uv01.y;
    const float det = du1 * dv2 - du2 * dv1;
    if (!(fabs(det) > 1e-20f)) {
        return shading;
    }
    float3 tangent = (dp1 * dv2 - dp2 * dv1) / det;
    const float3 bitangent = (dp2 * du1 - dp1 * du2) / det;
    tangent = tangent - shading * dot(shading, tangent);
    const float tangent2 = dot(tangent, tangent);
    if (!(tangent2 > 1e-30f) || !is_finite_f(tangent2)) {
        return shading;
    }
    tangent = tangent / sqrt(tangent2);
    float3 b = cross(shading, tangent);
    if (dot(b, bitangent) < 0.0f) {
        b = -b;  // a mirrored UV layout
    }
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
