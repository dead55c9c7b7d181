// Ray/AABB and ray/triangle tests, the flat structure's traversal, and the
// offset that keeps a new ray from hitting the surface it leaves.
#ifndef TRAC0R_KERNEL_INTERSECT_H
#define TRAC0R_KERNEL_INTERSECT_H

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

T0_INLINE Ray make_ray(float3 origin, float3 direction) {
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

// One slab of the slab test: narrows [*t_enter, *t_exit] to where the ray
// is between lo and hi. A ray parallel to the slab (a zero direction
// component, whose inv is the nudged +-1e30) is inside it for every t when
// its origin is in [lo, hi], boundary planes included (bounds are
// conservative), and nowhere otherwise. The general formula cannot say
// this: on the plane hi it gives (hi - origin) * inv = 0, an exit at t = 0.
T0_INLINE void clip_slab(float lo, float hi, float origin, float direction, float inv,
                         float* t_enter, float* t_exit) {
    if (is_parallel_component(direction)) {
        if (origin < lo || origin > hi) {
            *t_exit = -1.0f;
        }
        return;
    }
    // Plain comparisons, not fmin/fmax: nothing here is NaN (inv is finite),
    // and on the CPU fminf is a library call that dominated the profile.
    const float t_lo = (lo - origin) * inv;
    const float t_hi = (hi - origin) * inv;
    const float t_near = t_lo < t_hi ? t_lo : t_hi;
    // Widened by 2 gamma(3) (pbrt-v4, Bounds3::IntersectP): rounding in the
    // two products must not make a ray that grazes a box (or a triangle on
    // its boundary) miss it.
    const float t_far = (t_lo < t_hi ? t_hi : t_lo) * (1.0f + 2.0f * T0_GAMMA3);
    *t_enter = t_near > *t_enter ? t_near : *t_enter;
    *t_exit = t_far < *t_exit ? t_far : *t_exit;
}

// Plain comparisons, not fmin/fmax (see clip_slab); nothing here is NaN.
T0_INLINE float min_f(float a, float b) { return a < b ? a : b; }
T0_INLINE float max_f(float a, float b) { return a < b ? b : a; }

// Slab test over the ray's [0, t_max]: the distance at which the ray enters
// the box (0 when it starts inside), or T0_NO_HIT. inv_direction is finite,
// so no inf * 0 NaN arises.
T0_INLINE float aabb_entry(float3 box_min, float3 box_max, Ray ray, float t_max) {
    if (!ray.any_parallel) {
        // clip_slab on three slabs without its per-axis branch, the same
        // floats (widening each exit or their minimum is one rounding: both
        // monotonic). The BVH's inner loop: 17% more rays per second.
        const float3 t_lo = (box_min - ray.origin) * ray.inv_direction;
        const float3 t_hi = (box_max - ray.origin) * ray.inv_direction;
        const float t_near = max_f(max_f(min_f(t_lo.x, t_hi.x), min_f(t_lo.y, t_hi.y)),
                                   max_f(min_f(t_lo.z, t_hi.z), 0.0f));
        const float t_far =
            min_f(min_f(max_f(t_lo.x, t_hi.x), max_f(t_lo.y, t_hi.y)), max_f(t_lo.z, t_hi.z)) *
            (1.0f + 2.0f * T0_GAMMA3);
        return t_near <= min_f(t_far, t_max) ? t_near : T0_NO_HIT;
    }
    float t_enter = 0.0f;
    float t_exit = t_max;
    clip_slab(box_min.x, box_max.x, ray.origin.x, ray.direction.x, ray.inv_direction.x, &t_enter,
              &t_exit);
    clip_slab(box_min.y, box_max.y, ray.origin.y, ray.direction.y, ray.inv_direction.y, &t_enter,
              &t_exit);
    clip_slab(box_min.z, box_max.z, ray.origin.z, ray.direction.z, ray.inv_direction.z, &t_enter,
              &t_exit);
    return t_enter <= t_exit ? t_enter : T0_NO_HIT;
}

T0_INLINE int intersect_aabb(float3 box_min, float3 box_max, Ray ray, float t_max) {
    return aabb_entry(box_min, box_max, ray, t_max) < T0_NO_HIT;
}

// A triangle vertex in the ray's frame: translated to the origin, axes
// renamed, and sheared so the ray is the +z axis through x = y = 0. x and y
// are exact functions of the vertex and the ray, so every triangle that
// shares the vertex gets the same two floats; z is not yet scaled by 1/d[kz].
T0_INLINE float3 vertex_in_ray_frame(T0_GLOBAL const float4* vertex, Ray ray) {
    const float ax = buffer_component(vertex, ray.kx) - ray.permuted_origin.x;
    const float ay = buffer_component(vertex, ray.ky) - ray.permuted_origin.y;
    const float az = buffer_component(vertex, ray.kz) - ray.permuted_origin.z;
    return make_float3(ax - ray.shear.x * az, ay - ray.shear.y * az, az);
}

// The edge function p.x q.y - p.y q.x where its float value is 0, with
// the exact sign: the two products rounded to the same float (or below the
// smallest), and their difference, whose sign is the test's, was lost. A
// nonzero exact value comes back nonzero, at least FLT_MIN in magnitude (a
// device that flushes subnormals to zero keeps it).
T0_INLINE float nonzero_as_float_min(float value, int negative, int zero) {
    const float tiny = 1.17549435e-38f;  // FLT_MIN
    if (zero) {
        return 0.0f;
    }
    return fabs(value) >= tiny ? value : (negative ? -tiny : tiny);
}

#ifdef T0_HAVE_DOUBLE
// In doubles: a product of two floats is exact in a double, and the
// difference is rounded once, so its sign is exact.
T0_INLINE float exact_edge_double(float px, float py, float qx, float qy) {
    const double e = (double)px * (double)qy - (double)py * (double)qx;
    return nonzero_as_float_min((float)e, e < 0.0, e == 0.0);
}
#endif

// What a float product a b = p leaves out: a b - p, exact (Dekker's
// product with Veltkamp's split, no fused multiply-add: contraction is off)
// for |a|, |b| below 2^115 and a b not within 2^-100 of zero.
T0_INLINE float product_error(float a, float b, float p) {
    const float sa = 4097.0f * a;  // 2^12 + 1: halves of 12 bits
    const float ah = sa - (sa - a);
    const float al = a - ah;
    const float sb = 4097.0f * b;
    const float bh = sb - (sb - b);
    const float bl = b - bh;
    return ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

// In floats, for devices without doubles: where the two products are equal
// floats, the exact difference is the difference of their errors, whose
// float has the right sign (rounding is monotonic).
T0_INLINE float exact_edge_float(float px, float py, float qx, float qy) {
    const float p0 = px * qy;
    const float p1 = py * qx;
    if (p0 != p1) {
        const float d = p0 - p1;  // flushed to zero at worst: the sign is p0's side
        return nonzero_as_float_min(d, p0 < p1, 0);
    }
    const float e = product_error(px, qy, p0) - product_error(py, qx, p1);
    return nonzero_as_float_min(e, e < 0.0f, e == 0.0f);
}

T0_INLINE float exact_edge(float px, float py, float qx, float qy) {
#ifdef T0_HAVE_DOUBLE
    return exact_edge_double(px, py, qx, qy);
#else
    return exact_edge_float(px, py, qx, qy);
#endif
}

// Whether the ray's point (0, 0) is outside the triangle a, b, c of the
// ray's frame (x, y), from its edge functions with each float 0 recomputed
// by exact_edge. Called only for a hit with a zero edge function; out of
// line on the CPU (T0_NOINLINE).
T0_NOINLINE int outside_exactly(float3 a, float3 b, float3 c) {
    float w0 = c.x * b.y - c.y * b.x;
    float w1 = a.x * c.y - a.y * c.x;
    float w2 = b.x * a.y - b.y * a.x;
    w0 = w0 == 0.0f ? exact_edge(c.x, c.y, b.x, b.y) : w0;
    w1 = w1 == 0.0f ? exact_edge(a.x, a.y, c.x, c.y) : w1;
    w2 = w2 == 0.0f ? exact_edge(b.x, b.y, a.x, a.y) : w2;
    return (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) && (w0 > 0.0f || w1 > 0.0f || w2 > 0.0f);
}

// The watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013).
// Returns the distance along the ray, or T0_NO_HIT; the barycentrics of
// the hit (weights of v1 and v2) go to *u, *v. Edges and vertices count as
// inside, and a ray through an edge or vertex shared by several triangles
// hits at least one of them: each edge function is a 2D cross product of
// the two vertices' x, y, which neighbours compute from the same floats in
// swapped order, so their values are exact negatives. Rounding is
// monotonic, so a float edge function never has the wrong sign, but it may
// be 0 where the exact one is not: a small triangle far from the ray (in
// its frame), whose edges are nearly in line with the ray's point, had
// two of three edge functions rounded to 0, and counted as hit 0.7 units
// from the ray (test_stability.cpp). So, as the paper does, a hit with a
// zero is checked again with the zeros recomputed exactly (exact_edge),
// which stay 0 only on the edge's line. Only a hit: the check can only
// take it away (its distance and barycentrics stay the float ones), so the
// packet test, which checks its hits below t_max, agrees lane for lane.
// Needs exact IEEE products and sums: no fused multiply-add contraction
// (compat.h turns it off for OpenCL, -ffp-contract=off for C++).
T0_INLINE float intersect_triangle(T0_GLOBAL const TriangleRecord* tri, Ray ray, float* u,
                                   float* v) {
    const float3 a = vertex_in_ray_frame(&tri->v0, ray);
    const float3 b = vertex_in_ray_frame(&tri->v1, ray);
    const float3 c = vertex_in_ray_frame(&tri->v2, ray);
    // Twice the signed areas of the sub-triangles that the ray's point
    // (0, 0) forms with each edge: proportional to the barycentrics.
    const float weight0 = c.x * b.y - c.y * b.x;
    const float weight1 = a.x * c.y - a.y * c.x;
    const float weight2 = b.x * a.y - b.y * a.x;
    if ((weight0 < 0.0f || weight1 < 0.0f || weight2 < 0.0f) &&
        (weight0 > 0.0f || weight1 > 0.0f || weight2 > 0.0f)) {
        return T0_NO_HIT;
    }
    const int on_edge = weight0 == 0.0f || weight1 == 0.0f || weight2 == 0.0f;
    // det = (e1 x e2) . d / d[kz]: with |d| = 1 it is |e1 x e2| cos / |d[kz]|,
    // so this rejects rays within T0_PARALLEL_COSINE of the plane, relative to
    // the triangle's own size. Not '<=': a NaN det (never expected) misses too,
    // and a zero-area record (pack_scene drops those) is never hit.
    const float det = weight0 + weight1 + weight2;
    if (!(fabs(det) > tri->normal.w * ray.parallel_det) || !(tri->normal.w > 0.0f)) {
        return T0_NO_HIT;
    }
    const float inv_det = 1.0f / det;
    const float t = (weight0 * a.z + weight1 * b.z + weight2 * c.z) * ray.shear.z * inv_det;
    if (!(t > 0.0f)) {
        return T0_NO_HIT;
    }
    if (on_edge && outside_exactly(a, b, c)) {
        return T0_NO_HIT;
    }
    *u = weight1 * inv_det;
    *v = weight2 * inv_det;
    return t;
}

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
    // pointer it had to load first: PoCL frames 2.4 and 3.0 % faster this
    // way (two series), the CPU's the same, for three more splats a ray
    // (README).
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

// A vertex coordinate of a packet's four triangles in the ray's frame: as
// vertex_in_ray_frame, lane for lane.
T0_INLINE t0_lanes packet_coordinate(T0_GLOBAL const TrianglePacket* p, int vertex, int axis) {
    return lanes_load(&p->vertex[3 * vertex + axis]);
}

// One vertex of a packet's four triangles in the ray's frame: as
// vertex_in_ray_frame, lane for lane (the same floats).
typedef struct PacketVertex {
    t0_lanes x;
    t0_lanes y;
    t0_lanes z;
} PacketVertex;

T0_INLINE PacketVertex packet_vertex_in_ray_frame(T0_GLOBAL const TrianglePacket* p, const Ray* ray,
                                                  const RayLanes* l, int vertex) {
    PacketVertex v;
    v.z = lanes_sub(packet_coordinate(p, vertex, ray->kz), l->permuted_origin[2]);
    v.x = lanes_sub(lanes_sub(packet_coordinate(p, vertex, ray->kx), l->permuted_origin[0]),
                    lanes_mul(l->shear[0], v.z));
    v.y = lanes_sub(lanes_sub(packet_coordinate(p, vertex, ray->ky), l->permuted_origin[1]),
                    lanes_mul(l->shear[1], v.z));
    return v;
}

// outside_exactly for triangle i of a packet, its vertices in the ray's
// frame computed as the packet test computes them, lane i.
T0_NOINLINE int packet_outside_exactly(T0_GLOBAL const TrianglePacket* p, const Ray* ray, int i) {
    float3 v[3];
    for (int k = 0; k < 3; ++k) {
        const float x = buffer_component(&p->vertex[3 * k + ray->kx], i) - ray->permuted_origin.x;
        const float y = buffer_component(&p->vertex[3 * k + ray->ky], i) - ray->permuted_origin.y;
        const float z = buffer_component(&p->vertex[3 * k + ray->kz], i) - ray->permuted_origin.z;
        v[k] = make_float3(x - ray->shear.x * z, y - ray->shear.y * z, z);
    }
    return outside_exactly(v[0], v[1], v[2]);
}

// intersect_triangle for the four triangles of a packet at once, with the
// same floats lane for lane: bit i of the result is set when triangle i is
// hit at a distance below t_max (in every lane), which then goes to t[i]
// with its barycentrics to u[i], v[i].
T0_INLINE int intersect_packet(T0_GLOBAL const TrianglePacket* p, const Ray* ray, const RayLanes* l,
                               t0_lanes t_max, float* t, float* u, float* v) {
    const PacketVertex a = packet_vertex_in_ray_frame(p, ray, l, 0);
    const PacketVertex b = packet_vertex_in_ray_frame(p, ray, l, 1);
    const PacketVertex c = packet_vertex_in_ray_frame(p, ray, l, 2);
    const t0_lanes weight0 = lanes_sub(lanes_mul(c.x, b.y), lanes_mul(c.y, b.x));
    const t0_lanes weight1 = lanes_sub(lanes_mul(a.x, c.y), lanes_mul(a.y, c.x));
    const t0_lanes weight2 = lanes_sub(lanes_mul(b.x, a.y), lanes_mul(b.y, a.x));
    const t0_lanes zero = lanes_splat(0.0f);
    // Outside where one weight is negative and another positive: where the
    // smallest is negative and the largest positive. (A NaN weight may be
    // passed over here; it makes det NaN, which fails the next test.)
    const t0_lanes smallest = lanes_min(lanes_min(weight0, weight1), weight2);
    const t0_lanes largest = lanes_max(lanes_max(weight0, weight1), weight2);
    const t0_mask outside = mask_and(lanes_lt(smallest, zero), lanes_lt(zero, largest));
    const t0_lanes det = lanes_add(lanes_add(weight0, weight1), weight2);
    // An unused lane's area is infinite: never below |det|.
    const t0_mask upright =
        lanes_lt(lanes_mul(lanes_load(&p->area), l->parallel_det), lanes_abs(det));
    const t0_lanes inv_det = lanes_div(lanes_splat(1.0f), det);
    const t0_lanes distance =
        lanes_mul(lanes_mul(lanes_add(lanes_add(lanes_mul(weight0, a.z), lanes_mul(weight1, b.z)),
                                      lanes_mul(weight2, c.z)),
                            l->shear[2]),
                  inv_det);
    const t0_mask ahead = mask_and(lanes_lt(zero, distance), lanes_lt(distance, t_max));
    int hits = mask_bits(mask_and_not(mask_and(upright, ahead), outside));
    if (hits != 0) {
        // A hit with a zero edge function (rare; inside, so its smallest
        // or largest is 0) is checked again, as in intersect_triangle.
        // Checked here, for every packet with a hit, this costs 2 % of a
        // BVH frame; checking only the hit a traversal ends with (which
        // may only have come nearer by a false hit), and traversing again
        // where it is outside, cost as much with GCC and twice that with
        // PoCL.
        int check = hits & mask_bits(lanes_eq(lanes_mul(smallest, largest), zero));
        while (check != 0) {
            const int i = lowest_set_bit(check);
            check &= check - 1;
            hits &= packet_outside_exactly(p, ray, i) ? ~(1 << i) : ~0;
        }
        lanes_store(distance, t);
        lanes_store(lanes_mul(weight1, inv_det), u);
        lanes_store(lanes_mul(weight2, inv_det), v);
    }
    return hits;
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

// The thesis' structure: every shape's AABB, then its triangles. Nearest
// hit below t_max; with any_hit, the first one found (shadow rays).
T0_INLINE Hit traverse_flat(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
    Hit hit = no_hit(t_max);
    for (t0_u32 s = 0; s < scene->shape_count; ++s) {
        T0_GLOBAL const ShapeRecord* shape = &scene->shapes[s];
        if (!intersect_aabb(xyz(shape->aabb_min), xyz(shape->aabb_max), *ray, hit.t)) {
            continue;
        }
        const t0_u32 end = shape->range.x + shape->range.y;
        for (t0_u32 i = shape->range.x; i < end; ++i) {
            float u = 0.0f;
            float v = 0.0f;
            const float t = intersect_triangle(&scene->triangles[i], *ray, &u, &v);
            if (t < hit.t) {
                hit.t = t;
                hit.u = u;
                hit.v = v;
                hit.triangle = (int)i;
                if (any_hit) {
                    return hit;
                }
            }
        }
    }
    return hit;
}

// Entries the traversal stack holds: a node leaves at most seven children
// there (its nearest is visited next; all eight may be there for a moment
// while they are put in order), so 7 x the tree's depth in nodes + 1,
// which trac0r/bvh.cpp checks (SAH to binary depth 32, then halving, and
// three binary levels per 8-wide node: at most 21 levels).
#define T0_BVH_STACK_SIZE 148

// Plane p's coordinate of node n's child i (0 to 7): lane i of the plane.
T0_INLINE float node_plane(T0_GLOBAL const BvhNode* n, int p, int i) {
    return buffer_component(&n->bounds[2 * p + (i >> 2)], i & 3);
}

// Node n's child word i (0 to 7): a node index, or T0_BVH_LEAF | a packet.
// The eight words are consecutive: read as one array, not as lane i % 4
// of vector i / 4, which costs three more operations between a node's test
// and the next node's address.
T0_INLINE t0_u32 node_child(T0_GLOBAL const BvhNode* n, int i) {
    return ((T0_GLOBAL const t0_u32*)n->child)[i];
}

// The distances along the ray to the eight planes `offset` bytes into
// n->bounds (the children's planes across `axis`), with inv as the ray's
// inverse direction there.
T0_INLINE t0_wide plane_distances(T0_GLOBAL const BvhNode* n, size_t offset, const RayLanes* l,
                                  int axis, t0_wide inv) {
    T0_GLOBAL const float4* planes =
        (T0_GLOBAL const float4*)((T0_GLOBAL const char*)n->bounds + offset);
    return wide_mul(wide_sub(wide_load(planes), l->origin[axis]), inv);
}

// The ray against the boxes of node n's eight children over [0, t_max]
// (limit: t_max in every lane): bit i of the result is set when it enters
// child i's box, at entry[i] (the others' entries mean nothing).
// aabb_entry, eight boxes per operation, with one difference: the exits are
// widened by taking them with inv_direction (1 + 2 gamma(4)), made once per
// ray, not by multiplying each one by 1 + 2 gamma(3), which is one
// operation less in the chain from a node's load to the choice of the next.
// The factor's own rounding makes four in an exit, three in an entry:
// (1 + u)^3 / (1 - u)^4 < 1 + 8u = 1 + 2 gamma(4) rounded, so an exit is
// still never below an entry that rounding has moved out (pbrt-v4,
// Bounds3::IntersectP).
T0_INLINE int child_entries(T0_GLOBAL const BvhNode* n, const Ray* ray, const RayLanes* l,
                            float t_max, t0_wide limit, float* entry) {
    if (ray->any_parallel) {
        // aabb_entry's slow path, one lane at a time; unused lanes (their
        // box is inverted) are skipped.
        int mask = 0;
        for (int i = 0; i < T0_BVH_WIDTH; ++i) {
            const float3 lo =
                make_float3(node_plane(n, 0, i), node_plane(n, 2, i), node_plane(n, 4, i));
            const float3 hi =
                make_float3(node_plane(n, 1, i), node_plane(n, 3, i), node_plane(n, 5, i));
            const float t = lo.x <= hi.x ? aabb_entry(lo, hi, *ray, t_max) : T0_NO_HIT;
            entry[i] = t;
            mask |= (t < T0_NO_HIT ? 1 : 0) << i;
        }
        return mask;
    }
    // The near plane of each slab is the minimum for a positive direction
    // and the maximum for a negative one: for a box, the same floats as the
    // min and max of aabb_entry (rounding is monotonic), and for an unused
    // lane's inverted box an entry beyond the exit.
    const t0_wide near_x = plane_distances(n, l->near[0], l, 0, l->inv_direction[0]);
    const t0_wide far_x = plane_distances(n, l->far[0], l, 0, l->inv_direction_far[0]);
    const t0_wide near_y = plane_distances(n, l->near[1], l, 1, l->inv_direction[1]);
    const t0_wide far_y = plane_distances(n, l->far[1], l, 1, l->inv_direction_far[1]);
    const t0_wide near_z = plane_distances(n, l->near[2], l, 2, l->inv_direction[2]);
    const t0_wide far_z = plane_distances(n, l->far[2], l, 2, l->inv_direction_far[2]);
    const t0_wide t_near = wide_max(wide_max(near_x, near_y), wide_max(near_z, wide_splat(0.0f)));
    const t0_wide t_far = wide_min(wide_min(far_x, far_y), far_z);
    wide_store(t_near, entry);
    return wide_mask_bits(wide_le(t_near, wide_min(t_far, limit)));
}

// The triangles of leaf packet `packet` in order, as the flat list tests
// them (ties go to the first): the nearest that the ray hits below *limit
// (hit->t in every lane) replaces *hit and narrows *limit. Whether one
// did.
T0_INLINE int leaf_hits(const SceneView* scene, t0_u32 packet, const Ray* ray, const RayLanes* l,
                        t0_lanes* limit, Hit* hit) {
    T0_GLOBAL const TrianglePacket* p = &scene->packets[packet];
    float t[4];
    float u[4];
    float v[4];
    int hits = intersect_packet(p, ray, l, *limit, t, u, v);
    if (hits == 0) {
        return 0;
    }
    do {
        const int i = lowest_set_bit(hits);
        hits &= hits - 1;
        if (t[i] < hit->t) {
            hit->t = t[i];
            hit->u = u[i];
            hit->v = v[i];
            hit->triangle = (int)buffer_uint_component(&p->triangle, i);
        }
    } while (hits != 0);
    *limit = lanes_splat(hit->t);
    return 1;
}

// Nearest hit below t_max through the 8-wide BVH; with any_hit, stops at
// the first hit (shadow rays). Of a node's children that the ray enters,
// the nearest is visited next and the others wait on the stack with their
// entry distances, farthest at the bottom; one is skipped if a hit has come
// closer since.
T0_INLINE Hit traverse_bvh(const SceneView* scene, const Ray* ray, float t_max, int any_hit) {
    Hit hit = no_hit(t_max);
    t0_u32 stack_child[T0_BVH_STACK_SIZE];
    float stack_entry[T0_BVH_STACK_SIZE];
    int top = 0;
    const RayLanes lanes = make_ray_lanes(*ray);
    t0_lanes limit = lanes_splat(t_max);     // hit.t in every lane of a packet
    t0_wide node_limit = wide_splat(t_max);  // and of a node
    t0_u32 child = 0u;  // what is visited: node 0, the root, or a leaf (T0_BVH_LEAF)
    for (;;) {
        if ((child & T0_BVH_LEAF) != 0u) {
            if (leaf_hits(scene, child & ~T0_BVH_LEAF, ray, &lanes, &limit, &hit)) {
                if (any_hit) {
                    return hit;
                }
                node_limit = wide_splat(hit.t);
            }
        } else {
            T0_GLOBAL const BvhNode* n = &scene->nodes[child];
            float entry[T0_BVH_WIDTH];
            const int mask = child_entries(n, ray, &lanes, hit.t, node_limit, entry);
            if (mask != 0) {
                const int first = lowest_set_bit(mask);
                const int rest = mask & (mask - 1);
                if (T0_ONE_CHILD_APART && rest == 0) {
                    // One child entered (most nodes): no sort.
                    child = node_child(n, first);
                    continue;
                }
                if ((rest & (rest - 1)) == 0) {
                    // Two: the farther waits. Or one (T0_ONE_CHILD_APART
                    // 0), taken as two of the same child: it is written
                    // above the top of the stack and not counted, and the
                    // next push overwrites it.
                    const int second = lowest_set_bit(rest != 0 ? rest : mask);
                    const int first_nearer = entry[first] <= entry[second];
                    const int near = first_nearer ? first : second;
                    const int far = first_nearer ? second : first;
                    stack_child[top] = node_child(n, far);
                    stack_entry[top] = entry[far];
                    top += rest != 0 ? 1 : 0;
                    child = node_child(n, near);
                    continue;
                }
                // Three or more: each is inserted into the stack above the
                // ones farther than it, so the nearest ends on top, and is
                // visited next.
                const int bottom = top;
                for (int m = mask; m != 0; m &= m - 1) {
                    const int i = lowest_set_bit(m);
                    const float e = entry[i];
                    int k = top;
                    while (k > bottom && stack_entry[k - 1] < e) {
                        stack_entry[k] = stack_entry[k - 1];
                        stack_child[k] = stack_child[k - 1];
                        --k;
                    }
                    stack_entry[k] = e;
                    stack_child[k] = node_child(n, i);
                    ++top;
                }
                --top;
                child = stack_child[top];
                continue;
            }
        }
        // Pop the next subtree that can still hold a nearer hit.
        for (;;) {
            if (top == 0) {
                return hit;
            }
            --top;
            if (stack_entry[top] < hit.t) {
                child = stack_child[top];
                break;
            }
        }
    }
}

// Rays that share an origin (a tile's camera rays), bounded together:
// per axis the least and the greatest of their inverse directions (none
// parallel: Ray.any_parallel rays are left out of a bundle).
typedef struct RayBundle {
    float3 origin;
    float3 inv_min;
    float3 inv_max;
    int rays;  // how many rays the bounds hold
} RayBundle;

T0_INLINE void bundle_start(RayBundle* b, float3 origin) {
    b->origin = origin;
    b->inv_min = float3_splat(0.0f);
    b->inv_max = float3_splat(0.0f);
    b->rays = 0;
}

// Adds a ray that starts at b->origin, bit for bit (the bounds are exact
// only so: a tile's camera rays start at the camera's position), is not
// parallel to an axis (Ray.any_parallel), and has inverse direction inv
// (Ray.inv_direction).
T0_INLINE void bundle_add(RayBundle* b, float3 inv) {
    if (b->rays == 0) {
        b->inv_min = inv;
        b->inv_max = inv;
    } else {
        b->inv_min = make_float3(min_f(b->inv_min.x, inv.x), min_f(b->inv_min.y, inv.y),
                                 min_f(b->inv_min.z, inv.z));
        b->inv_max = make_float3(max_f(b->inv_max.x, inv.x), max_f(b->inv_max.y, inv.y),
                                 max_f(b->inv_max.z, inv.z));
    }
    ++b->rays;
}

// Whether the bounds along `axis` may be used: every ray's inverse
// direction there of one sign.
T0_INLINE int bundle_axis_usable(const RayBundle* b, int axis) {
    return component3(b->inv_min, axis) > 0.0f || component3(b->inv_max, axis) < 0.0f;
}

// A leaf that some ray of a bundle may enter, and a lower bound of the
// distance at which any of them enters its box.
typedef struct LeafCandidate {
    t0_u32 packet;
    float entry;
} LeafCandidate;

// The most leaves a bundle keeps; a bundle that meets more is not used.
#define T0_BUNDLE_LEAVES 16

// Over the eight children of node n, for one usable axis of the bundle:
// the least distance at which any of its rays meets each child's near
// plane, and the greatest at which any meets its far plane. A ray's own
// distances in child_entries are (plane - origin) * inv and (plane -
// origin) * inv_far, rounded; rounding is monotonic, so over the rays their
// least and greatest are those of the two extreme inverses: the same
// floats, no margin needed.
T0_INLINE void bundle_axis(T0_GLOBAL const BvhNode* n, const RayBundle* b, int axis,
                           t0_wide* near_lo, t0_wide* far_hi) {
    const float inv_min = component3(b->inv_min, axis);
    const float inv_max = component3(b->inv_max, axis);
    const size_t plane = 2 * sizeof(float4);
    // As make_ray_lanes: minima first for a positive direction.
    const size_t near = (size_t)(2 * axis + (inv_max < 0.0f ? 1 : 0)) * plane;
    const size_t far = (size_t)(4 * axis + 1) * plane - near;
    const t0_wide origin = wide_splat(component3(b->origin, axis));
    const float widen = 1.0f + 2.0f * T0_GAMMA4;
    T0_GLOBAL const float4* near_planes =
        (T0_GLOBAL const float4*)((T0_GLOBAL const char*)n->bounds + near);
    T0_GLOBAL const float4* far_planes =
        (T0_GLOBAL const float4*)((T0_GLOBAL const char*)n->bounds + far);
    const t0_wide to_near = wide_sub(wide_load(near_planes), origin);
    const t0_wide to_far = wide_sub(wide_load(far_planes), origin);
    *near_lo =
        wide_min(wide_mul(to_near, wide_splat(inv_min)), wide_mul(to_near, wide_splat(inv_max)));
    *far_hi = wide_max(wide_mul(to_far, wide_splat(inv_min * widen)),
                       wide_mul(to_far, wide_splat(inv_max * widen)));
}

// The BVH's leaves that a ray of bundle b may enter, with a lower bound of
// each one's entry, nearest first, into out[0, T0_BUNDLE_LEAVES): their
// count, or -1 where there are more (a wide bundle; its rays traverse the
// tree one by one). A child is left out only where its box's entry bound
// lies beyond its exit bound, so a ray that child_entries would take into a
// leaf finds it here; with it every triangle that ray hits.
T0_INLINE int bundle_leaves(const SceneView* scene, const RayBundle* b,
                            T0_LOCAL LeafCandidate* out) {
    t0_u32 stack[T0_BVH_STACK_SIZE];
    int top = 0;
    int count = 0;
    stack[top++] = 0u;
    while (top > 0) {
        T0_GLOBAL const BvhNode* n = &scene->nodes[stack[--top]];
        t0_wide entry = wide_splat(0.0f);
        t0_wide exit = wide_splat(T0_INFINITY);
        for (int axis = 0; axis < 3; ++axis) {
            if (bundle_axis_usable(b, axis)) {
                t0_wide near_lo;
                t0_wide far_hi;
                bundle_axis(n, b, axis, &near_lo, &far_hi);
                entry = wide_max(entry, near_lo);
                exit = wide_min(exit, far_hi);
            }
        }
        float entries[T0_BVH_WIDTH];
        wide_store(entry, entries);
        for (int m = wide_mask_bits(wide_le(entry, exit)); m != 0; m &= m - 1) {
            const int i = lowest_set_bit(m);
            const t0_u32 child = node_child(n, i);
            if ((child & T0_BVH_LEAF) == 0u) {
                stack[top++] = child;
                continue;
            }
            if (count == T0_BUNDLE_LEAVES) {
                return -1;
            }
            // Kept in order of entry (insertion; ties keep the order found).
            int k = count++;
            while (k > 0 && out[k - 1].entry > entries[i]) {
                out[k] = out[k - 1];
                --k;
            }
            out[k].packet = child & ~T0_BVH_LEAF;
            out[k].entry = entries[i];
        }
    }
    return count;
}

// The leaves that the rays of bundle b may enter (bundle_leaves), or -1
// where it cannot be used (no ray, no axis along which all have one sign,
// or more leaves than T0_BUNDLE_LEAVES).
T0_INLINE int bundle_finish_leaves(const SceneView* scene, const RayBundle* b,
                                   T0_LOCAL LeafCandidate* out) {
    const int usable =
        bundle_axis_usable(b, 0) || bundle_axis_usable(b, 1) || bundle_axis_usable(b, 2);
    return b->rays > 0 && usable ? bundle_leaves(scene, b, out) : -1;
}

// The nearest hit of a ray of a bundle among the bundle's leaves
// (bundle_leaves): traverse_bvh's hit, found without the tree. The leaves
// are tested nearest bound first, up to the first whose bound is not below
// the hit (as traverse_bvh pops its stack), each with traverse_bvh's packet
// test: the same floats. The two test the leaves in different orders, so
// only where two triangles of different leaves are hit within rounding of
// each other (an edge they share; a triangle in the face of its flat leaf
// box, whose hit may lie an ulp before the box's entry) may they pick
// different ones: both are hits there.
T0_INLINE Hit intersect_bundle_leaves(const SceneView* scene, T0_LOCAL const LeafCandidate* leaves,
                                      int count, const Ray* ray) {
    Hit hit = no_hit(T0_NO_HIT);
    const RayLanes lanes = make_ray_lanes(*ray);
    t0_lanes limit = lanes_splat(T0_NO_HIT);
    for (int k = 0; k < count && leaves[k].entry < hit.t; ++k) {
        leaf_hits(scene, leaves[k].packet, ray, &lanes, &limit, &hit);
    }
    return hit;
}

T0_INLINE Hit intersect_scene(const SceneView* scene, const Ray* ray) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_BVH)) {
        return traverse_bvh(scene, ray, T0_NO_HIT, 0);
    }
    return traverse_flat(scene, ray, T0_NO_HIT, 0);
}

