// The OpenCL entry point: the same kernel headers the CPU backend compiles.
// The library embeds this file after the headers (cmake/embed.cmake), and
// builds it with -DT0_FEATURES=<mask> so unused branches are compiled out.
#include "trace.h"

// The kernel's view of the packed buffers (PackedScene::view on the host).
// A kernel that reads no materials or lights (the ray-cast benchmark's)
// passes 0 for them.
SceneView scene_view(__global const TriangleRecord* triangles, __global const ShapeRecord* shapes,
                     __global const MaterialRecord* materials, __global const BvhNode* nodes,
                     __global const TrianglePacket* packets, __global const LightRecord* lights,
                     uint shape_count, uint light_count) {
    SceneView scene;
    scene.triangles = triangles;
    scene.shapes = shapes;
    scene.materials = materials;
    scene.nodes = nodes;
    scene.packets = packets;
    scene.lights = lights;
    scene.shape_count = shape_count;
    scene.light_count = light_count;
    scene.features = T0_FEATURES;
    return scene;
}

__kernel void render_frame(__global const TriangleRecord* triangles,
                           __global const ShapeRecord* shapes,
                           __global const MaterialRecord* materials, __global const BvhNode* nodes,
                           uint shape_count, CameraRecord camera, __global AccumPixel* accum,
                           ulong seed, uint frame, int max_depth,
                           __global const LightRecord* lights, uint light_count,
                           __global const TrianglePacket* packets) {
    const uint pixel = (uint)get_global_id(0);
    if (pixel >= camera.size.x * camera.size.y) {
        return;
    }
    const SceneView scene =
        scene_view(triangles, shapes, materials, nodes, packets, lights, shape_count, light_count);
    render_pixel(&scene, camera, accum, pixel, seed, frame, max_depth);
}
