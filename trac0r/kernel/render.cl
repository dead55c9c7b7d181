// The OpenCL entry point: the same kernel headers the CPU backend compiles.
// The library embeds this file after the headers (cmake/embed.cmake), and
// builds it with -DT0_FEATURES=<mask> so unused branches are compiled out.
#include "trace.h"

__kernel void render_frame(__global const TriangleRecord* triangles,
                           __global const ShapeRecord* shapes,
                           __global const MaterialRecord* materials,
                           __global const BvhNode* nodes, uint shape_count,
                           CameraRecord camera, __global AccumPixel* accum, ulong seed, uint frame,
                           int max_depth, __global const LightRecord* lights,
                           uint light_count, __global const TrianglePacket* packets) {
    const uint pixel = (uint)get_global_id(0);
    if (pixel >= camera.size.x * camera.size.y) {
        return;
    }
    SceneView scene;
    scene.triangles = triangles;
    scene.shapes = shapes;
    scene.materials = materials;
    scene.nodes = nodes;
    scene.packets = packets;
    scene.shape_count = shape_count;
    scene.lights = lights;
    scene.light_count = light_count;
    scene.features = T0_FEATURES;
    render_pixel(&scene, camera, accum, pixel, seed, frame, max_depth);
}
