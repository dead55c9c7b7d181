// Direction sampling. Each routine maps two uniform numbers in [0, 1) to a
// unit direction and reports its density (per solid angle); exact 0 and
// values just below 1 give finite results.
#ifndef TRAC0R_KERNEL_SAMPLING_H
#define TRAC0R_KERNEL_SAMPLING_H

#include "compat.h"

T0_NAMESPACE_BEGIN

typedef struct DirectionSample {
    float3 direction;
    float pdf;
} DirectionSample;

// An orthonormal basis around unit n (Duff et al., "Building an Orthonormal
// Basis, Revisited", 2017): no branch, no singularity at n = -z.
typedef struct Frame {
    float3 tangent;
    float3 bitangent;
    float3 normal;
} Frame;

T0_INLINE Frame frame_from_normal(float3 n) {
    const float sign = copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    Frame f;
    f.tangent = make_float3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.bitangent = make_float3(b, sign + n.y * n.y * a, -n.y);
    f.normal = n;
    return f;
}

T0_INLINE float3 frame_to_world(Frame f, float3 local_dir) {
    return f.tangent * local_dir.x + f.bitangent * local_dir.y + f.normal * local_dir.z;
}

T0_INLINE DirectionSample sample_uniform_sphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = sqrt(fmax(0.0f, 1.0f - z * z));
    const float phi = 2.0f * T0_PI * u2;
    DirectionSample s;
    s.direction = make_float3(r * cos(phi), r * sin(phi), z);
    s.pdf = 1.0f / (4.0f * T0_PI);
    return s;
}

// Cosine-weighted directions inside the cone of half-angle cone_angle
// (0..pi/2) around unit axis: pdf = cos(theta) / (pi sin^2(cone_angle)).
// cone_angle = pi/2 is the cosine-weighted hemisphere.
// sin^2 of a cone's half-angle, clamped to 0..pi/2: the one number the
// cosine-weighted cone's sampling and density depend on.
T0_INLINE float cone_sin2(float cone_angle) {
    const float sin_max = sin(fmin(fmax(cone_angle, 0.0f), 0.5f * T0_PI));
    return sin_max * sin_max;
}

T0_INLINE DirectionSample sample_cosine_cone(float3 axis, float cone_angle, float u1, float u2) {
    const float sin2_max = cone_sin2(cone_angle);
    const float sin2_theta = u1 * sin2_max;
    const float cos_theta = sqrt(fmax(0.0f, 1.0f - sin2_theta));
    const float sin_theta = sqrt(sin2_theta);
    const float phi = 2.0f * T0_PI * u2;
    const float3 local_dir = make_float3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
    DirectionSample s;
    s.direction = normalize(frame_to_world(frame_from_normal(axis), local_dir));
    // A cone of zero width is a delta: report the density as zero, callers
    // treat it as a specular (delta) direction.
    s.pdf = sin2_max > 0.0f ? cos_theta / (T0_PI * sin2_max) : 0.0f;
    return s;
}

// The density sample_cosine_cone gives unit direction d (zero outside the
// cone, and for a cone of zero width, whose directions are a delta).
T0_INLINE float cosine_cone_pdf(float3 axis, float sin2_max, float3 d) {
    const float cos_theta = dot(d, axis);
    const float cos_max = sqrt(fmax(0.0f, 1.0f - sin2_max));
    if (!(sin2_max > 0.0f) || !(cos_theta >= cos_max)) {
        return 0.0f;
    }
    return cos_theta / (T0_PI * sin2_max);
}

T0_INLINE DirectionSample sample_cosine_hemisphere(float3 normal, float u1, float u2) {
    return sample_cosine_cone(normal, 0.5f * T0_PI, u1, u2);
}

// A uniform point on a triangle, as the barycentric weights of its second
// and third vertices (the square-root map; pbrt-v4, section A.5.5).
T0_INLINE void sample_triangle_barycentrics(float u1, float u2, float* b1, float* b2) {
    const float root = sqrt(u1);
    *b1 = u2 * root;
    *b2 = 1.0f - root;
}

// The power heuristic (Veach 1997, beta = 2): the multiple importance
// sampling weight of a sample drawn with density pdf_a when another
// strategy would have drawn it with density pdf_b. Computed from their
// ratio, so a very narrow lobe's huge density cannot overflow when squared.
T0_INLINE float power_heuristic(float pdf_a, float pdf_b) {
    if (!(pdf_a > 0.0f)) {
        return 0.0f;
    }
    if (pdf_a >= pdf_b) {
        const float r = pdf_b / pdf_a;
        return 1.0f / (1.0f + r * r);
    }
    const float r = pdf_a / pdf_b;
    return r * r / (1.0f + r * r);
}

T0_NAMESPACE_END

#endif
