// The structs that the program packs and each version of the kernel reads
// (ab_kernels.sh checks that their sizes agree): AB_BUFFER(type) for each.
#ifndef TRAC0R_BENCHMARKS_AB_BUFFERS_H
#define TRAC0R_BENCHMARKS_AB_BUFFERS_H

#define AB_BUFFERS(AB_BUFFER) \
    AB_BUFFER(SceneView)      \
    AB_BUFFER(TriangleRecord) \
    AB_BUFFER(ShapeRecord)    \
    AB_BUFFER(MaterialRecord) \
    AB_BUFFER(BvhNode)        \
    AB_BUFFER(TrianglePacket) \
    AB_BUFFER(LightRecord)    \
    AB_BUFFER(CameraRecord)   \
    AB_BUFFER(AccumPixel)

#endif
