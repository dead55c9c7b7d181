// Buffer structs shared by the host and both backends, and the feature mask.
//
// Only 16-byte vector members (float4/uint4), so C++ and OpenCL C lay them
// out identically; the C++ side static_asserts size and alignment.
#ifndef TRAC0R_KERNEL_TYPES_H
#define TRAC0R_KERNEL_TYPES_H

#include "compat.h"

// Material types; the values are stored in MaterialRecord.type.x.
#define T0_MATERIAL_EMISSIVE 1u
#define T0_MATERIAL_DIFFUSE 2u
#define T0_MATERIAL_GLASS 3u
#define T0_MATERIAL_GLOSSY 4u
#define T0_MATERIAL_CONDUCTOR 5u   // GGX metal (rough_materials.h)
#define T0_MATERIAL_PLASTIC 6u     // a diffuse base under a GGX dielectric coat
#define T0_MATERIAL_PRINCIPLED 7u  // glTF 2.0's metallic-roughness BRDF
#define T0_MATERIAL_ROUGH_GLASS 8u // glass of roughness > 0: GGX reflection and refraction

// The feature mask: what a packed scene uses. The OpenCL program is built
// with T0_FEATURES defined to the mask, so code behind a bit the scene does
// not set is compiled out; the CPU backend tests the same bits at run time.
#define T0_FEATURE_EMISSIVE (1u << 0)  // pure emitters
#define T0_FEATURE_DIFFUSE (1u << 1)
#define T0_FEATURE_GLASS (1u << 2)
#define T0_FEATURE_GLOSSY (1u << 3)
#define T0_FEATURE_EMITTANCE (1u << 4)  // any surface that emits light
#define T0_FEATURE_FLAT (1u << 5)       // the thesis' flat list of shapes
#define T0_FEATURE_BVH (1u << 6)        // a BVH over all triangles
#define T0_FEATURE_NEE (1u << 7)        // next-event estimation with MIS
#define T0_FEATURE_SOBOL (1u << 8)      // Owen-scrambled Sobol samples (sampler.h)
#define T0_FEATURE_SMOOTH (1u << 9)     // vertex normals (VertexNormals) on some triangles
#define T0_FEATURE_TEXTURE (1u << 10)   // base-colour textures (texture.h) on some triangles
#define T0_FEATURE_ENVIRONMENT (1u << 11)  // light from all around (environment.h)
#define T0_FEATURE_LAMPS (1u << 12)        // point, spot and sun lights (lamps.h)
#define T0_FEATURE_ONE_SIDED (1u << 13)    // emitters that emit from their front only
#define T0_FEATURE_LIGHT_TREE (1u << 14)   // lights picked by a tree (light_tree.h)
#define T0_FEATURE_CONDUCTOR (1u << 15)
#define T0_FEATURE_PLASTIC (1u << 16)
#define T0_FEATURE_PRINCIPLED (1u << 17)
#define T0_FEATURE_ROUGH_GLASS (1u << 18)
#define T0_FEATURE_ALPHA (1u << 19)  // surfaces rays pass through (alpha.h)
#define T0_FEATURE_BDPT (1u << 20)   // bidirectional path tracing (bdpt.h)
#define T0_FEATURE_COUNT 21

T0_NAMESPACE_BEGIN

// One triangle for the watertight test (kernel/triangle.h): its three
// vertices exactly as the scene has them, so triangles sharing an edge or a
// vertex share its floats bit for bit; the unit geometric normal (w: twice
// the area, |e1 x e2| with e1 = v1 - v0, e2 = v2 - v0) and indices; and
// numbers of the hit point's computation that depend on the triangle alone
// (kernel/ray_offset.h, make_triangle_record, which fills a record).
typedef struct T0_ALIGN16 TriangleRecord {
    float4 v0;      // xyz: first vertex, w: hit_position's lower bound for its weight
    float4 v1;      // xyz: second vertex, w: the same for v1
    float4 v2;      // xyz: third vertex, w: the same for v2
    float4 normal;  // xyz: normalize(e1 x e2), w: |e1 x e2|
    uint4 ids;      // x: material index, y: shape index, z: light index (T0_NO_LIGHT: none),
                    // w: the float bits of vertices_magnitude (hit_magnitude)
} TriangleRecord;

// TriangleRecord.ids.z of a triangle that emits no light.
#define T0_NO_LIGHT 0xffffffffu

