// The few differences between the two compilers of the kernel headers.
//
// Every file in trac0r/kernel/ is compiled twice: as C++14 (included by the
// OpenMP backend and the tests) and as OpenCL C 1.2 (embedded into the
// library and built by the OpenCL backend). This header is the only place
// that knows which one is running; the rest is written in the subset both
// accept: POD structs, free functions, no references, templates or virtuals.
#ifndef TRAC0R_KERNEL_COMPAT_H
#define TRAC0R_KERNEL_COMPAT_H

#ifdef __OPENCL_VERSION__

// No silent fused multiply-adds: the C++ build has none either
// (-ffp-contract=off, CMakeLists.txt), and the watertight triangle test and
// the compensated sums in accumulate.h rely on exact rounding.
#pragma OPENCL FP_CONTRACT OFF

// Doubles where the device has them: the triangle test's exact edge
// functions (kernel/triangle.h). Without, the same exact signs in floats.
#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define T0_HAVE_DOUBLE 1
#endif

#define T0_GLOBAL __global
#define T0_LOCAL __local
#define T0_INLINE inline __attribute__((always_inline))
// A rare path kept out of the hot code: on the CPU (compat.h below); PoCL
// frames were 3 % slower with a call in the kernel than with it inline.
#define T0_NOINLINE T0_INLINE
#define T0_ALIGN16
#define T0_NAMESPACE_BEGIN
#define T0_NAMESPACE_END
#define T0_STATIC_ASSERT_SIZE(type, bytes)

typedef ulong t0_u64;
typedef uint t0_u32;

#define make_float3(x, y, z) ((float3)((x), (y), (z)))
#define make_float4(x, y, z, w) ((float4)((x), (y), (z), (w)))
#define make_uint4(x, y, z, w) ((uint4)((x), (y), (z), (w)))
#define float3_splat(v) ((float3)(v))

T0_INLINE float3 xyz(float4 v) { return v.xyz; }
T0_INLINE float3 vmin3(float3 a, float3 b) { return fmin(a, b); }
T0_INLINE float3 vmax3(float3 a, float3 b) { return fmax(a, b); }
T0_INLINE float3 vabs3(float3 a) { return fabs(a); }
T0_INLINE int float_bits(float f) { return as_int(f); }
T0_INLINE float bits_float(int i) { return as_float(i); }
T0_INLINE int is_finite_f(float f) { return isfinite(f); }
// choose_f(condition, a, b): a where condition holds, else b, for a choice
// that the data decide (whether a normal's component is zero). Here both
// are computed and one is picked by bits: PoCL's LLVM kept ?: as a branch,
// which mispredicted (README, "Performance"). The C++ build keeps ?:
// (below): GCC's branches were faster on the CPU than computing both.
T0_INLINE float choose_by_bits(int condition, float a, float b) {
    const int mask = -(condition != 0);
    return as_float((as_int(a) & mask) | (as_int(b) & ~mask));
}
#define choose_f(condition, a, b) choose_by_bits((condition), (a), (b))
// Whether the BVH traversal takes a node with one child entered apart from
// one with two (traverse_bvh): yes here, PoCL's frames were 2 to 4 % slower
// with the two taken together; not in C++ (below).
#define T0_ONE_CHILD_APART 1
// Component k (0, 1, 2) of a vector that is not in a buffer, the axis of
// a's largest component (the lower axis on a tie), and the axis after k
// (0 1 2 to 1 2 0): choices here, which LLVM makes selects; in C++ memory
// and arithmetic (below).
T0_INLINE float component3(float3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }
T0_INLINE int largest_axis(float3 a) {
    return a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
}
T0_INLINE int next_axis(int k) { return k == 2 ? 0 : k + 1; }
// Component k (0, 1, 2) of a vector in a buffer, read as a scalar: vector
// types have no run-time component index in OpenCL C.
T0_INLINE float buffer_component(__global const float4* v, int k) {
    return ((__global const float*)v)[k];
}
T0_INLINE t0_u32 buffer_uint_component(__global const uint4* v, int k) {
    return ((__global const uint*)v)[k];
}
#define T0_INFINITY INFINITY
// The index of the lowest set bit of m (m != 0).
T0_INLINE int lowest_set_bit(int m) { return 31 - (int)clz(m & -m); }

