// The OpenCL entry point: the same kernel headers the CPU backend compiles.
// The library embeds this file after the headers (cmake/embed.cmake), and
// builds it with -DT0_FEATURES=<mask> so unused branches are compiled out.
#include "bdpt.h"
#include "filter.h"
#include "temporal.h"
#include "tile_grid.h"
#include "trace.h"

// The kernel's view of the packed buffers (PackedScene::view on the host).
// A kernel that reads no materials, lights, normals, tangents, textures or
// environment (the ray-cast benchmark's) passes 0 for them.
T0_INLINE SceneView
scene_view(__global const TriangleRecord* triangles, __global const ShapeRecord* shapes,
           __global const MaterialRecord* materials, __global const BvhNode* nodes,
           __global const TrianglePacket* packets, __global const LightRecord* lights,
           __global const VertexNormals* normals, __global const TriangleUVs* uvs,
           __global const VertexTangents* tangents, __global const TextureRecord* textures,
           __global const uint* texels, __global const float4* environment,
           __global const LightTreeNode* light_nodes, uint shape_count, uint light_count,
           uint distant_count, float4 sphere) {
    SceneView scene;
    scene.triangles = triangles;
    scene.shapes = shapes;
    scene.materials = materials;
    scene.nodes = nodes;
    scene.packets = packets;
    scene.lights = lights;
    scene.normals = normals;
    scene.uvs = uvs;
    scene.tangents = tangents;
    scene.textures = textures;
    scene.texels = texels;
    scene.environment = environment;
    scene.distant_count = distant_count;
    scene.light_nodes = light_nodes;
    scene.sphere = sphere;
    scene.shape_count = shape_count;
    scene.light_count = light_count;
    scene.features = T0_FEATURES;
    return scene;
}

// With the BVH a work-group renders a tile of T0_TILE x T0_TILE pixels
// (the host launches them so), as the CPU backend's render_tile does:
// tile_pixel makes the work-item's pixel's generator and camera ray, and
// whether the pixel is in the image (the last tiles may be cut off).
T0_INLINE int tile_pixel(const SceneView* scene, CameraRecord camera, ulong seed, uint frame,
                         PixelSample* s, uint* pixel) {
    // The global id, not the group's: a frame may be launched in parts
    // (a global offset of whole tiles).
    const TileRect tile =
        tile_rect((uint)(get_global_id(0) / (T0_TILE * T0_TILE)), camera.size.x, camera.size.y);
    const uint item = (uint)get_local_id(0);
    const uint x = tile.x0 + item % T0_TILE;
    const uint y = tile.y0 + item / T0_TILE;
    if (x >= tile.x1 || y >= tile.y1) {
        return 0;
    }
    *pixel = y * camera.size.x + x;
    begin_pixel(scene, camera, *pixel, seed, frame, s);
    return 1;
}

// What a work-group shares in local memory to find its tile's leaves.
typedef struct TileShared {
    float4 inverse[T0_TILE * T0_TILE];  // xyz: a ray's inverse direction; w: 1 if bundled
    LeafCandidate leaves[T0_BUNDLE_LEAVES];
    int leaf_count;
} TileShared;

