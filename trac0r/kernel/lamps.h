// The lights that are not surfaces: point and spot lamps, and the sun
// (a distant disc of light, or a single direction): where next-event
// estimation's sample goes and what it brings.
#ifndef TRAC0R_KERNEL_LAMPS_H
#define TRAC0R_KERNEL_LAMPS_H

#include "environment.h"
#include "ray.h"
#include "sampling.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// A light sample seen from a point: the unit direction towards it, how far
// a shadow ray must go (T0_NO_HIT for a distant light), and what arrives:
// for a light with an area (pdf > 0) its radiance, with pdf the direction's
// density per solid angle; for a delta light (pdf 0) the irradiance it
// brings to a surface facing it (intensity / r^2, or the delta sun's
// irradiance), which no scattered ray can find.
typedef struct LightSample {
    float3 direction;
    float distance;
    float3 radiance;
    float pdf;
} LightSample;

// A spot's share of its axis intensity at cosine cos_angle from the axis:
// 1 inside the inner cone (cos_inner), 0 outside the outer one
// (cos_outer), and between them smoothstep of the cosine (pbrt-v4's
// SpotLight); a hard edge where the two cones are the same.
T0_INLINE float spot_falloff(float cos_angle, float cos_outer, float cos_inner) {
    if (!(cos_inner > cos_outer)) {
        return cos_angle >= cos_outer ? 1.0f : 0.0f;
    }
    const float t = fmin(fmax((cos_angle - cos_outer) / (cos_inner - cos_outer), 0.0f), 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// A point or spot lamp seen from `position`.
T0_INLINE LightSample sample_point_lamp(T0_GLOBAL const LightRecord* light, float3 position) {
    LightSample s;
    s.pdf = 0.0f;
    s.radiance = float3_splat(0.0f);
    s.direction = make_float3(0.0f, 1.0f, 0.0f);
    const float3 to_light = xyz(light->a) - position;
    const float distance2 = dot(to_light, to_light);
    s.distance = sqrt(distance2);
    if (!(distance2 > 0.0f)) {
        return s;
    }
    s.direction = to_light / s.distance;
    s.radiance = xyz(light->b) / distance2;
    if (light->ids.y == T0_LIGHT_SPOT) {
        s.radiance *= spot_falloff(-dot(s.direction, xyz(light->c)), light->a.w, light->c.w);
    }
    return s;
}

// Whether unit direction d lies in the sun's disc: the sine squared of its
// angle to the sun's direction (from the cross product, exact for tiny
// angles where the cosine is 1 in float) within the disc's.
T0_INLINE int in_sun_disc(T0_GLOBAL const LightRecord* light, float3 d) {
    const float3 axis = xyz(light->a);
    const float3 c = cross(d, axis);
    return dot(d, axis) > 0.0f && dot(c, c) <= light->c.x;
}

// The sun: a delta direction, or a uniform direction in its disc (a cone of
// solid angle c.y; 1 - cos of the angle at u.x's share of 1 - cos of the
// disc's radius, the sine from that difference, exact for tiny discs).
T0_INLINE LightSample sample_sun(T0_GLOBAL const LightRecord* light, float2 u) {
    LightSample s;
    s.distance = T0_NO_HIT;
    s.radiance = xyz(light->b);
    if (!(light->c.x > 0.0f)) {
        s.direction = xyz(light->a);
        s.pdf = 0.0f;
        return s;
    }
    const float one_minus_cos = u.x * light->c.z;
    const float sin_theta = sqrt(fmax(0.0f, one_minus_cos * (2.0f - one_minus_cos)));
    const float2_cs phi = turn_cos_sin(u.y);
    const float3 local_dir =
        make_float3(sin_theta * phi.c, sin_theta * phi.s, 1.0f - one_minus_cos);
    s.direction = normalize(frame_to_world(frame_from_normal(xyz(light->a)), local_dir));
    s.pdf = 1.0f / light->c.y;
    return s;
}

// The environment's sample as a light sample.
T0_INLINE LightSample sample_environment_light(const SceneView* scene,
                                               T0_GLOBAL const LightRecord* light, float2 u) {
    const EnvironmentSample e = environment_sample(scene, light, u);
    LightSample s;
    s.direction = e.direction;
    s.distance = T0_NO_HIT;
    s.radiance = e.pdf > 0.0f ? e.radiance : float3_splat(0.0f);
    s.pdf = e.pdf;
    return s;
}

// Whether the light is at infinity (the environment, a sun).
T0_INLINE int light_is_distant(T0_GLOBAL const LightRecord* light) {
    return light->ids.y == T0_LIGHT_SUN || light->ids.y == T0_LIGHT_ENVIRONMENT;
}

// A distant light's sample (the environment or a sun): the direction
// towards it, its radiance, and the density per solid angle (zero for a
// delta sun). Next-event estimation, BDPT's light samples and its light
// subpaths all take their distant lights' directions from here.
T0_INLINE LightSample sample_distant_light(const SceneView* scene,
                                           T0_GLOBAL const LightRecord* light, float2 u) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_ENVIRONMENT) && light->ids.y == T0_LIGHT_ENVIRONMENT) {
        return sample_environment_light(scene, light, u);
    }
    return sample_sun(light, u);
}

// The radiance that a ray leaving the scene along unit `direction` finds
// in the distant lights (the environment, and suns with a disc), each
// weighted by MIS against next-event estimation when `weighted` (the
// vertex it left sampled a light, and picked it with density
// scatter_pdf).
T0_INLINE float3 escaped_radiance(const SceneView* scene, float3 direction, int weighted,
                                  float scatter_pdf) {
    float3 sum = float3_splat(0.0f);
    for (t0_u32 i = 0u; i < scene->distant_count; ++i) {
        T0_GLOBAL const LightRecord* light = &scene->lights[i];
        float3 radiance;
        float light_pdf;
        if (T0_HAS_FEATURE(scene, T0_FEATURE_ENVIRONMENT) && light->ids.y == T0_LIGHT_ENVIRONMENT) {
            radiance = environment_radiance(scene, light, direction);
            light_pdf = weighted ? light->cdf.y * environment_pdf(scene, light, direction) : 0.0f;
        } else if (T0_HAS_FEATURE(scene, T0_FEATURE_LAMPS) && light->c.x > 0.0f &&
                   in_sun_disc(light, direction)) {
            radiance = xyz(light->b);
            light_pdf = light->cdf.y / light->c.y;
        } else {
            continue;
        }
        sum += weighted ? radiance * power_heuristic(scatter_pdf, light_pdf) : radiance;
    }
    return sum;
}

T0_NAMESPACE_END

#endif