// Four floats that one instruction works on: the BVH tests a packet's four
// triangles at once (kernel/triangle.h). OpenCL's float4 is one.
typedef float4 t0_lanes;
T0_INLINE t0_lanes lanes_load(__global const float4* p) { return *p; }
T0_INLINE t0_lanes lanes_splat(float v) { return (float4)(v); }
T0_INLINE t0_lanes lanes_make(float a, float b, float c, float d) { return (float4)(a, b, c, d); }
T0_INLINE t0_lanes lanes_add(t0_lanes a, t0_lanes b) { return a + b; }
T0_INLINE t0_lanes lanes_sub(t0_lanes a, t0_lanes b) { return a - b; }
T0_INLINE t0_lanes lanes_mul(t0_lanes a, t0_lanes b) { return a * b; }
T0_INLINE t0_lanes lanes_div(t0_lanes a, t0_lanes b) { return a / b; }
T0_INLINE t0_lanes lanes_abs(t0_lanes a) { return fabs(a); }
// a < b ? a : b and a > b ? a : b per lane, as SSE's minps and maxps.
T0_INLINE t0_lanes lanes_min(t0_lanes a, t0_lanes b) { return select(b, a, isless(a, b)); }
T0_INLINE t0_lanes lanes_max(t0_lanes a, t0_lanes b) { return select(b, a, isgreater(a, b)); }
// Comparisons lane by lane: all bits set in a lane where it holds.
typedef int4 t0_mask;
T0_INLINE t0_mask lanes_lt(t0_lanes a, t0_lanes b) { return isless(a, b); }
T0_INLINE t0_mask lanes_le(t0_lanes a, t0_lanes b) { return islessequal(a, b); }
T0_INLINE t0_mask lanes_eq(t0_lanes a, t0_lanes b) { return isequal(a, b); }
T0_INLINE t0_mask mask_and(t0_mask a, t0_mask b) { return a & b; }
T0_INLINE t0_mask mask_or(t0_mask a, t0_mask b) { return a | b; }
T0_INLINE t0_mask mask_and_not(t0_mask a, t0_mask b) { return a & ~b; }
// Bit i set where lane i of m is: one movmskps where the compiler targets
// x86 (PoCL on a CPU), else lane by lane (LLVM makes that six
// instructions on x86).
#if defined(__SSE__) && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_movmskps)
#define T0_HAVE_MOVMSKPS 1
#endif
#endif
T0_INLINE int mask_bits(t0_mask m) {
#ifdef T0_HAVE_MOVMSKPS
    return __builtin_ia32_movmskps(as_float4(m));
#else
    return (m.x & 1) | (m.y & 2) | (m.z & 4) | (m.w & 8);
#endif
}
T0_INLINE void lanes_store(t0_lanes v, float* out) { vstore4(v, 0, out); }
T0_INLINE float lanes_first(t0_lanes v) { return v.x; }

// Eight floats: the BVH tests a node's eight child boxes at once. One AVX
// instruction where PoCL targets AVX (float8); on other devices what the
// driver makes of float8. Loaded from two consecutive float4s of a buffer.
typedef float8 t0_wide;
typedef int8 t0_wide_mask;
T0_INLINE t0_wide wide_load(__global const float4* p) {
    return vload8(0, (__global const float*)p);
}
T0_INLINE t0_wide wide_splat(float v) { return (float8)(v); }
T0_INLINE t0_wide wide_sub(t0_wide a, t0_wide b) { return a - b; }
T0_INLINE t0_wide wide_mul(t0_wide a, t0_wide b) { return a * b; }
T0_INLINE t0_wide wide_min(t0_wide a, t0_wide b) { return select(b, a, isless(a, b)); }
T0_INLINE t0_wide wide_max(t0_wide a, t0_wide b) { return select(b, a, isgreater(a, b)); }
T0_INLINE t0_wide_mask wide_le(t0_wide a, t0_wide b) { return islessequal(a, b); }
#if defined(__AVX__) && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_movmskps256)
#define T0_HAVE_MOVMSKPS256 1
#endif
#endif
T0_INLINE int wide_mask_bits(t0_wide_mask m) {
#if defined(T0_HAVE_MOVMSKPS256)
    return __builtin_ia32_movmskps256(as_float8(m));
#else
    return mask_bits(m.lo) | (mask_bits(m.hi) << 4);
#endif
}
T0_INLINE void wide_store(t0_wide v, float* out) { vstore8(v, 0, out); }

