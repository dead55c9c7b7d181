// The watertight ray/triangle test, for one triangle (intersect_triangle)
// and for a packet of four at once (intersect_packet).
#ifndef TRAC0R_KERNEL_TRIANGLE_H
#define TRAC0R_KERNEL_TRIANGLE_H

#include "lanes.h"
#include "ray.h"
#include "tuning.h"
#include "types.h"

T0_NAMESPACE_BEGIN

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

// Vertex k of triangle i of a packet in the ray's frame, computed as the
// packet test computes it, lane i (packet_vertex_in_ray_frame).
T0_INLINE float3 packet_lane_vertex(T0_GLOBAL const TrianglePacket* p, const Ray* ray, int i,
                                    int k) {
    const float x = buffer_component(&p->vertex[3 * k + ray->kx], i) - ray->permuted_origin.x;
    const float y = buffer_component(&p->vertex[3 * k + ray->ky], i) - ray->permuted_origin.y;
    const float z = buffer_component(&p->vertex[3 * k + ray->kz], i) - ray->permuted_origin.z;
    return make_float3(x - ray->shear.x * z, y - ray->shear.y * z, z);
}

// outside_exactly for triangle i of a packet, its vertices in the ray's
// frame computed as the packet test computes them, lane i.
T0_NOINLINE int packet_outside_exactly(T0_GLOBAL const TrianglePacket* p, const Ray* ray, int i) {
    return outside_exactly(packet_lane_vertex(p, ray, i, 0), packet_lane_vertex(p, ray, i, 1),
                           packet_lane_vertex(p, ray, i, 2));
}

// intersect_packet's lane i alone, the same floats, for a GPU (whose
// work-item is one lane; traverse_bvh_groups): the distance at which
// triangle i of the packet is hit below t_max (at most T0_NO_HIT, so that
// a miss is never below it), with its barycentrics in *u, *v, or
// T0_NO_HIT.
T0_INLINE float packet_lane_hit(T0_GLOBAL const TrianglePacket* p, const Ray* ray, int i,
                                float t_max, float* u, float* v) {
    float3 w[3];  // the vertices in the ray's frame
    for (int k = 0; k < 3; ++k) {
        w[k] = packet_lane_vertex(p, ray, i, k);
    }
    const float weight0 = w[2].x * w[1].y - w[2].y * w[1].x;
    const float weight1 = w[0].x * w[2].y - w[0].y * w[2].x;
    const float weight2 = w[1].x * w[0].y - w[1].y * w[0].x;
    // lanes_min and lanes_max: a < b ? a : b, a > b ? a : b.
    const float min01 = weight0 < weight1 ? weight0 : weight1;
    const float smallest = min01 < weight2 ? min01 : weight2;
    const float max01 = weight0 > weight1 ? weight0 : weight1;
    const float largest = max01 > weight2 ? max01 : weight2;
    const float det = weight0 + weight1 + weight2;
    const float inv_det = 1.0f / det;
    const float distance =
        (weight0 * w[0].z + weight1 * w[1].z + weight2 * w[2].z) * ray->shear.z * inv_det;
    const int outside = smallest < 0.0f && 0.0f < largest;
    const int upright = buffer_component(&p->area, i) * ray->parallel_det < fabs(det);
    if (outside || !upright || !(0.0f < distance && distance < t_max)) {
        return T0_NO_HIT;
    }
    if (smallest * largest == 0.0f && outside_exactly(w[0], w[1], w[2])) {
        return T0_NO_HIT;
    }
    *u = weight1 * inv_det;
    *v = weight2 * inv_det;
    return distance;
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
        // Checked here, for every packet with a hit, rather than only for
        // the hit a traversal ends with (which may only have come nearer
        // by a false hit), traversing again where it is outside: no dearer
        // with GCC, cheaper with PoCL (kernel/tuning.h).
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

T0_NAMESPACE_END

#endif