// Whether anything lies on the ray before t_max.
T0_INLINE int occluded(const SceneView* scene, const Ray* ray, float t_max) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_BVH)) {
        return traverse_bvh(scene, ray, t_max, 1).triangle >= 0;
    }
    return traverse_flat(scene, ray, t_max, 1).triangle >= 0;
}

// How far a new ray's origin moves off its surface, per unit of the hit's
// magnitude: 8 eps (eps = 2^-24, the unit roundoff). hit_position's terms
// pass through at most four roundings (an edge, its product with a
// barycentric, two sums), so each coordinate is within gamma(4) magnitude
// of a point of the plane, and the point within |n|_1 gamma(4) <= 6.93 eps
// magnitude of the plane (pbrt-v4, section 6.8.5). The rest (1 eps magnitude)
// is what the triangle test from the moved origin must resolve; its vertex
// differences are exact near the origin (Sterbenz), and test_stability.cpp
// checks grazing rays at several scales and distances.
// Ray Tracing Gems' 256 ULPs (ch. 6) is 32 times more: at 1e5 from the
// origin, 2 units, enough to jump through a wall of a room of size 2.
#define T0_RAY_OFFSET_PER_MAGNITUDE (8.0f * 5.9604645e-8f)

// Plain comparisons (max_f): the points and vertices here are finite.
T0_INLINE float max_abs3(float3 a) {
    const float3 m = vabs3(a);
    return max_f(m.x, max_f(m.y, m.z));
}