// The kinds of light in the light list (LightRecord.ids.y).
#define T0_LIGHT_TRIANGLE 0u     // an emitting triangle (its material emits)
#define T0_LIGHT_POINT 1u        // a point lamp
#define T0_LIGHT_SPOT 2u         // a point lamp whose light is a cone
#define T0_LIGHT_SUN 3u          // a distant disc, or a direction (angle 0)
#define T0_LIGHT_ENVIRONMENT 4u  // an environment (environment.h)

// One light of the list that next-event estimation picks from, in
// proportion to its power. The pick is an inverse-CDF search over cdf.x,
// so y is exactly the difference of consecutive cdf.x and picks and
// densities agree bit for bit. The distant lights (the environment and
// suns) come first, SceneView.distant_count of them: a ray that leaves the
// scene looks them up; an environment is always the first.
// By kind (all vectors in the packed scene's coordinates):
//   triangle:    ids.x the triangle; ids.z its path in the light tree (bit k:
//                the child taken at depth k), with T0_FEATURE_LIGHT_TREE.
//   point:       a.xyz position; b.xyz intensity (W/sr, colour times intensity);
//                ids.z its path in the light tree, as a triangle's.
//   spot:        a.xyz position, a.w cos of the cone's half-angle (where the light
//                ends); b.xyz intensity on the axis; c.xyz unit axis, c.w cos of
//                the angle where the soft edge begins (lamps.h, spot_falloff).
//   sun:         a.xyz unit direction towards the sun; b.xyz its radiance, or for a
//                delta sun (angle 0) its irradiance (W/m^2); c.x sin^2 of its
//                angular radius (0: delta), c.y the solid angle of its disc,
//                c.z 1 - cos of its angular radius.
//   environment: a.x, a.y cos and sin of the rotation about +y; ids.z, ids.w the
//                map's width and height (SceneView.environment).
typedef struct T0_ALIGN16 LightRecord {
    float4 cdf;  // x: probability of this light or an earlier one (the last is 1),
                 // y: probability of this light, z: y / area, the density per
                 // area (triangles)
    uint4 ids;   // x: triangle index, y: kind (T0_LIGHT_*), z, w: map size
    float4 a;
    float4 b;
    float4 c;
} LightRecord;

// A node of the light tree (light_tree.h): bounds of the lights under it
// (the emitting triangles and point and spot lamps), their power, and the
// cone of directions their light leaves in: an axis, the half-angle
// theta_o of the cone of their normals, and theta_e, how far beyond it
// light leaves (pi/2 for a surface). A node's two children are next to
// each other; a leaf holds one light.
typedef struct T0_ALIGN16 LightTreeNode {
    float4 lo;    // xyz: the bounds' minimum, w: the power (the light list's unit)
    float4 hi;    // xyz: the bounds' maximum, w: cos theta_o
    float4 axis;  // xyz: the cone's unit axis, w: cos theta_e
    uint4 info;   // x: the first child, or for a leaf its light (an index into the
                  // light list); y: 1 for a leaf; z: 1 if light leaves on both sides
} LightTreeNode;

// One shape of the flat structure: its AABB and its run of triangles.
typedef struct T0_ALIGN16 ShapeRecord {
    float4 aabb_min;  // xyz
    float4 aabb_max;  // xyz
    uint4 range;      // x: first triangle, y: triangle count, z: material
} ShapeRecord;

// A node of the 8-wide BVH (trac0r/bvh.h): the boxes of its (up to) eight
// children (nodes, or leaves of one TrianglePacket each) side by side, so
// that one eight-lane operation per plane tests all eight boxes (t0_wide:
// AVX on PoCL, two SSE vectors on the CPU). Plane p (0 min x, 1 max x,
// 2 min y, 3 max y, 4 min z, 5 max z) holds child i's coordinate in lane
// i % 4 of bounds[2 p + i / 4]; child i's word is lane i % 4 of
// child[i / 4]. An unused lane has the empty box min = +FLT_MAX,
// max = -FLT_MAX, which no ray enters.
#define T0_BVH_WIDTH 8
typedef struct T0_ALIGN16 BvhNode {
    float4 bounds[12];
    uint4 child[2];  // per lane: a node index, or T0_BVH_LEAF | a packet index
    uint4 count[2];  // per lane: the leaf's triangle count; 0: a node (or unused).
                     // No kernel reads it (T0_BVH_LEAF says leaf); test_bvh checks
                     // packets against it, and it keeps a node at four cache lines.
} BvhNode;

// In BvhNode.child, the lane is a leaf: the traversal reads one word a
// child (and keeps one on its stack), not the child and its count.
#define T0_BVH_LEAF 0x80000000u

