// Sampling a triangle by the solid angle it covers as seen from a point
// (Arvo, "Stratified Sampling of Spherical Triangles", SIGGRAPH 1995, in
// the form of pbrt-v4's SampleSphericalTriangle): every direction towards
// the triangle equally likely, density 1 / (its solid angle). Next-event
// estimation uses it for emitting triangles that look large from the
// shading point, where picking a uniform point on the triangle makes the
// 1 / distance^2 of the nearest part of a lamp a firefly.
#ifndef TRAC0R_KERNEL_SPHERICAL_TRIANGLE_H
#define TRAC0R_KERNEL_SPHERICAL_TRIANGLE_H

#include "compat.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// Where sampling by solid angle is used. Above 6.22 sr the triangle covers
// nearly a hemisphere and the formulas break down (pbrt-v4's bound). Below
// 0.2 sr a uniform point on it does nearly as well for less: each sample
// by solid angle costs about as much as the rest of a path's vertex. On
// cornell_diffuse.json (200 x 150, 32 spp, 4 seeds, against 2048 spp)
// the thresholds 0.15, 0.2, 0.3 and 0.6 sr gave 1.78, 1.80, 1.75 and 1.54
// times the efficiency of area sampling alone (its MSE over theirs, over
// their frame time's ratio from benchmarks/ab_kernels.sh), pbrt-v4's
// 3e-4 sr 1.40.
#define T0_SPHERICAL_MIN_SOLID_ANGLE 0.2f
#define T0_SPHERICAL_MAX_SOLID_ANGLE 6.22f

// The triangle (v0, v1, v2) as seen from a point: the unit directions to
// its corners and the solid angle it covers (Van Oosterom and Strackee
// 1983; zero for a degenerate one or a point in its plane outside it, 2 pi
// for a point in the plane inside it, where it is no light to sample: the
// bound T0_SPHERICAL_MAX_SOLID_ANGLE leaves that to area sampling).
typedef struct SphericalTriangle {
    float3 a;
    float3 b;
    float3 c;
    float solid_angle;
} SphericalTriangle;

T0_OUT_OF_LINE SphericalTriangle spherical_triangle(float3 p, float3 v0, float3 v1, float3 v2) {
    SphericalTriangle t;
    t.a = normalize(v0 - p);
    t.b = normalize(v1 - p);
    t.c = normalize(v2 - p);
    const float omega =
        fabs(2.0f * atan2_float(dot(t.a, cross(t.b, t.c)),
                                1.0f + dot(t.a, t.b) + dot(t.a, t.c) + dot(t.b, t.c)));
    t.solid_angle = omega == omega ? omega : 0.0f;  // a point on a corner: 0 / 0
    return t;
}

// Whether a triangle seen with solid angle omega is sampled by solid angle
// (else by area): sampling and the density of a hit agree on it.
T0_INLINE int sample_by_solid_angle(float omega) {
    return omega > T0_SPHERICAL_MIN_SOLID_ANGLE && omega < T0_SPHERICAL_MAX_SOLID_ANGLE;
}

// The triangle (v0, v1, v2) with unit normal n and the given area seen
// from p, where it looks large; elsewhere only a solid angle of zero,
// without the cost of spherical_triangle. "Large" is decided cheaply, and
// the same way wherever p is the same (so sampling and the density of a
// hit agree): within 1.5 times the radius of its bounding sphere from its
// centre (where a grazing view may still see much of it), or by the solid
// angle of a small triangle there (area |cos| / distance^2) over
// T0_SPHERICAL_MIN_SOLID_ANGLE.
T0_INLINE SphericalTriangle spherical_triangle_if_large(float3 p, float3 v0, float3 v1, float3 v2,
                                                        float3 n, float area) {
    const float3 centre = (v0 + v1 + v2) * (1.0f / 3.0f);
    const float3 d0 = v0 - centre;
    const float3 d1 = v1 - centre;
    const float3 d2 = v2 - centre;
    const float radius2 = fmax(dot(d0, d0), fmax(dot(d1, d1), dot(d2, d2)));
    const float3 to_centre = centre - p;
    const float distance2 = dot(to_centre, to_centre);
    if (distance2 > 2.25f * radius2 &&
        area * fabs(dot(n, to_centre)) <=
            T0_SPHERICAL_MIN_SOLID_ANGLE * distance2 * sqrt(distance2)) {
        SphericalTriangle small;
        small.a = small.b = small.c = float3_splat(0.0f);
        small.solid_angle = 0.0f;
        return small;
    }
    return spherical_triangle(p, v0, v1, v2);
}

