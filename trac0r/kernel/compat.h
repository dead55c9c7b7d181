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

// No silent fused multiply-adds: the C++ build has none either (baseline
// x86-64), and the compensated sums in accumulate.h rely on exact rounding.
#pragma OPENCL FP_CONTRACT OFF

#define T0_GLOBAL __global
#define T0_INLINE inline
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
// Component k (0, 1, 2) of a vector in a buffer, read as a scalar: vector
// types have no run-time component index in OpenCL C.
T0_INLINE float buffer_component(__global const float4* v, int k) {
    return ((__global const float*)v)[k];
}

#else  // C++

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#define T0_GLOBAL
#define T0_INLINE inline
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
using std::fmax;
using std::fmin;
using std::sin;
using std::sqrt;

inline float3 make_float3(float x, float y, float z) { return float3(x, y, z); }
inline float4 make_float4(float x, float y, float z, float w) { return float4(x, y, z, w); }
inline uint4 make_uint4(t0_u32 x, t0_u32 y, t0_u32 z, t0_u32 w) { return uint4(x, y, z, w); }
inline float3 float3_splat(float v) { return float3(v); }
inline float3 xyz(float4 v) { return float3(v); }
inline float3 vmin3(float3 a, float3 b) {
    return float3(std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z));
}
inline float3 vmax3(float3 a, float3 b) {
    return float3(std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z));
}
inline float3 vabs3(float3 a) { return glm::abs(a); }
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

T0_NAMESPACE_END

#endif

#define T0_PI 3.14159265358979323846f
#define T0_INV_PI 0.31830988618379067154f

#endif