// The triangles of one BVH leaf (up to four) side by side for the
// watertight test, lane i of each vector for triangle i, so that one vector
// operation works on all four: the same vertex floats as their
// TriangleRecords. An unused lane has zero vertices and an infinite area,
// which is never hit (intersect_packet).
typedef struct T0_ALIGN16 TrianglePacket {
    float4 vertex[9];  // vertex[3 k + axis]: coordinate axis of vertex k (v0, v1, v2)
    float4 area;       // twice the area, TriangleRecord.normal.w
    uint4 triangle;    // the index into the triangle records
} TrianglePacket;

// A triangle's normals at its vertices v0, v1, v2 (T0_FEATURE_SMOOTH), by
// triangle index: interpolated, they are its shading normal. n0.w is 1
// where the triangle has them, 0 where it is flat (all zero).
typedef struct T0_ALIGN16 VertexNormals {
    float4 n0;  // xyz: unit normal at v0, w: 1 if the triangle is smooth
    float4 n1;  // xyz: unit normal at v1
    float4 n2;  // xyz: unit normal at v2
} VertexNormals;

// A triangle's tangents at v0, v1, v2, by triangle index, for normal maps
// (MaterialRecord.maps.z): xyz the direction of increasing u, w the sign
// of the bitangent (the direction of increasing v is w cross(n, t)), as
// glTF's TANGENT and MikkTSpace give them; all zero where the triangle has
// none (its normal map is not applied).
typedef struct T0_ALIGN16 VertexTangents {
    float4 t0;
    float4 t1;
    float4 t2;
} VertexTangents;

// A triangle's texture coordinates at v0, v1, v2 (T0_FEATURE_TEXTURE), by
// triangle index, with u to the right and v up from the image's bottom
// row (OBJ's and assimp's convention). uv2.z is 1 where the triangle has
// them, 0 where it has none (its material's colour is used untextured).
typedef struct T0_ALIGN16 TriangleUVs {
    float4 uv01;  // xy: (u, v) at v0, zw: at v1
    float4 uv2;   // xy: (u, v) at v2, z: 1 if the triangle has them, w: unused
} TriangleUVs;

// A base-colour texture: `width` x `height` texels from `first` on in the
// scene's texel buffer, row by row from the image's top row, each RGBA8 in
// sRGB (red in the low byte; alpha unused).
typedef struct T0_ALIGN16 TextureRecord {
    uint4 info;  // x: first texel, y: width, z: height, w: wrap modes (texture.h)
} TextureRecord;

typedef struct T0_ALIGN16 MaterialRecord {
    float4 color;   // xyz: colour (albedo, emitted colour, a conductor's F0, or
                    // a principled material's base colour), w: metallic
    float4 params;  // x: emittance, y: roughness, z: ior, w: glossy_cone_sin2
                    // (glossy) or GGX alpha (the microfacet types)
    uint4 type;     // x: T0_MATERIAL_*, y: base-colour texture + 1 (0: none),
                    // z: 1 for a material that emits from its front only,
                    // w: 1 for a conductor of complex index (eta, k)
    float4 eta;     // conductor: xyz the real part of the index; plastic: w the
                    // diffuse term's scale 1 / (ior^2 (1 - internal reflectance));
                    // principled: x glTF's specular factor
    float4 k;       // conductor: xyz the imaginary part of the index;
                    // w: the normal map's scale (glTF normalTexture.scale)
    uint4 maps;     // data textures + 1 (0: none; texture.h): x roughness (its
                    // green), y metallic (its blue), z a tangent-space normal map,
                    // w alpha (its channel alpha.w)
    float4 alpha;   // x: alpha factor, y: MASK's cutoff, z: mode (alpha.h),
                    // w: the alpha texture's channel (0 red, 3 alpha)
    float4 emission;  // xyz: the radiance it emits (colour x emittance, or a
                      // principled material's emission), w: a principled
                      // material's emission texture + 1 (0: none)
} MaterialRecord;

// The camera as the kernel needs it: an orthonormal frame and the image
// plane's half extents at distance one.
typedef struct T0_ALIGN16 CameraRecord {
    float4 position;  // xyz
    float4 forward;   // xyz, unit; w: 0 perspective, 1 orthographic
    float4 right;     // xyz, unit: normalize(cross(forward, world_up)) (right-handed)
    float4 up;        // xyz, unit: cross(right, forward)
    float4 extent;    // x: tan(vfov/2) * aspect, y: tan(vfov/2) (orthographic: half the
                      // view's width and height in metres), z: the lens' aperture
                      // radius (0: a pinhole), w: the focus distance along forward
    uint4 size;       // x: width, y: height
} CameraRecord;

