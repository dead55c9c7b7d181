// The kernel's measured choices, each with the figure that chose it: the
// switches that differ per compiler (defined here), then the choices both
// compilers share (in the code where named). docs/performance.md, "Kernel
// tuning", summarises them; OpenCL C is as PoCL compiles it, C++ as GCC.
//
// Per compiler:
//
//   T0_NOINLINE, a rare path (outside_exactly, packet_outside_exactly)
//     OpenCL  inline: PoCL's frames were 3 % slower with a call.
//     C++     out of line, kept out of the hot code.
//   choose_f(condition, a, b), a choice that the data decide (whether a
//   normal's component is zero: offset_coordinate, next_float_towards)
//     OpenCL  both computed, one picked by bits: PoCL's LLVM kept ?: as
//             a branch, which mispredicted.
//     C++     ?:, only the one chosen computed: GCC's branches were
//             faster on the CPU than computing both.
//   T0_ONE_CHILD_APART, traverse_bvh's node with one child entered
//     OpenCL  1, taken apart: PoCL's frames were 2 to 4 % slower with it
//             taken as one with two.
//     C++     0, taken as one with two, whose farther child is pushed
//             without being counted: one branch less to mispredict,
//             1.2 % of a BVH frame on cornell.json.
//   T0_LANE_TRAVERSAL, traverse_bvh: traverse_bvh_groups, a stack word
//   a level and a node's children and a packet's triangles one at a time
//     OpenCL  on a GPU (the host's -DT0_GPU=1), 1: its work-item is one
//             lane; eight lanes at once filled its registers and put the
//             children's distances and a 148-entry stack in scratch, which
//             is DRAM (docs/gpu.md). On PoCL's CPU device 0, as C++.
//     C++     0, the sorted stack of eight lanes at once: the group
//             stack's second test of a node took 9.9 % more instructions
//             a path on cornell.json (instructions_per_path.sh).
//   T0_SHADOW_RAY_LAST, when NEE's shadow ray is traced
//     OpenCL  on a GPU, 1: after the vertex's shading, which then holds
//             no registers across the traversal: 129 to 114 VGPRs on
//             gfx1030 (cornell.json, docs/gpu.md).
//     C++     0, straight after the light sample, whose MIS weight is
//             then not computed where the ray is blocked.
//   component3, largest_axis, next_axis (make_ray, on a ray's axes)
//     OpenCL  choices, which LLVM makes selects: PoCL's frames were 6 %
//             slower with the arithmetic largest axis.
//     C++     memory and arithmetic, no branch: GCC made the choices
//             branches, on axes which for bounce rays are anyone's
//             guess; 2.5 % of a BVH frame of cornell.json.
//
// The same on both:
//
//   aabb_entry, three slabs without clip_slab's per-axis branch
//             the BVH's inner loop, 17 % more rays per second.
//   RayLanes.permuted_origin, read by fixed index, not by the ray's axes
//             PoCL's frames 2.4 and 3.0 % faster (two series), the CPU's
//             the same, for three more splats a ray.
//   intersect_packet, a hit with a zero edge function checked again in
//   every packet with a hit
//             2 % of a BVH frame; checking only the hit a traversal ends
//             with, and traversing again where it is outside, cost as
//             much with GCC and twice that with PoCL.
//   turn_cos_sin, Cephes' polynomials, no library sin and cos
//             PoCL's argument reduction for every angle took 16 % of a
//             path's time on cornell.json; glibc's sincosf about 3 %.
//   sample_cosine_hemisphere, the direction not renormalised
//             2.6 % of a BVH frame's time on cornell.json.
//   render_tile_bundled, a tile's camera rays finding their leaves once
//             a tenth of a BVH frame's time less on cornell.json.
#ifndef TRAC0R_KERNEL_TUNING_H
#define TRAC0R_KERNEL_TUNING_H

#include "compat.h"

#ifdef __OPENCL_VERSION__

#define T0_NOINLINE T0_INLINE

T0_INLINE float choose_by_bits(int condition, float a, float b) {
    const int mask = -(condition != 0);
    return as_float((as_int(a) & mask) | (as_int(b) & ~mask));
}
#define choose_f(condition, a, b) choose_by_bits((condition), (a), (b))

#define T0_ONE_CHILD_APART 1

#ifdef T0_GPU
#define T0_LANE_TRAVERSAL 1
#define T0_SHADOW_RAY_LAST 1
#else
#define T0_LANE_TRAVERSAL 0
#define T0_SHADOW_RAY_LAST 0
#endif

// Component k (0, 1, 2) of a vector that is not in a buffer, the axis of
// a's largest component (the lower axis on a tie), and the axis after k
// (0 1 2 to 1 2 0).
T0_INLINE float component3(float3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }
T0_INLINE int largest_axis(float3 a) {
    return a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
}
T0_INLINE int next_axis(int k) { return k == 2 ? 0 : k + 1; }

#else  // C++

#define T0_NOINLINE inline __attribute__((noinline))

#define choose_f(condition, a, b) ((condition) ? (a) : (b))

#define T0_ONE_CHILD_APART 0

#define T0_LANE_TRAVERSAL 0
#define T0_SHADOW_RAY_LAST 0

T0_NAMESPACE_BEGIN

// As the OpenCL side's, without a branch.
inline float component3(float3 v, int k) { return glm::value_ptr(v)[k]; }
inline int largest_axis(float3 a) {
    const int xy = a.x >= a.y ? 1 : 0;
    const int xz = a.x >= a.z ? 1 : 0;
    const int yz = a.y >= a.z ? 1 : 0;
    return 2 - 2 * (xy & xz) - ((1 - xy) & yz);
}
inline int next_axis(int k) { return (9 >> (2 * k)) & 3; }

T0_NAMESPACE_END

#endif

#endif
