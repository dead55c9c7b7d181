// Textures (T0_FEATURE_TEXTURE): a surface's colour times its base-colour
// texture's (an emitter's emission times its emission texture's), looked
// up bilinearly at the hit's texture coordinates, repeating outside
// [0, 1); colour texels are sRGB and are made linear before they are
// filtered, as GPUs' sRGB textures do. The microfacet materials' data
// textures (roughness, metallic, normal maps) are read as they are.
#ifndef TRAC0R_KERNEL_TEXTURE_H
#define TRAC0R_KERNEL_TEXTURE_H

#include "compat.h"
#include "ray.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// An 8-bit sRGB value's linear value (IEC 61966-2-1), rounded to float: a
// table, so that both backends read the same numbers.
T0_CONSTANT float t0_srgb_to_linear[256] = {
    0.0f,           0.000303526991f, 0.000607053982f, 0.000910580973f, 0.00121410796f,
    0.00151763496f, 0.00182116195f,  0.00212468882f,  0.00242821593f,  0.0027317428f,
    0.00303526991f, 0.00334653584f,  0.00367650739f,  0.00402471703f,  0.00439144205f,
    0.00477695325f, 0.00518151652f,  0.00560539169f,  0.00604883302f,  0.00651209056f,
    0.00699541019f, 0.00749903219f,  0.00802319311f,  0.00856812578f,  0.00913405884f,
    0.00972121768f, 0.010329823f,    0.0109600937f,   0.0116122449f,   0.012286488f,
    0.0129830325f,  0.0137020834f,   0.0144438436f,   0.0152085144f,   0.0159962941f,
    0.0168073755f,  0.0176419541f,   0.01850022f,     0.0193823613f,   0.0202885624f,
    0.0212190095f,  0.0221738853f,   0.0231533665f,   0.0241576321f,   0.0251868591f,
    0.0262412224f,  0.0273208916f,   0.02842604f,     0.0295568351f,   0.0307134446f,
    0.0318960324f,  0.0331047662f,   0.0343398079f,   0.0356013142f,   0.0368894488f,
    0.0382043719f,  0.0395462364f,   0.0409151986f,   0.0423114114f,   0.043735031f,
    0.045186203f,   0.0466650873f,   0.0481718257f,   0.0497065671f,   0.0512694567f,
    0.0528606474f,  0.054480277f,    0.0561284907f,   0.0578054301f,   0.0595112368f,
    0.0612460524f,  0.0630100146f,   0.064803265f,    0.0666259378f,   0.0684781671f,
    0.0703600943f,  0.0722718537f,   0.0742135718f,   0.0761853829f,   0.078187421f,
    0.0802198201f,  0.0822827071f,   0.0843762085f,   0.0865004584f,   0.0886555836f,
    0.0908417106f,  0.0930589661f,   0.0953074694f,   0.097587347f,    0.0998987257f,
    0.102241732f,   0.104616486f,    0.107023105f,    0.10946171f,     0.111932427f,
    0.114435375f,   0.116970666f,    0.119538426f,    0.122138776f,    0.124771819f,
    0.127437681f,   0.130136475f,    0.13286832f,     0.135633335f,    0.138431609f,
    0.141263291f,   0.144128472f,    0.147027269f,    0.149959788f,    0.152926147f,
    0.155926466f,   0.158960834f,    0.162029371f,    0.165132195f,    0.168269396f,
    0.171441108f,   0.174647406f,    0.177888423f,    0.18116425f,     0.18447499f,
    0.187820777f,   0.191201687f,    0.194617838f,    0.198069319f,    0.20155625f,
    0.205078736f,   0.208636865f,    0.212230757f,    0.215860501f,    0.219526201f,
    0.223227963f,   0.226965874f,    0.230740055f,    0.23455058f,     0.238397568f,
    0.242281124f,   0.246201321f,    0.25015828f,     0.254152089f,    0.258182853f,
    0.262250662f,   0.266355604f,    0.270497799f,    0.274677306f,    0.278894275f,
    0.283148736f,   0.287440836f,    0.291770637f,    0.296138257f,    0.300543785f,
    0.304987311f,   0.309468925f,    0.313988715f,    0.318546772f,    0.323143214f,
    0.327778101f,   0.332451522f,    0.337163627f,    0.341914415f,    0.346704066f,
    0.351532608f,   0.356400132f,    0.361306787f,    0.366252601f,    0.371237695f,
    0.376262128f,   0.38132602f,     0.386429429f,    0.391572475f,    0.396755219f,
    0.401977777f,   0.407240212f,    0.412542611f,    0.417885065f,    0.423267663f,
    0.428690493f,   0.434153646f,    0.439657182f,    0.445201188f,    0.450785786f,
    0.456411034f,   0.462076992f,    0.467783809f,    0.473531485f,    0.479320168f,
    0.48514995f,    0.491020858f,    0.496932983f,    0.502886474f,    0.50888133f,
    0.514917672f,   0.520995557f,    0.527115107f,    0.533276379f,    0.539479494f,
    0.545724452f,   0.55201143f,     0.558340371f,    0.564711511f,    0.571124852f,
    0.577580452f,   0.584078431f,    0.590618849f,    0.597201765f,    0.603827357f,
    0.610495567f,   0.617206573f,    0.623960376f,    0.630757153f,    0.637596846f,
    0.644479692f,   0.651405632f,    0.658374846f,    0.665387273f,    0.672443151f,
    0.679542482f,   0.686685324f,    0.693871737f,    0.701101899f,    0.708375752f,
    0.715693474f,   0.723055124f,    0.730460763f,    0.73791039f,     0.745404184f,
    0.752942204f,   0.760524511f,    0.768151164f,    0.775822222f,    0.783537805f,
    0.791297913f,   0.799102724f,    0.806952238f,    0.814846575f,    0.822785735f,
    0.830769897f,   0.838799f,       0.846873224f,    0.854992628f,    0.863157213f,
    0.871367097f,   0.8796224f,      0.887923121f,    0.896269381f,    0.904661179f,
    0.913098633f,   0.921581864f,    0.930110872f,    0.938685715f,    0.947306514f,
    0.955973327f,   0.964686275f,    0.973445296f,    0.982250571f,    0.991102099f,
    1.0f,
};