// Whether the camera is orthographic (its rays parallel, along forward,
// from points of the image plane), not a pinhole or a thin lens.
T0_INLINE int camera_is_orthographic(CameraRecord cam) { return cam.forward.w != 0.0f; }

// Per pixel: a compensated (Kahan) sum of the radiance samples, so the mean
// stays exact over very many frames, and Welford moments of the luminance
// for the noise estimate.
typedef struct T0_ALIGN16 AccumPixel {
    float4 sum;           // xyz: sum of accepted samples
    float4 compensation;  // xyz: Kahan compensation of sum
    float4 moments;       // x: mean luminance, y: M2 of luminance,
                          // z: accepted samples, w: dropped (non-finite) samples
} AccumPixel;

// What the kernel reads of a scene: views of the packed buffers.
typedef struct SceneView {
    T0_GLOBAL const TriangleRecord* triangles;
    T0_GLOBAL const ShapeRecord* shapes;
    T0_GLOBAL const MaterialRecord* materials;
    T0_GLOBAL const BvhNode* nodes;
    T0_GLOBAL const TrianglePacket* packets;
    T0_GLOBAL const LightRecord* lights;
    t0_u32 shape_count;
    t0_u32 light_count;
    t0_u32 features;
    T0_GLOBAL const VertexNormals* normals;  // by triangle; only with T0_FEATURE_SMOOTH
    // Only with T0_FEATURE_TEXTURE: by triangle, its texture coordinates;
    // the textures; and their texels.
    T0_GLOBAL const TriangleUVs* uvs;
    T0_GLOBAL const TextureRecord* textures;
    T0_GLOBAL const t0_u32* texels;
    // By triangle; only where a material of the scene has a normal map.
    T0_GLOBAL const VertexTangents* tangents;
    // Only with T0_FEATURE_ENVIRONMENT: the map's texels row by row from
    // the top (xyz radiance, w the row's CDF through this texel), then one
    // a row (x: the rows' CDF through it) (environment.h).
    T0_GLOBAL const float4* environment;
    t0_u32 distant_count;  // the lights list's distant lights, first in it
    // Only with T0_FEATURE_LIGHT_TREE: the tree over the lights that are
    // not distant, its root first.
    T0_GLOBAL const LightTreeNode* light_nodes;
    // A sphere around every triangle (xyz: its centre, w: its radius), from
    // which light subpaths of distant lights start (light_emission.h).
    float4 sphere;
} SceneView;

// Per-frame settings of the render.
typedef struct T0_ALIGN16 FrameRecord {
    uint4 seed_frame;  // x, y: seed low and high words, z: frame index
    uint4 limits;      // x: max depth
} FrameRecord;

T0_NAMESPACE_END

#ifndef __OPENCL_VERSION__
T0_NAMESPACE_BEGIN
T0_STATIC_ASSERT_SIZE(TriangleRecord, 80);
T0_STATIC_ASSERT_SIZE(ShapeRecord, 48);
T0_STATIC_ASSERT_SIZE(MaterialRecord, 128);
T0_STATIC_ASSERT_SIZE(BvhNode, 256);
T0_STATIC_ASSERT_SIZE(TrianglePacket, 176);
T0_STATIC_ASSERT_SIZE(LightRecord, 80);
T0_STATIC_ASSERT_SIZE(LightTreeNode, 64);
T0_STATIC_ASSERT_SIZE(VertexNormals, 48);
T0_STATIC_ASSERT_SIZE(TriangleUVs, 32);
T0_STATIC_ASSERT_SIZE(VertexTangents, 48);
T0_STATIC_ASSERT_SIZE(TextureRecord, 16);
T0_STATIC_ASSERT_SIZE(CameraRecord, 96);
T0_STATIC_ASSERT_SIZE(AccumPixel, 48);
T0_STATIC_ASSERT_SIZE(FrameRecord, 32);
T0_NAMESPACE_END
#endif

// A feature test that folds to a constant in OpenCL (the program is built
// with -DT0_FEATURES=mask) and reads the packed scene's mask on the CPU.
#ifdef __OPENCL_VERSION__
#ifndef T0_FEATURES
#define T0_FEATURES 0xffffffffu
#endif
#define T0_HAS_FEATURE(scene, bit) ((T0_FEATURES & (bit)) != 0u)
#else
#define T0_HAS_FEATURE(scene, bit) (((scene)->features & (bit)) != 0u)
#endif

#endif