#else  // C++

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#define T0_GLOBAL
#define T0_LOCAL
#define T0_INLINE inline
#define T0_NOINLINE inline __attribute__((noinline))
#define T0_HAVE_DOUBLE 1
#define T0_ALIGN16 alignas(16)
#define T0_NAMESPACE_BEGIN \
    namespace trac0r {     \
    namespace kernel {
#define T0_NAMESPACE_END \
    }                    \
    }
// Buffers shared with OpenCL devices: only 16-byte vector members, so the
// host and device layouts are identical. Checked where each struct is defined.
#define T0_STATIC_ASSERT_SIZE(type, bytes)                                  \
    static_assert(sizeof(type) == (bytes), #type " must match the device"); \
    static_assert(alignof(type) == 16, #type " must be 16-byte aligned")

T0_NAMESPACE_BEGIN

typedef uint64_t t0_u64;
typedef uint32_t t0_u32;
typedef glm::vec3 float3;
typedef glm::vec4 float4;
typedef glm::uvec4 uint4;

using glm::cross;
using glm::dot;
using glm::length;
using glm::normalize;
using std::copysign;
using std::cos;
using std::fabs;
using std::floor;
using std::sin;
using std::sqrt;

// fmax and fmin with their C99 meaning (a NaN argument gives the other),
// written out: std::fmax is a call into libm unless -ffast-math lets the
// compiler assume no NaN, and these sit in every path's inner loop.
inline float fmax(float a, float b) { return a > b || b != b ? a : b; }
inline float fmin(float a, float b) { return a < b || b != b ? a : b; }

inline float3 make_float3(float x, float y, float z) { return float3(x, y, z); }
inline float4 make_float4(float x, float y, float z, float w) { return float4(x, y, z, w); }
inline uint4 make_uint4(t0_u32 x, t0_u32 y, t0_u32 z, t0_u32 w) { return uint4(x, y, z, w); }
inline float3 float3_splat(float v) { return float3(v); }
inline float3 xyz(float4 v) { return float3(v); }
inline float3 vmin3(float3 a, float3 b) {
    return float3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}
inline float3 vmax3(float3 a, float3 b) {
    return float3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}
// std::fabs, which clears the sign bit; glm::abs compares and branches.
inline float3 vabs3(float3 a) { return float3(std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)); }
inline int float_bits(float f) {
    int i;
    std::memcpy(&i, &f, sizeof i);
    return i;
}
inline float bits_float(int i) {
    float f;
    std::memcpy(&f, &i, sizeof f);
    return f;
}
inline int is_finite_f(float f) { return std::isfinite(f) ? 1 : 0; }
// choose_f(condition, a, b): a where condition holds, else b; only the
// one chosen is computed (OpenCL computes both, above).
#define choose_f(condition, a, b) ((condition) ? (a) : (b))
// traverse_bvh takes a node with one child entered as one with two, whose
// farther child is pushed without being counted: one branch less to
// mispredict, 1.2 % of a BVH frame on cornell.json (README, "Performance").
#define T0_ONE_CHILD_APART 0
// component3, largest_axis and next_axis (see the OpenCL side) without a
// branch: GCC made the choices branches, on a ray's axes, which for bounce
// rays are anyone's guess; 2.5 % of a BVH frame of cornell.json (README,
// "Performance"). PoCL's frames were 6 % slower with the arithmetic
// largest axis, so OpenCL keeps the choices.
inline float component3(float3 v, int k) { return glm::value_ptr(v)[k]; }
inline int largest_axis(float3 a) {
    const int xy = a.x >= a.y ? 1 : 0;
    const int xz = a.x >= a.z ? 1 : 0;
    const int yz = a.y >= a.z ? 1 : 0;
    return 2 - 2 * (xy & xz) - ((1 - xy) & yz);
}
inline int next_axis(int k) { return (9 >> (2 * k)) & 3; }
// glm's own view of a vector as an array of its components.
inline float buffer_component(const float4* v, int k) { return glm::value_ptr(*v)[k]; }
inline t0_u32 buffer_uint_component(const uint4* v, int k) { return glm::value_ptr(*v)[k]; }
#define T0_INFINITY HUGE_VALF
// The index of the lowest set bit of m (m != 0).
inline int lowest_set_bit(int m) { return __builtin_ctz(static_cast<unsigned>(m)); }

// Four floats that one instruction works on (see the OpenCL side): SSE,
// which every x86-64 CPU has, or a plain array elsewhere.
#if defined(__SSE__)
typedef __m128 t0_lanes;
inline t0_lanes lanes_load(const float4* p) { return _mm_loadu_ps(glm::value_ptr(*p)); }
inline t0_lanes lanes_splat(float v) { return _mm_set1_ps(v); }
inline t0_lanes lanes_make(float a, float b, float c, float d) { return _mm_setr_ps(a, b, c, d); }
inline t0_lanes lanes_add(t0_lanes a, t0_lanes b) { return _mm_add_ps(a, b); }
inline t0_lanes lanes_sub(t0_lanes a, t0_lanes b) { return _mm_sub_ps(a, b); }
inline t0_lanes lanes_mul(t0_lanes a, t0_lanes b) { return _mm_mul_ps(a, b); }
inline t0_lanes lanes_div(t0_lanes a, t0_lanes b) { return _mm_div_ps(a, b); }
inline t0_lanes lanes_abs(t0_lanes a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a); }
inline t0_lanes lanes_min(t0_lanes a, t0_lanes b) { return _mm_min_ps(a, b); }
inline t0_lanes lanes_max(t0_lanes a, t0_lanes b) { return _mm_max_ps(a, b); }
typedef __m128 t0_mask;
inline t0_mask lanes_lt(t0_lanes a, t0_lanes b) { return _mm_cmplt_ps(a, b); }
inline t0_mask lanes_le(t0_lanes a, t0_lanes b) { return _mm_cmple_ps(a, b); }
inline t0_mask lanes_eq(t0_lanes a, t0_lanes b) { return _mm_cmpeq_ps(a, b); }
inline t0_mask mask_and(t0_mask a, t0_mask b) { return _mm_and_ps(a, b); }
inline t0_mask mask_or(t0_mask a, t0_mask b) { return _mm_or_ps(a, b); }
inline t0_mask mask_and_not(t0_mask a, t0_mask b) { return _mm_andnot_ps(b, a); }
inline int mask_bits(t0_mask m) { return _mm_movemask_ps(m); }
inline void lanes_store(t0_lanes v, float* out) { _mm_storeu_ps(out, v); }
inline float lanes_first(t0_lanes v) { return _mm_cvtss_f32(v); }
// Eight floats (see the OpenCL side): two SSE vectors, lanes 0-3 and 4-7.
struct t0_wide {
    __m128 lo;
    __m128 hi;
};
typedef t0_wide t0_wide_mask;
inline t0_wide wide_load(const float4* p) { return t0_wide{lanes_load(p), lanes_load(p + 1)}; }
inline t0_wide wide_splat(float v) { return t0_wide{_mm_set1_ps(v), _mm_set1_ps(v)}; }
inline t0_wide wide_sub(t0_wide a, t0_wide b) {
    return t0_wide{_mm_sub_ps(a.lo, b.lo), _mm_sub_ps(a.hi, b.hi)};
}
inline t0_wide wide_mul(t0_wide a, t0_wide b) {
    return t0_wide{_mm_mul_ps(a.lo, b.lo), _mm_mul_ps(a.hi, b.hi)};
}
inline t0_wide wide_min(t0_wide a, t0_wide b) {
    return t0_wide{_mm_min_ps(a.lo, b.lo), _mm_min_ps(a.hi, b.hi)};
}
inline t0_wide wide_max(t0_wide a, t0_wide b) {
    return t0_wide{_mm_max_ps(a.lo, b.lo), _mm_max_ps(a.hi, b.hi)};
}
inline t0_wide_mask wide_le(t0_wide a, t0_wide b) {
    return t0_wide{_mm_cmple_ps(a.lo, b.lo), _mm_cmple_ps(a.hi, b.hi)};
}
inline int wide_mask_bits(t0_wide_mask m) {
    return _mm_movemask_ps(m.lo) | (_mm_movemask_ps(m.hi) << 4);
}
inline void wide_store(t0_wide v, float* out) {
    _mm_storeu_ps(out, v.lo);
    _mm_storeu_ps(out + 4, v.hi);
}
#else
struct t0_lanes {
    float v[4];
};
inline t0_lanes lanes_load(const float4* p) { return t0_lanes{{p->x, p->y, p->z, p->w}}; }
inline t0_lanes lanes_splat(float v) { return t0_lanes{{v, v, v, v}}; }
inline t0_lanes lanes_make(float a, float b, float c, float d) { return t0_lanes{{a, b, c, d}}; }
// Returns a `type` (t0_lanes, t0_mask, t0_wide or t0_wide_mask) whose
// lane i is expr.
#define T0_LANEWISE(type, expr)                                   \
    type r;                                                       \
    for (int i = 0; i < (int)(sizeof r.v / sizeof r.v[0]); ++i) { \
        r.v[i] = (expr);                                          \
    }                                                             \
    return r
