// Vectors of four floats (t0_lanes: a packet's four triangles) and of
// eight (t0_wide: a BVH node's eight children), and their lane masks.
#ifndef TRAC0R_KERNEL_LANES_H
#define TRAC0R_KERNEL_LANES_H

#include "compat.h"

#ifdef __OPENCL_VERSION__

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
// Not two of the four above, as C++ makes them (below): that would give
// up the one AVX instruction.
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
// Lane i of v (0 to 7), by choices rather than through memory: a GPU keeps
// v in registers.
T0_INLINE float wide_lane(t0_wide v, int i) {
    const float4 four = (i & 4) != 0 ? v.hi : v.lo;
    const float2 two = (i & 2) != 0 ? four.hi : four.lo;
    return (i & 1) != 0 ? two.y : two.x;
}
// The index of the lowest set bit of m (m != 0): the first lane of a mask's
// bits.
T0_INLINE int lowest_set_bit(int m) { return 31 - (int)clz(m & -m); }
// The index of the highest set bit of m (m != 0).
T0_INLINE int highest_set_bit(int m) { return 31 - (int)clz(m); }

#else  // C++

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

T0_NAMESPACE_BEGIN

// The index of the lowest set bit of m (m != 0), as the OpenCL side's.
inline int lowest_set_bit(int m) { return __builtin_ctz(static_cast<unsigned>(m)); }
inline int highest_set_bit(int m) { return 31 - __builtin_clz(static_cast<unsigned>(m)); }

// Four floats that one instruction works on (see the OpenCL side): SSE,
// which every x86-64 CPU has, or a plain array elsewhere. Not OpenCL's
// own code: its float4 has operators and select, SSE has intrinsics, and
// the array needs a loop; what each writes differs, not what it computes.
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
#else
struct t0_lanes {
    float v[4];
};
inline t0_lanes lanes_load(const float4* p) { return t0_lanes{{p->x, p->y, p->z, p->w}}; }
inline t0_lanes lanes_splat(float v) { return t0_lanes{{v, v, v, v}}; }
inline t0_lanes lanes_make(float a, float b, float c, float d) { return t0_lanes{{a, b, c, d}}; }
// Returns a `type` (t0_lanes or t0_mask) whose lane i is expr.
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
#undef T0_LANEWISE
inline int mask_bits(t0_mask m) {
    return (m.v[0] & 1) | (m.v[1] & 2) | (m.v[2] & 4) | (m.v[3] & 8);
}
inline void lanes_store(t0_lanes v, float* out) { std::memcpy(out, v.v, sizeof v.v); }
inline float lanes_first(t0_lanes v) { return v.v[0]; }
#endif

// Eight floats (see the OpenCL side): two of the four above, lanes 0-3 and
// 4-7, the same on SSE and elsewhere.
struct t0_wide {
    t0_lanes lo;
    t0_lanes hi;
};
struct t0_wide_mask {
    t0_mask lo;
    t0_mask hi;
};
inline t0_wide wide_load(const float4* p) { return t0_wide{lanes_load(p), lanes_load(p + 1)}; }
inline t0_wide wide_splat(float v) { return t0_wide{lanes_splat(v), lanes_splat(v)}; }
inline t0_wide wide_sub(t0_wide a, t0_wide b) {
    return t0_wide{lanes_sub(a.lo, b.lo), lanes_sub(a.hi, b.hi)};
}
inline t0_wide wide_mul(t0_wide a, t0_wide b) {
    return t0_wide{lanes_mul(a.lo, b.lo), lanes_mul(a.hi, b.hi)};
}
inline t0_wide wide_min(t0_wide a, t0_wide b) {
    return t0_wide{lanes_min(a.lo, b.lo), lanes_min(a.hi, b.hi)};
}
inline t0_wide wide_max(t0_wide a, t0_wide b) {
    return t0_wide{lanes_max(a.lo, b.lo), lanes_max(a.hi, b.hi)};
}
inline t0_wide_mask wide_le(t0_wide a, t0_wide b) {
    return t0_wide_mask{lanes_le(a.lo, b.lo), lanes_le(a.hi, b.hi)};
}
inline int wide_mask_bits(t0_wide_mask m) { return mask_bits(m.lo) | (mask_bits(m.hi) << 4); }
inline void wide_store(t0_wide v, float* out) {
    lanes_store(v.lo, out);
    lanes_store(v.hi, out + 4);
}
inline float wide_lane(t0_wide v, int i) {
    float lanes[8];
    wide_store(v, lanes);
    return lanes[i];
}

T0_NAMESPACE_END

#endif

#endif
