// The few differences between the two compilers of the kernel headers: the
// types (float3, t0_u64), the qualifiers (T0_GLOBAL, T0_INLINE) and the
// scalar helpers whose spelling differs.
//
// Every file in trac0r/kernel/ is compiled twice: as C++14 (included by the
// OpenMP backend and the tests) and as OpenCL C 1.2 (embedded into the
// library and built by the OpenCL backend). This header, lanes.h (vectors
// of four and eight floats) and tuning.h (what each compiler was faster
// with) are the only places that know which one is running; the rest is
// written in the subset both accept: POD structs, free functions, no
// references, templates or virtuals.
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
#define T0_CONSTANT __constant
#define T0_INLINE inline __attribute__((always_inline))
#define T0_FORCE_INLINE T0_INLINE
#define T0_OUT_OF_LINE T0_INLINE
#define T0_ALIGN16
#define T0_NAMESPACE_BEGIN
#define T0_NAMESPACE_END
#define T0_STATIC_ASSERT_SIZE(type, bytes)

typedef ulong t0_u64;
typedef uint t0_u32;

#define atan2_float atan2
#define make_float2(x, y) ((float2)((x), (y)))
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
// Component k (0, 1, 2) of a vector in a buffer, read as a scalar: vector
// types have no run-time component index in OpenCL C.
T0_INLINE float buffer_component(__global const float4* v, int k) {
    return ((__global const float*)v)[k];
}
T0_INLINE t0_u32 buffer_uint_component(__global const uint4* v, int k) {
    return ((__global const uint*)v)[k];
}
#define T0_INFINITY INFINITY

#else  // C++

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#define T0_GLOBAL
#define T0_LOCAL
// A table at file scope: OpenCL's constant memory, a C++ constant.
#define T0_CONSTANT static const
#define T0_INLINE inline
// Inlined even where the compiler would not: the sampler's draws, whose
// chains of multiplies overlap only when they sit side by side.
#define T0_FORCE_INLINE inline __attribute__((always_inline))
// Kept out of line on the CPU: a rarely taken branch's body (the
// microfacet materials) that would otherwise make its caller too large
// to inline where the common branches run.
#define T0_OUT_OF_LINE inline __attribute__((noinline))
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
typedef glm::vec2 float2;
typedef glm::vec3 float3;
typedef glm::vec4 float4;
typedef glm::uvec4 uint4;

using glm::cross;
using glm::dot;
using glm::length;
using glm::normalize;
using std::copysign;
using std::cos;
using std::exp;
using std::fabs;
using std::floor;
using std::sin;
using std::sqrt;

// fmax and fmin with their C99 meaning (a NaN argument gives the other),
// written out: std::fmax is a call into libm unless -ffast-math lets the
// compiler assume no NaN, and these sit in every path's inner loop.
inline float fmax(float a, float b) { return a > b || b != b ? a : b; }
inline float fmin(float a, float b) { return a < b || b != b ? a : b; }

// atan2 in float, as OpenCL C's (unqualified here, atan2 is the C
// library's, in double).
inline float atan2_float(float y, float x) { return std::atan2(y, x); }
inline float2 make_float2(float x, float y) { return float2(x, y); }
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
// glm's own view of a vector as an array of its components.
inline float buffer_component(const float4* v, int k) { return glm::value_ptr(*v)[k]; }
inline t0_u32 buffer_uint_component(const uint4* v, int k) { return glm::value_ptr(*v)[k]; }
#define T0_INFINITY HUGE_VALF

T0_NAMESPACE_END

#endif

#define T0_PI 3.14159265358979323846f
#define T0_INV_PI 0.31830988618379067154f

#endif