inline t0_lanes lanes_add(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_lanes, a.v[i] + b.v[i]); }
inline t0_lanes lanes_sub(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_lanes, a.v[i] - b.v[i]); }
inline t0_lanes lanes_mul(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_lanes, a.v[i] * b.v[i]); }
inline t0_lanes lanes_div(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_lanes, a.v[i] / b.v[i]); }
inline t0_lanes lanes_abs(t0_lanes a) { T0_LANEWISE(t0_lanes, std::fabs(a.v[i])); }
inline t0_lanes lanes_min(t0_lanes a, t0_lanes b) {
    T0_LANEWISE(t0_lanes, a.v[i] < b.v[i] ? a.v[i] : b.v[i]);
}
inline t0_lanes lanes_max(t0_lanes a, t0_lanes b) {
    T0_LANEWISE(t0_lanes, a.v[i] > b.v[i] ? a.v[i] : b.v[i]);
}
struct t0_mask {
    int v[4];
};
inline t0_mask lanes_lt(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_mask, a.v[i] < b.v[i] ? -1 : 0); }
inline t0_mask lanes_le(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_mask, a.v[i] <= b.v[i] ? -1 : 0); }
inline t0_mask lanes_eq(t0_lanes a, t0_lanes b) { T0_LANEWISE(t0_mask, a.v[i] == b.v[i] ? -1 : 0); }
inline t0_mask mask_and(t0_mask a, t0_mask b) { T0_LANEWISE(t0_mask, a.v[i] & b.v[i]); }
inline t0_mask mask_or(t0_mask a, t0_mask b) { T0_LANEWISE(t0_mask, a.v[i] | b.v[i]); }
inline t0_mask mask_and_not(t0_mask a, t0_mask b) { T0_LANEWISE(t0_mask, a.v[i] & ~b.v[i]); }
struct t0_wide {
    float v[8];
};
struct t0_wide_mask {
    int v[8];
};
inline t0_wide wide_load(const float4* p) {
    t0_wide r;
    std::memcpy(r.v, glm::value_ptr(p[0]), 4 * sizeof(float));
    std::memcpy(r.v + 4, glm::value_ptr(p[1]), 4 * sizeof(float));
    return r;
}
inline t0_wide wide_splat(float v) { T0_LANEWISE(t0_wide, v); }
inline t0_wide wide_sub(t0_wide a, t0_wide b) { T0_LANEWISE(t0_wide, a.v[i] - b.v[i]); }
inline t0_wide wide_mul(t0_wide a, t0_wide b) { T0_LANEWISE(t0_wide, a.v[i] * b.v[i]); }
inline t0_wide wide_min(t0_wide a, t0_wide b) {
    T0_LANEWISE(t0_wide, a.v[i] < b.v[i] ? a.v[i] : b.v[i]);
}
inline t0_wide wide_max(t0_wide a, t0_wide b) {
    T0_LANEWISE(t0_wide, a.v[i] > b.v[i] ? a.v[i] : b.v[i]);
}
inline t0_wide_mask wide_le(t0_wide a, t0_wide b) {
    T0_LANEWISE(t0_wide_mask, a.v[i] <= b.v[i] ? -1 : 0);
}
#undef T0_LANEWISE
inline int mask_bits(t0_mask m) {
    return (m.v[0] & 1) | (m.v[1] & 2) | (m.v[2] & 4) | (m.v[3] & 8);
}
inline int wide_mask_bits(t0_wide_mask m) {
    int bits = 0;
    for (int i = 0; i < 8; ++i) {
        bits |= (m.v[i] & 1) << i;
    }
    return bits;
}
inline void lanes_store(t0_lanes v, float* out) { std::memcpy(out, v.v, sizeof v.v); }
inline float lanes_first(t0_lanes v) { return v.v[0]; }
inline void wide_store(t0_wide v, float* out) { std::memcpy(out, v.v, sizeof v.v); }
#endif

T0_NAMESPACE_END

#endif

#define T0_PI 3.14159265358979323846f
#define T0_INV_PI 0.31830988618379067154f

#endif
