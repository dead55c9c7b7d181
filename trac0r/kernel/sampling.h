// Direction sampling. Each routine maps two uniform numbers in [0, 1) to a
// unit direction and reports its density (per solid angle); exact 0 and
// values just below 1 give finite results.
#ifndef TRAC0R_KERNEL_SAMPLING_H
#define TRAC0R_KERNEL_SAMPLING_H

#include "compat.h"

T0_NAMESPACE_BEGIN

typedef struct float2_cs {
    float c;  // cosine
    float s;  // sine
} float2_cs;

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

// The cosine and sine of the angle 2 pi u, u in [0, 1): u is taken to the
// nearest quarter turn k (4u is exact, and for rng_float's multiples of
// 2^-24 so is 4u - k, by Sterbenz; for a u within 2^-27 below 1/8,
// 4u + 0.5 rounds up to k = 1 and 4u - k rounds once, a 5e-8 error), the
// rest, an angle of at most pi/4, goes through Cephes' sinf/cosf
// polynomials (error about 1 ulp there), and the result is rotated by k
// quarter turns. The same operations on both backends, so the
// same floats; and no library sin/cos, which PoCL runs through a slow
// argument reduction for every angle (kernel/tuning.h).
T0_INLINE float2_cs turn_cos_sin(float u) {
    const float quarters = 4.0f * u;
    const float k = floor(quarters + 0.5f);
    const float x = (quarters - k) * (0.5f * T0_PI);
    const float x2 = x * x;
    const float s =
        x + x * x2 * (-1.6666654611e-1f + x2 * (8.3321608736e-3f + x2 * -1.9515295891e-4f));
    const float c =
        1.0f - 0.5f * x2 +
        x2 * x2 *
            (4.166664568298827e-2f + x2 * (-1.388731625493765e-3f + x2 * 2.443315711809948e-5f));
    // Quarter turn q: (c, s), (-s, c), (-c, -s), (s, -c), made with bit
    // operations (a swap, then sign flips), not branches: q is random, and
    // PoCL kept the three-way choice as branches that mispredicted.
    const int q = (int)k & 3;
    const int swap = -(q & 1);
    const int sign = float_bits(-0.0f);
    const int cb = float_bits(c);
    const int sb = float_bits(s);
    float2_cs r;
    r.c = bits_float(((sb & swap) | (cb & ~swap)) ^ (sign & -(((q + 1) >> 1) & 1)));
    r.s = bits_float(((cb & swap) | (sb & ~swap)) ^ (sign & -(q >> 1)));
    return r;
}

T0_INLINE DirectionSample sample_uniform_sphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = sqrt(fmax(0.0f, 1.0f - z * z));
    const float2_cs phi = turn_cos_sin(u2);
    DirectionSample s;
    s.direction = make_float3(r * phi.c, r * phi.s, z);
    s.pdf = 1.0f / (4.0f * T0_PI);
    return s;
}

// sin^2 of a cone's half-angle, clamped to 0..pi/2: the one number the
// cosine-weighted cone's sampling and density depend on.
T0_INLINE float cone_sin2(float cone_angle) {
    const float sin_max = sin(fmin(fmax(cone_angle, 0.0f), 0.5f * T0_PI));
    return sin_max * sin_max;
}

// Cosine-weighted directions inside the cone around unit axis whose
// half-angle has sine squared sin2_max (cone_sin2): pdf = cos(theta) /
// (pi sin2_max). sin2_max = 1 is the cosine-weighted hemisphere. The
// direction is the local one (unit length) in the axis' orthonormal
// frame, not renormalised: unit to within a few ulps (test_sampling
// measures at most 4, 2.4e-7).
T0_INLINE DirectionSample cosine_cone_direction(float3 axis, float sin2_max, float u1, float u2) {
    const float sin2_theta = u1 * sin2_max;
    const float cos_theta = sqrt(fmax(0.0f, 1.0f - sin2_theta));
    const float sin_theta = sqrt(sin2_theta);
    const float2_cs phi = turn_cos_sin(u2);
    const float3 local_dir = make_float3(sin_theta * phi.c, sin_theta * phi.s, cos_theta);
    DirectionSample s;
    s.direction = frame_to_world(frame_from_normal(axis), local_dir);
    // A cone of zero width is a delta: report the density as zero, callers
    // treat it as a specular (delta) direction.
    s.pdf = sin2_max > 0.0f ? cos_theta / (T0_PI * sin2_max) : 0.0f;
    return s;
}

// cosine_cone_direction renormalised. A glossy lobe may be a cone of a
// hundredth of a degree, whose rim eval_glossy must place its samples
// inside (cosine_cone_pdf): there a few ulps of length decide.
T0_INLINE DirectionSample sample_cosine_cone_sin2(float3 axis, float sin2_max, float u1, float u2) {
    DirectionSample s = cosine_cone_direction(axis, sin2_max, u1, u2);
    s.direction = normalize(s.direction);
    return s;
}

// The density sample_cosine_cone_sin2 gives unit direction d (zero outside
// the cone, and for a cone of zero width, whose directions are a delta).
T0_INLINE float cosine_cone_pdf(float3 axis, float sin2_max, float3 d) {
    const float cos_theta = dot(d, axis);
    const float cos_max = sqrt(fmax(0.0f, 1.0f - sin2_max));
    if (!(sin2_max > 0.0f) || !(cos_theta >= cos_max)) {
        return 0.0f;
    }
    return cos_theta / (T0_PI * sin2_max);
}

// The cone of half-angle pi/2 (cone_sin2(pi/2) is exactly 1), not
// renormalised: a hemisphere direction's cosine to the normal is at least
// sqrt(2^-24), a thousand times its length's error, so which side of the
// surface it leaves is never in doubt, and the normalisation's square root
// and division would sit in every diffuse bounce between one hit and the
// next ray (kernel/tuning.h).
T0_INLINE DirectionSample sample_cosine_hemisphere(float3 normal, float u1, float u2) {
    return cosine_cone_direction(normal, 1.0f, u1, u2);
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