T0_INLINE float3 texel_linear(T0_GLOBAL const t0_u32* texels, t0_u32 index) {
    const t0_u32 p = texels[index];
    return make_float3(t0_srgb_to_linear[p & 255u], t0_srgb_to_linear[(p >> 8) & 255u],
                       t0_srgb_to_linear[(p >> 16) & 255u]);
}

// The part of t (finite) in [0, 1), else 0.
T0_INLINE float repeat_coordinate(float t) {
    const float f = t - floor(t);
    return f >= 0.0f && f < 1.0f ? f : 0.0f;
}

// A texel's value: its channels made linear from sRGB (colours), or as
// they are, over 255 (data: roughness, metallic, normals).
T0_INLINE float3 texel_value(T0_GLOBAL const t0_u32* texels, t0_u32 index, int srgb) {
    if (srgb) {
        return texel_linear(texels, index);
    }
    const t0_u32 p = texels[index];
    return make_float3((float)(p & 255u), (float)((p >> 8) & 255u), (float)((p >> 16) & 255u)) *
           (1.0f / 255.0f);
}

// A coordinate mirrored at every integer (glTF's MIRRORED_REPEAT): 1.25
// reads as 0.75, 2.25 as 0.25, -0.25 as 0.25.
T0_INLINE float mirror_coordinate(float t) {
    const float f = t - 2.0f * floor(0.5f * t);  // in [0, 2)
    const float m = f < 1.0f ? f : 2.0f - f;
    return m >= 0.0f && m <= 1.0f ? m : 0.0f;
}

// A coordinate in [0, 1] as the wrap mode says (TextureWrap: 0 repeat,
// 1 clamp to the edge, 2 mirrored repeat); NaN reads as 0.
T0_INLINE float wrap_coordinate(float t, t0_u32 mode) {
    if (mode == 1u) {
        return t > 0.0f ? (t < 1.0f ? t : 1.0f) : 0.0f;
    }
    return mode == 2u ? mirror_coordinate(t) : repeat_coordinate(t);
}

// The texel column (row) of index i in [-1, n] (n texels): repeat wraps
// -1 and n round; clamp and mirror keep the edge texel.
T0_INLINE t0_u32 wrap_index(float i, t0_u32 n, t0_u32 mode) {
    if (i < 0.0f) {
        return mode == 0u ? n - 1u : 0u;
    }
    const t0_u32 k = (t0_u32)i;
    return k < n ? k : (mode == 0u ? 0u : n - 1u);
}

// The four texels around (u, v) and the weights between them: bilinear
// between the nearest texel centres, beyond the edges as the texture's
// wrap modes say (info.w: u's in bits 0-1, v's in bits 2-3).
typedef struct BilinearTaps {
    t0_u32 i00, i01, i10, i11;  // top-left, top-right, bottom-left, bottom-right
    float fx, fy;
} BilinearTaps;

T0_INLINE BilinearTaps bilinear_taps(TextureRecord texture, float u, float v) {
    const t0_u32 first = texture.info.x;
    const t0_u32 w = texture.info.y;
    const t0_u32 h = texture.info.z;
    const t0_u32 wrap_u = texture.info.w & 3u;
    const t0_u32 wrap_v = (texture.info.w >> 2) & 3u;
    // Row 0 is the image's top; v = 0 its bottom.
    const float x = wrap_coordinate(u, wrap_u) * (float)w - 0.5f;
    const float y = (1.0f - wrap_coordinate(v, wrap_v)) * (float)h - 0.5f;
    const float x0 = floor(x);
    const float y0 = floor(y);
    // x0 in [-1, w] (y0 alike).
    const t0_u32 ix0 = wrap_index(x0, w, wrap_u);
    const t0_u32 iy0 = wrap_index(y0, h, wrap_v);
    const t0_u32 ix1 = wrap_index(x0 + 1.0f, w, wrap_u);
    const t0_u32 iy1 = wrap_index(y0 + 1.0f, h, wrap_v);
    BilinearTaps t;
    t.i00 = first + iy0 * w + ix0;
    t.i01 = first + iy0 * w + ix1;
    t.i10 = first + iy1 * w + ix0;
    t.i11 = first + iy1 * w + ix1;
    t.fx = x - x0;
    t.fy = y - y0;
    return t;
}

