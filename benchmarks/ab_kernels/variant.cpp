// One version of the kernel headers, compiled by benchmarks/ab_kernels.sh
// with its namespace renamed (AB_NAMESPACE: trac0r::kernel_a0 to kernel_a3,
// kernel_b0 to kernel_b3), so that two versions, each at four code offsets
// (AB_PAD), link into one program. Exports a
// frame on one thread, tile by tile as the CPU backend renders it
// (kernel/tile.h), and the sizes of the buffer structs, which must be the
// ones the program packs.
// AB_PAD bytes of padding ahead of this version's code (the script builds
// each version at several such offsets, so that where the linker happens to
// put a hot loop does not decide a comparison).
#define AB_STR2(x) #x
#define AB_STR(x) AB_STR2(x)
__asm__(".text\n.p2align 6\n.skip " AB_STR(AB_PAD) ", 0xcc\n");

#include "trac0r/kernel/tile.h"

#include "buffers.h"

#include <cstddef>
#include <cstdint>

#define AB_CAT2(a, b) a##b
#define AB_CAT(a, b) AB_CAT2(a, b)

namespace k = trac0r::AB_NAMESPACE;

extern "C" void AB_CAT(AB_NAMESPACE, _frame)(const void* scene, const void* camera, void* accum,
                                             std::uint64_t seed, std::uint32_t frame,
                                             int max_depth) {
    const k::SceneView view = *static_cast<const k::SceneView*>(scene);
    const k::CameraRecord cam = *static_cast<const k::CameraRecord*>(camera);
    const std::uint32_t width = cam.size.x;
    const std::uint32_t height = cam.size.y;
    for (std::uint32_t t = 0; t < k::tile_count(width, height); ++t) {
        k::render_tile(&view, cam, static_cast<k::AccumPixel*>(accum), seed, frame, max_depth,
                       k::tile_rect(t, width, height), width);
    }
}

extern "C" void AB_CAT(AB_NAMESPACE, _sizes)(std::size_t* out) {
#define AB_SIZE(type) *out++ = sizeof(k::type);
    AB_BUFFERS(AB_SIZE)
#undef AB_SIZE
}
