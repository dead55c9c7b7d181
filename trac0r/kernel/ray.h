// A ray with what the intersection tests compute once per ray (make_ray,
// and make_ray_lanes for the vector tests), and a hit.
#ifndef TRAC0R_KERNEL_RAY_H
#define TRAC0R_KERNEL_RAY_H

#include "lanes.h"
#include "tuning.h"
#include "types.h"

// A ray is parallel to a triangle when |cos(angle to its plane's normal)|
// is below this: relative to the triangle's own size, so the test behaves
// the same at every scene scale.
#define T0_PARALLEL_COSINE 1e-7f
#define T0_NO_HIT 3.402823e38f
// gamma(n) = n eps / (1 - n eps), eps = 2^-24: the bound on the relative
// rounding error of n float operations (pbrt-v4, section 6.8.1).
#define T0_GAMMA3 (3.0f * 5.9604645e-8f / (1.0f - 3.0f * 5.9604645e-8f))
#define T0_GAMMA4 (4.0f * 5.9604645e-8f / (1.0f - 4.0f * 5.9604645e-8f))

T0_NAMESPACE_BEGIN

typedef struct Ray {
    float3 origin;
    float3 direction;      // unit length, to a few ulps
    float3 inv_direction;  // finite: zero components are nudged to +-1e-30
    // For the watertight triangle test, computed once per ray (Woop, Benthin
    // and Wald, JCGT 2013): the axes renamed so that kz is the direction's
    // largest component, the shear that maps the direction to +z, and the
    // origin in that axis order.
    int kx;
    int ky;
    int kz;
    float3 shear;            // d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz]
    float3 permuted_origin;  // origin[kx], origin[ky], origin[kz]
    float parallel_det;      // T0_PARALLEL_COSINE |1 / d[kz]|: see intersect_triangle
    int any_parallel;        // a zero direction component: aabb_entry's slow path
} Ray;

typedef struct Hit {
    float t;
    float u;
    float v;
    int triangle;  // -1: nothing was hit
} Hit;

T0_INLINE int is_parallel_component(float d) { return !(fabs(d) > 1e-30f); }

// d, or +-1e-30 where d is (nearly) zero: the divisor for 1 / d.
T0_INLINE float nudged_divisor(float d) {
    return is_parallel_component(d) ? copysign(1e-30f, d) : d;
}

T0_FORCE_INLINE Ray make_ray(float3 origin, float3 direction) {
    Ray r;
    r.origin = origin;
    r.direction = direction;
    // The three inverses in one four-lane division (a division costs as
    // much as four).
    float inv[4];
    lanes_store(lanes_div(lanes_splat(1.0f),
                          lanes_make(nudged_divisor(direction.x), nudged_divisor(direction.y),
                                     nudged_divisor(direction.z), 1.0f)),
                inv);
    r.inv_direction = make_float3(inv[0], inv[1], inv[2]);
    const float3 a = vabs3(direction);
    r.kz = largest_axis(a);
    r.kx = next_axis(r.kz);
    r.ky = next_axis(r.kx);
    // d[kz] is the largest component, never nudged: inv[kz] = 1 / d[kz].
    const float inv_dz = inv[r.kz];
    r.shear = make_float3(component3(direction, r.kx) * inv_dz,
                          component3(direction, r.ky) * inv_dz, inv_dz);
    r.permuted_origin =
        make_float3(component3(origin, r.kx), component3(origin, r.ky), component3(origin, r.kz));
    r.parallel_det = T0_PARALLEL_COSINE * fabs(inv_dz);
    r.any_parallel = is_parallel_component(direction.x) || is_parallel_component(direction.y) ||
                     is_parallel_component(direction.z);
    return r;
}

// No hit yet: nothing nearer than t_max.
T0_INLINE Hit no_hit(float t_max) {
    Hit hit;
    hit.t = t_max;
    hit.u = 0.0f;
    hit.v = 0.0f;
    hit.triangle = -1;
    return hit;
}

// Plain comparisons, not fmin/fmax (see clip_slab, kernel/aabb.h); nothing
// the tests compare is NaN.
T0_INLINE float min_f(float a, float b) { return a < b ? a : b; }
T0_INLINE float max_f(float a, float b) { return a < b ? b : a; }

// The numbers of a ray that the BVH's vector tests use, each in every
// lane: made once per traversal, not once per node. The node test works on
// eight lanes (a node's children), the packet test on four (its triangles).
typedef struct RayLanes {
    t0_wide origin[3];
    t0_wide inv_direction[3];
    // inv_direction widened by 2 gamma(4), for the far planes (see
    // child_entries).
    t0_wide inv_direction_far[3];
    // The origin in the triangle test's axis order (Ray.permuted_origin),
    // read by fixed index. Indexed by the ray's axes at run time, LLVM
    // (PoCL) kept this struct in memory and reached each vector through a
    // pointer it had to load first; so three more splats a ray
    // (kernel/tuning.h).
    t0_lanes permuted_origin[3];
    t0_lanes shear[3];
    t0_lanes parallel_det;
    // Per axis, where in a node the eight lanes of the plane are that the
    // ray enters (near) and leaves (far) through, as a byte offset (an
    // address, not an index, to compute per node): the minima for a
    // positive direction component, the maxima for a negative one.
    size_t near[3];
    size_t far[3];
} RayLanes;

// Each component of v in all four lanes: out[0..2].
T0_INLINE void splat3(float3 v, t0_lanes* out) {
    out[0] = lanes_splat(v.x);
    out[1] = lanes_splat(v.y);
    out[2] = lanes_splat(v.z);
}

// Each component of v in all eight lanes: out[0..2].
T0_INLINE void wide_splat3(float3 v, t0_wide* out) {
    out[0] = wide_splat(v.x);
    out[1] = wide_splat(v.y);
    out[2] = wide_splat(v.z);
}

T0_INLINE RayLanes make_ray_lanes(Ray ray) {
    RayLanes l;
    wide_splat3(ray.origin, l.origin);
    wide_splat3(ray.inv_direction, l.inv_direction);
    wide_splat3(ray.inv_direction * (1.0f + 2.0f * T0_GAMMA4), l.inv_direction_far);
    splat3(ray.permuted_origin, l.permuted_origin);
    splat3(ray.shear, l.shear);
    l.parallel_det = lanes_splat(ray.parallel_det);
    // Plane p's eight lanes are 2 p float4s into BvhNode.bounds.
    const size_t plane = 2 * sizeof(float4);
    l.near[0] = ray.inv_direction.x < 0.0f ? 1 * plane : 0 * plane;
    l.near[1] = ray.inv_direction.y < 0.0f ? 3 * plane : 2 * plane;
    l.near[2] = ray.inv_direction.z < 0.0f ? 5 * plane : 4 * plane;
    l.far[0] = 1 * plane - l.near[0];
    l.far[1] = 5 * plane - l.near[1];
    l.far[2] = 9 * plane - l.near[2];
    return l;
}

T0_NAMESPACE_END

#endif