// The size of the numbers a point of the triangle is computed from.
T0_INLINE float vertices_magnitude(float3 v0, float3 v1, float3 v2) {
    return max_abs3(v0) + max_abs3(v1 - v0) + max_abs3(v2 - v0);
}

// The same, computed when the record was made.
T0_INLINE float triangle_magnitude(T0_GLOBAL const TriangleRecord* tri) {
    return bits_float((int)tri->ids.w);
}

// The lower bounds of hit_position's barycentric weights (below) for the
// triangle v0 v1 v2: for vertex k, the edge opposite it. They depend on the
// triangle alone, so they are computed once, when it is packed
// (make_triangle_record), and kept in the vertices' w.
T0_INLINE float3 triangle_edge_pulls(float3 v0, float3 v1, float3 v2, float twice_area,
                                     float magnitude) {
    const float pull_per_area = T0_RAY_OFFSET_PER_MAGNITUDE * magnitude / twice_area;
    if (!(pull_per_area < 1e30f)) {
        // An area so small that a device flushing denormals takes it for 0
        // (inf pull, then inf / inf), or none: equal weights, the centroid.
        return float3_splat(1.0f);
    }
    return make_float3(length(v2 - v1) * pull_per_area, length(v2 - v0) * pull_per_area,
                       length(v1 - v0) * pull_per_area);
}