// v's part orthogonal to unit w, normalized.
T0_INLINE float3 orthonormal_part(float3 v, float3 w) { return normalize(v - w * dot(v, w)); }

// A direction into the spherical triangle t (seen from p; its corners
// v0, v1, v2), uniform in solid angle for u uniform in [0, 1)^2, as the
// barycentrics (b1, b2) of the point it meets (of v1 and v2: the point is
// v0 + b1 (v1 - v0) + b2 (v2 - v0)). Returns 0 where the triangle is
// degenerate as seen from p (no sample).
T0_OUT_OF_LINE int sample_spherical_triangle(SphericalTriangle t, float3 p, float3 v0, float3 v1,
                                             float3 v2, float2 u, float* b1, float* b2) {
    const float3 a = t.a;
    const float3 b = t.b;
    const float3 c = t.c;
    float3 n_ab = cross(a, b);
    float3 n_ca = cross(c, a);
    if (!(dot(n_ab, n_ab) > 0.0f) || !(dot(n_ca, n_ca) > 0.0f)) {
        return 0;
    }
    n_ab = normalize(n_ab);
    n_ca = normalize(n_ca);
    // The angle alpha at a, between the great circles through a and b and
    // through a and c, by its cosine and sine (accurate near 0 and pi).
    const float cos_alpha = -dot(n_ab, n_ca);
    const float sin_alpha = length(cross(n_ab, n_ca));
    // The sub-triangle (a, b, c'), c' on the arc from a to c, whose area is
    // u.x times the triangle's, A' = u.x omega: Arvo's phi = A' + pi -
    // alpha, by the sine and cosine of a difference.
    const float sin_area = sin(u.x * t.solid_angle);
    const float cos_area = cos(u.x * t.solid_angle);
    const float sin_phi = -(sin_area * cos_alpha - cos_area * sin_alpha);
    const float cos_phi = -(cos_area * cos_alpha + sin_area * sin_alpha);
    const float k1 = cos_phi + cos_alpha;
    const float k2 = sin_phi - sin_alpha * dot(a, b);
    float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) /
                   ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
    cos_bp = cos_bp == cos_bp ? fmax(-1.0f, fmin(1.0f, cos_bp)) : 1.0f;
    const float sin_bp = sqrt(fmax(0.0f, 1.0f - cos_bp * cos_bp));
    const float3 cp = a * cos_bp + orthonormal_part(c, a) * sin_bp;
    // Then a direction on the arc from b to c', uniform in the sub-triangle.
    const float cos_theta = 1.0f - u.y * (1.0f - dot(cp, b));
    const float sin_theta = sqrt(fmax(0.0f, 1.0f - cos_theta * cos_theta));
    const float3 w = b * cos_theta + orthonormal_part(cp, b) * sin_theta;
    // Where the ray from p along w meets the triangle's plane.
    const float3 e1 = v1 - v0;
    const float3 e2 = v2 - v0;
    const float3 s1 = cross(w, e2);
    const float divisor = dot(s1, e1);
    if (!(fabs(divisor) > 0.0f)) {
        return 0;
    }
    const float3 s = p - v0;
    float x = dot(s, s1) / divisor;
    float y = dot(w, cross(s, e1)) / divisor;
    if (!(x == x) || !(y == y)) {
        return 0;  // before the clamps, which would turn a NaN into an edge
    }
    x = fmax(0.0f, fmin(1.0f, x));
    y = fmax(0.0f, fmin(1.0f, y));
    const float sum = x + y;
    if (sum > 1.0f) {
        x /= sum;
        y /= sum;
    }
    *b1 = x;
    *b2 = y;
    return 1;
}

T0_NAMESPACE_END

#endif