// texture at (u, v), bilinear (bilinear_taps); srgb as texel_value.
T0_INLINE float3 texture_bilinear_as(T0_GLOBAL const t0_u32* texels, TextureRecord texture, float u,
                                     float v, int srgb) {
    const BilinearTaps t = bilinear_taps(texture, u, v);
    const float3 top =
        texel_value(texels, t.i00, srgb) * (1.0f - t.fx) + texel_value(texels, t.i01, srgb) * t.fx;
    const float3 bottom =
        texel_value(texels, t.i10, srgb) * (1.0f - t.fx) + texel_value(texels, t.i11, srgb) * t.fx;
    return top * (1.0f - t.fy) + bottom * t.fy;
}

// One channel (0 red ... 3 alpha) of a texture at (u, v), bilinear as
// texture_bilinear_as, read as stored (over 255).
T0_INLINE float texture_channel(T0_GLOBAL const t0_u32* texels, TextureRecord texture, float u,
                                float v, int channel) {
    const BilinearTaps t = bilinear_taps(texture, u, v);
    const t0_u32 shift = 8u * (t0_u32)channel;
    const float a = (float)((texels[t.i00] >> shift) & 255u);
    const float b = (float)((texels[t.i01] >> shift) & 255u);
    const float c = (float)((texels[t.i10] >> shift) & 255u);
    const float d = (float)((texels[t.i11] >> shift) & 255u);
    return ((a * (1.0f - t.fx) + b * t.fx) * (1.0f - t.fy) +
            (c * (1.0f - t.fx) + d * t.fx) * t.fy) *
           (1.0f / 255.0f);
}

T0_INLINE float3 texture_bilinear(T0_GLOBAL const t0_u32* texels, TextureRecord texture, float u,
                                  float v) {
    return texture_bilinear_as(texels, texture, u, v, 1);
}

// The hit's texture coordinates, if its triangle has them (returns 0
// where it has none or they are not finite).
T0_INLINE int hit_uv(const SceneView* scene, Hit hit, float2* uv) {
    T0_GLOBAL const TriangleUVs* t = &scene->uvs[hit.triangle];
    if (!(t->uv2.z > 0.0f)) {
        return 0;
    }
    const float b0 = 1.0f - hit.u - hit.v;
    const float u = t->uv01.x * b0 + t->uv01.z * hit.u + t->uv2.x * hit.v;
    const float v = t->uv01.y * b0 + t->uv01.w * hit.u + t->uv2.y * hit.v;
    if (!(is_finite_f(u) && is_finite_f(v))) {
        return 0;
    }
    *uv = make_float2(u, v);
    return 1;
}

// A data texture (index + 1, 0: none) at the hit: its channels over 255;
// `fallback` where there is no texture or no coordinates.
T0_INLINE float3 hit_data_texture(const SceneView* scene, t0_u32 texture, Hit hit,
                                  float3 fallback) {
    float2 uv;
    if (texture == 0u || !hit_uv(scene, hit, &uv)) {
        return fallback;
    }
    return texture_bilinear_as(scene->texels, scene->textures[texture - 1u], uv.x, uv.y, 0);
}

// The factors a metallic-roughness texture puts on a microfacet
// material's roughness (x: the roughness texture's green) and metallic
// (y: the metallic texture's blue), as glTF's metallicRoughnessTexture;
// one where there is none.
T0_INLINE float2 hit_roughness_metallic(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                        Hit hit) {
    float2 rm = make_float2(1.0f, 1.0f);
    if (m->maps.x != 0u) {
        rm.x = hit_data_texture(scene, m->maps.x, hit, float3_splat(1.0f)).y;
    }
    if (m->maps.y != 0u) {
        rm.y = hit_data_texture(scene, m->maps.y, hit, float3_splat(1.0f)).z;
    }
    return rm;
}

// What a hit's material colour is multiplied by: its texture at the hit's
// texture coordinates, where the material has a texture and the triangle
// has coordinates; else one.
T0_INLINE float3 surface_texture(const SceneView* scene, T0_GLOBAL const MaterialRecord* m,
                                 Hit hit) {
    const t0_u32 texture = m->type.y;
    if (texture == 0u) {
        return float3_splat(1.0f);
    }
    float2 uv;
    if (!hit_uv(scene, hit, &uv)) {
        return float3_splat(1.0f);
    }
    return texture_bilinear(scene->texels, scene->textures[texture - 1u], uv.x, uv.y);
}

T0_NAMESPACE_END

#endif