// The nearest hit of the work-item's camera ray (where inside), from the
// leaves that the tile's rays may enter, found once by the first work-item
// (bundle_finish_leaves) into the group's local memory, or by traversal
// where there are too many (camera_hit). Every work-item of the group calls
// it (barriers), with the group's `shared`. Through a thin lens, or from
// an orthographic camera, the rays do not share an origin: the leaf count
// is -1, and each ray traverses the tree. (The barriers stay on every path: PoCL gave wrong results with an
// early return before them, though the condition is the group's own.)
T0_INLINE Hit tile_camera_hit(const SceneView* scene, CameraRecord camera, int inside,
                              const Ray* ray, __local TileShared* shared) {
    const uint item = (uint)get_local_id(0);
    __local float4* inverse = shared->inverse;
    inverse[item] =
        inside ? (float4)(ray->inv_direction, ray->any_parallel ? 0.0f : 1.0f) : (float4)(0.0f);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (item == 0u && (camera.extent.z > 0.0f || camera_is_orthographic(camera))) {
        shared->leaf_count = -1;
    } else if (item == 0u) {
        RayBundle b;
        bundle_start(&b, camera.position.xyz);
        for (int i = 0; i < T0_TILE * T0_TILE; ++i) {
            if (inverse[i].w != 0.0f) {
                bundle_add(&b, inverse[i].xyz);
            }
        }
        shared->leaf_count = bundle_finish_leaves(scene, &b, shared->leaves);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    return inside ? camera_hit(scene, ray, shared->leaves, shared->leaf_count) : no_hit(T0_NO_HIT);
}

// What a work-item of the BVH program starts from: its pixel of the
// group's tile (tile_pixel), the pixel's generator and camera ray, and the
// ray's nearest hit (tile_camera_hit). Every work-item of the group calls
// it (barriers), with the group's `shared`.
typedef struct TileSample {
    PixelSample sample;
    Hit first;   // the camera ray's nearest hit, where inside
    uint pixel;  // the pixel's index in the image, where inside
    int inside;  // whether the pixel is in the image
} TileSample;

T0_INLINE TileSample tile_sample(const SceneView* scene, CameraRecord camera, ulong seed,
                                 uint frame, __local TileShared* shared) {
    TileSample t;
    t.pixel = 0u;
    t.inside = tile_pixel(scene, camera, seed, frame, &t.sample, &t.pixel);
    t.first = tile_camera_hit(scene, camera, t.inside, &t.sample.ray, shared);
    return t;
}

__kernel void render_frame(__global const TriangleRecord* triangles,
                           __global const ShapeRecord* shapes,
                           __global const MaterialRecord* materials, __global const BvhNode* nodes,
                           uint shape_count, CameraRecord camera, __global AccumPixel* accum,
                           ulong seed, uint frame, int max_depth,
                           __global const LightRecord* lights, uint light_count,
                           __global const TrianglePacket* packets,
                           __global const VertexNormals* normals,
                           __global const TriangleUVs* uvs,
                           __global const TextureRecord* textures, __global const uint* texels,
                           __global const float4* environment, uint distant_count,
                           __global const LightTreeNode* light_nodes,
                           __global const VertexTangents* tangents, float4 sphere) {
    const SceneView scene = scene_view(triangles, shapes, materials, nodes, packets, lights,
                                       normals, uvs, tangents, textures, texels, environment,
                                       light_nodes, shape_count, light_count, distant_count, sphere);
    if (!T0_HAS_FEATURE(&scene, T0_FEATURE_BVH)) {
        // A pixel a work-item.
        const uint pixel = (uint)get_global_id(0);
        if (pixel < camera.size.x * camera.size.y) {
            render_pixel(&scene, camera, accum, pixel, seed, frame, max_depth);
        }
        return;
    }
    // With the BVH, a tile a work-group (tile_sample).
    __local TileShared shared;
    TileSample t = tile_sample(&scene, camera, seed, frame, &shared);
    if (t.inside) {
        accumulate_sample(&accum[t.pixel],
                          trace_path_from(&scene, t.sample.ray, t.first, max_depth, &t.sample.sampler));
    }
}

// Bidirectional path tracing (bdpt.h), a pixel a work-item: its sample,
// with render_frame's arguments and the frame's two buffers; bdpt_merge
// then accumulates every pixel's, once all the splats are in. Only in the
// programs of scenes that use it: the build of the others stays as fast.
#if (T0_FEATURES & T0_FEATURE_BDPT) != 0u
__kernel void bdpt_frame(__global const TriangleRecord* triangles,
                         __global const ShapeRecord* shapes,
                         __global const MaterialRecord* materials, __global const BvhNode* nodes,
                         uint shape_count, CameraRecord camera, __global AccumPixel* accum,
                         ulong seed, uint frame, int max_depth,
                         __global const LightRecord* lights, uint light_count,
                         __global const TrianglePacket* packets,
                         __global const VertexNormals* normals, __global const TriangleUVs* uvs,
                         __global const TextureRecord* textures, __global const uint* texels,
                         __global const float4* environment, uint distant_count,
                         __global const LightTreeNode* light_nodes,
                         __global const VertexTangents* tangents, float4 sphere,
                         __global float4* frame_radiance, __global long* splats) {
    const SceneView scene = scene_view(triangles, shapes, materials, nodes, packets, lights,
                                       normals, uvs, tangents, textures, texels, environment,
                                       light_nodes, shape_count, light_count, distant_count, sphere);
    const uint pixel = (uint)get_global_id(0);
    if (pixel < camera.size.x * camera.size.y) {
        bdpt_sample(&scene, camera, pixel, seed, frame, max_depth, bdpt_all_strategies(),
                    frame_radiance, splats);
    }
}

__kernel void bdpt_merge_frame(__global AccumPixel* accum, __global const float4* frame_radiance,
                               __global long* splats, uint pixels) {
    const uint i = (uint)get_global_id(0);
    if (i < pixels) {
        bdpt_merge(accum, frame_radiance, splats, i);
    }
}
#endif

// The edge-preserving filter (filter.h), a pixel a work-item: the first
// pass's input from the accumulator, the guides as the passes read them,
// one a-trous pass, and the colour.
__kernel void filter_begin(__global const AccumPixel* accum, __global const FilterGuide* guides,
                           __global FilterPixel* out, uint pixels) {
    const uint i = (uint)get_global_id(0);
    if (i < pixels) {
        out[i] = filter_input(accum[i], guides[i]);
    }
}

__kernel void filter_taps(__global const FilterGuide* guides, __global FilterTap* taps, int width,
                          int height) {
    const int i = (int)get_global_id(0);
    if (i < width * height) {
        taps[i] = filter_tap(guides, width, height, i % width, i / width);
    }
}

__kernel void filter_noise_pass(__global const FilterPixel* in, __global FilterNoise* noise,
                                uint pixels) {
    const uint i = (uint)get_global_id(0);
    if (i < pixels) {
        noise[i] = filter_noise(in[i]);
    }
}

__kernel void filter_pass(__global const FilterPixel* in, __global const FilterTap* taps,
                          __global const FilterNoise* noise, __global FilterPixel* out, int width,
                          int height, int pass) {
    const int i = (int)get_global_id(0);
    if (i < width * height) {
        out[i] = atrous_pixel(in, taps, noise, width, height, i % width, i / width, pass);
    }
}

__kernel void filter_end(__global const FilterPixel* in, __global const FilterGuide* guides,
                         __global float4* out, uint pixels) {
    const uint i = (uint)get_global_id(0);
    if (i < pixels) {
        const float3 c = filter_output(in[i], guides[i]);
        out[i] = (float4)(c, 0.0f);
    }
}