// A triangle as the kernels read it: normal is unit, twice_area |e1 x e2|.
T0_INLINE TriangleRecord make_triangle_record(float3 v0, float3 v1, float3 v2, float3 normal,
                                              float twice_area, t0_u32 material, t0_u32 shape) {
    const float magnitude = vertices_magnitude(v0, v1, v2);
    const float3 pull = triangle_edge_pulls(v0, v1, v2, twice_area, magnitude);
    TriangleRecord r;
    r.v0 = make_float4(v0.x, v0.y, v0.z, pull.x);
    r.v1 = make_float4(v1.x, v1.y, v1.z, pull.y);
    r.v2 = make_float4(v2.x, v2.y, v2.z, pull.z);
    r.normal = make_float4(normal.x, normal.y, normal.z, twice_area);
    r.ids = make_uint4(material, shape, T0_NO_LIGHT, (t0_u32)float_bits(magnitude));
    return r;
}

// The hit point from the barycentrics (more accurate than origin + t dir),
// kept at least the offset distance inside each edge. Rounding can put the
// computed point on an edge, which on a closed mesh is the plane of the
// neighbouring face (a box's edge); a new ray from there through that face
// finds it at t = 0, no hit, and slips out. A barycentric weight is the
// distance from the opposite edge over the height onto it (2 area / edge
// length), so raising each to pull |edge| / (2 area) keeps the point pull
// away from every edge, and moves only points that were nearer (a tiny
// triangle's go to its centroid). Moving all points, say towards the
// centroid, would make paths drift (+9 % light in a room at 1e5). The point
// is still v0 + e1 b1 + e2 b2, as close to the plane as before. The raised
// weights' bounds are in the vertices' w (triangle_edge_pulls).
T0_INLINE float3 hit_position(T0_GLOBAL const TriangleRecord* tri, Hit hit) {
    const float3 v0 = xyz(tri->v0);
    const float3 e1 = xyz(tri->v1) - v0;
    const float3 e2 = xyz(tri->v2) - v0;
    // max_f(bound, weight): as fmax, the bound where a weight is NaN (a
    // bound never is), in one instruction.
    const float w0 = max_f(tri->v0.w, 1.0f - hit.u - hit.v);
    const float w1 = max_f(tri->v1.w, hit.u);
    const float w2 = max_f(tri->v2.w, hit.v);
    const float sum = w0 + w1 + w2;
    return v0 + e1 * (w1 / sum) + e2 * (w2 / sum);
}

