// The hit point on a triangle and the offset that keeps a new ray from
// hitting the surface it leaves, with the numbers of a triangle's record
// that both use (make_triangle_record).
#ifndef TRAC0R_KERNEL_RAY_OFFSET_H
#define TRAC0R_KERNEL_RAY_OFFSET_H

#include "ray.h"
#include "tuning.h"
#include "types.h"

T0_NAMESPACE_BEGIN

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