// The magnitude of the numbers the hit point was computed from.
T0_INLINE float hit_magnitude(T0_GLOBAL const TriangleRecord* tri, float3 position) {
    return max_f(triangle_magnitude(tri), max_abs3(position));  // as fmax (see hit_position)
}

// The next float after x in the direction of the sign of towards (nonzero).
// From 0 it steps to the smallest normal float: denormals may be flushed.
// The step is unsigned: OpenCL computes it for x = -0 too (choose_f), where
// a signed step down would overflow.
T0_INLINE float next_float_towards(float x, float towards) {
    const t0_u32 bits = (t0_u32)float_bits(x);
    return choose_f(x == 0.0f, copysign(1.17549435e-38f, towards),
                    bits_float((int)((x > 0.0f) == (towards > 0.0f) ? bits + 1u : bits - 1u)));
}

// One coordinate moved by n * distance, then one float further, so that
// rounding never shortens the move (pbrt-v4's OffsetRayOrigin).
T0_INLINE float offset_coordinate(float p, float n, float distance) {
    return choose_f(n == 0.0f, p, next_float_towards(p + n * distance, n));
}

// Moves p off its surface along unit n (pointing to the side the new ray
// leaves into) by T0_RAY_OFFSET_PER_MAGNITUDE * magnitude or a little more:
// an offset that grows with the hit point's magnitude (hit_magnitude), so
// it beats the rounding error of the hit point at every scale and every
// distance from the origin, and stays far below the scene's features.
T0_INLINE float3 offset_ray_origin(float3 p, float3 n, float magnitude) {
    const float distance = T0_RAY_OFFSET_PER_MAGNITUDE * magnitude;
    return make_float3(offset_coordinate(p.x, n.x, distance), offset_coordinate(p.y, n.y, distance),
                       offset_coordinate(p.z, n.z, distance));
}

T0_NAMESPACE_END

#endif
