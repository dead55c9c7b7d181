// Next-event estimation's light sampling: a light picked by power or by
// the light tree (choose_light: an emitting triangle, a lamp, the sun or
// the environment), a point or
// direction on it, its radiance through the material with its MIS weight
// (sample_light), and the density of picking a given point on a triangle
// (light_pdf_solid_angle).
#ifndef TRAC0R_KERNEL_LIGHT_SAMPLING_H
#define TRAC0R_KERNEL_LIGHT_SAMPLING_H

#include "lamps.h"
#include "light_tree.h"
#include "material.h"
#include "texture.h"
#include "ray.h"
#include "ray_offset.h"
#include "sampling.h"
#include "spherical_triangle.h"
#include "traverse.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// The light list's inverse CDF: the first light whose cdf.x exceeds u.
T0_INLINE t0_u32 pick_light(const SceneView* scene, float u) {
    t0_u32 lo = 0u;
    t0_u32 hi = scene->light_count - 1u;
    while (lo < hi) {
        const t0_u32 mid = lo + (hi - lo) / 2u;
        if (u < scene->lights[mid].cdf.x) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// The share of picks that the distant lights (environment, suns: first in
// the list) take; the light tree picks among the rest.
T0_INLINE float distant_share(const SceneView* scene) {
    return scene->distant_count > 0u ? scene->lights[scene->distant_count - 1u].cdf.x : 0.0f;
}

// The probability that next-event estimation at p with normal n picks
// `light`, a light of the tree (not a distant one).
T0_INLINE float tree_light_pmf(const SceneView* scene, T0_GLOBAL const LightRecord* light, float3 p,
                               float3 n) {
    return (1.0f - distant_share(scene)) * light_tree_pmf(scene, p, n, light->ids.z);
}

// The light next-event estimation picks at `position` (normal `normal`,
// either side): with the light tree, a distant light by power (u_pick)
// or one of the tree's (u_tree, the way down it); else one by power.
typedef struct LightChoice {
    t0_u32 light;         // an index into the light list
    float pick;           // its probability; 0: nothing to pick
    float pick_per_area;  // for a triangle, over its area
} LightChoice;

T0_INLINE LightChoice choose_light(const SceneView* scene, float3 position, float3 normal,
                                   float u_pick, float u_tree) {
    LightChoice c;
    const float distant =
        T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE) ? distant_share(scene) : 1.0f;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE) && u_pick >= distant) {
        const LightPick tree = light_tree_pick(scene, position, normal, u_tree);
        T0_GLOBAL const LightRecord* light = &scene->lights[tree.light];
        c.light = tree.light;
        c.pick = (1.0f - distant) * tree.pmf;
        c.pick_per_area = light->ids.y == T0_LIGHT_TRIANGLE
                              ? c.pick / (0.5f * scene->triangles[light->ids.x].normal.w)
                              : 0.0f;
    } else {
        c.light = pick_light(scene, u_pick);
        c.pick = scene->lights[c.light].cdf.y;
        c.pick_per_area = scene->lights[c.light].cdf.z;
    }
    return c;
}

// The probability that choose_light at p, with normal n, picks `light`.
T0_INLINE float light_pick_pmf(const SceneView* scene, T0_GLOBAL const LightRecord* light, float3 p,
                               float3 n) {
    if (T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE) && !light_is_distant(light)) {
        return tree_light_pmf(scene, light, p, n);
    }
    return light->cdf.y;
}

// A density per area on a light turned into one per solid angle, seen from
// squared distance distance2 at cosine cos_light to the light's surface.
T0_INLINE float area_to_solid_angle(float pdf_area, float distance2, float cos_light) {
    return pdf_area * distance2 / cos_light;
}

// An emitting triangle seen from p, where sample_light samples it by solid
// angle (sample_by_solid_angle of its solid_angle): one function for both
// the sample and the density of a hit, so that they decide alike.
T0_INLINE SphericalTriangle emitter_seen_from(T0_GLOBAL const TriangleRecord* tri, float3 p) {
    return spherical_triangle_if_large(p, xyz(tri->v0), xyz(tri->v1), xyz(tri->v2),
                                       xyz(tri->normal), 0.5f * tri->normal.w);
}

// The density per solid angle, seen from distance away along unit
// direction, with which next-event estimation at `from` (with normal
// from_normal: the light tree's pick depends on them) picks a point on
// the emitting triangle tri; zero for a triangle that is not in the light
// list. The cosine at the light is taken on either side (a one-sided
// emitter's back, which this is asked about too, emits nothing anyway).
// A triangle that sample_light samples by solid angle from `from` has
// density pick / (its solid angle) in every direction that meets it.
T0_INLINE float light_pdf_solid_angle(const SceneView* scene, T0_GLOBAL const TriangleRecord* tri,
                                      float3 direction, float distance, float3 from,
                                      float3 from_normal) {
    if (tri->ids.z == T0_NO_LIGHT) {
        return 0.0f;
    }
    T0_GLOBAL const LightRecord* light = &scene->lights[tri->ids.z];
    float pick = light->cdf.y;
    float pdf_area = light->cdf.z;
    if (T0_HAS_FEATURE(scene, T0_FEATURE_LIGHT_TREE)) {
        pick = light_pick_pmf(scene, light, from, from_normal);
        pdf_area = pick / (0.5f * tri->normal.w);
    }
    const float omega = emitter_seen_from(tri, from).solid_angle;
    if (sample_by_solid_angle(omega)) {
        return pick / omega;
    }
    const float cos_light = fabs(dot(direction, xyz(tri->normal)));
    return area_to_solid_angle(pdf_area, distance * distance, cos_light);
}

// Whether a direction lies on one side of the shading normal and on the
// other of the triangle (with vertex normals): a light sample there would
// pass through the surface it is meant to reflect off, or refract back.
T0_INLINE int on_other_side(float3 direction, float3 facing_normal, float3 facing_geometric) {
    return (dot(direction, facing_geometric) > 0.0f) != (dot(direction, facing_normal) > 0.0f);
}

// The side of the triangle a light sample's ray in `direction` leaves
// from: the incoming side, but for rough glass, which samples lights
// through the surface too.
T0_INLINE float3 leaving_side(const SceneView* scene, float3 direction, float3 facing_geometric) {
    if (!T0_HAS_FEATURE(scene, T0_FEATURE_ROUGH_GLASS)) {
        return facing_geometric;
    }
    return dot(direction, facing_geometric) > 0.0f ? facing_geometric : -facing_geometric;
}

// A light sample as sample_light makes it: what it sends through the
// material, and the shadow ray that decides whether that arrives: from
// origin along direction, clear up to length. A length of 0: no ray, and
// nothing sent. On a CPU the ray is traced at once (an occluded sample
// sends nothing); on a GPU (T0_SHADOW_RAY_LAST) the caller traces it
// (shadow_ray_clear) once the vertex is shaded, so that less state is held
// across the traversal (docs/gpu.md).
typedef struct ShadowedLight {
    float3 sent;
    float3 origin;
    float3 direction;
    float length;
} ShadowedLight;

T0_INLINE ShadowedLight shadowed_light(float3 sent, float3 origin, float3 direction,
                                       float clear_to) {
    ShadowedLight s;
    s.sent = sent;
    s.origin = origin;
    s.direction = direction;
    s.length = clear_to;
    return s;
}

T0_INLINE ShadowedLight no_light_sample(void) {
    const float3 zero = float3_splat(0.0f);
    return shadowed_light(zero, zero, zero, 0.0f);
}

// Where the shadow ray is traced at once (a CPU): whether something lies on
// the ray from origin along direction before clear_to.
T0_INLINE int occluded_now(const SceneView* scene, float3 origin, float3 direction,
                           float clear_to) {
    if (T0_SHADOW_RAY_LAST) {
        return 0;
    }
    const Ray ray = make_ray(origin, direction);
    return occluded(scene, &ray, clear_to);
}

// Whether a light sample's shadow ray is clear (nothing on it), and so its
// light arrives.
T0_INLINE int shadow_ray_clear(const SceneView* scene, const ShadowedLight* s) {
    if (!(s->length > 0.0f)) {
        return 0;
    }
    const Ray ray = make_ray(s->origin, s->direction);
    return !occluded(scene, &ray, s->length);
}

// Next-event estimation of a light that is not a triangle (lamps.h): the
// sample's radiance through the material, if nothing is in between (its
// shadow ray: ShadowedLight); with
// its MIS weight where the light has an area (the sun's disc, the
// environment), in full for a delta light. pick is the light's
// probability.
T0_INLINE ShadowedLight sample_lamp(const SceneView* scene, T0_GLOBAL const LightRecord* light,
                                    float pick, T0_GLOBAL const MaterialRecord* m, float3 texture,
                                    float2 rm, int front, float3 incoming, float3 facing_normal,
                                    float3 facing_geometric, float3 position, float magnitude,
                                    float2 u) {
    const LightSample ls = light_is_distant(light) ? sample_distant_light(scene, light, u)
                                                   : sample_point_lamp(light, position);
    if (!(ls.radiance.x > 0.0f || ls.radiance.y > 0.0f || ls.radiance.z > 0.0f)) {
        return no_light_sample();
    }
    const MaterialEval e =
        eval_material(scene, m, texture, rm, front, incoming, facing_normal, ls.direction);
    if (!(e.pdf > 0.0f)) {
        return no_light_sample();
    }
    if ((T0_HAS_FEATURE(scene, T0_FEATURE_SMOOTH) || T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) &&
        on_other_side(ls.direction, facing_normal, facing_geometric)) {
        return no_light_sample();
    }
    const float3 origin =
        offset_ray_origin(position, leaving_side(scene, ls.direction, facing_geometric), magnitude);
    float3 shadow_direction = ls.direction;
    float shadow_length = T0_NO_HIT;
    if (ls.distance < T0_NO_HIT) {
        // To the lamp's point itself, from the moved origin.
        const float3 shadow = xyz(light->a) - origin;
        shadow_length = length(shadow);
        if (!(shadow_length > 0.0f)) {
            return no_light_sample();
        }
        shadow_direction = shadow / shadow_length;
    }
    if (occluded_now(scene, origin, shadow_direction, shadow_length)) {
        return no_light_sample();
    }
    if (!(ls.pdf > 0.0f)) {
        return shadowed_light(e.f_cos * ls.radiance / pick, origin, shadow_direction,
                              shadow_length);
    }
    const float light_pdf = pick * ls.pdf;
    return shadowed_light(e.f_cos * ls.radiance * (power_heuristic(light_pdf, e.pdf) / light_pdf),
                          origin, shadow_direction, shadow_length);
}

// Next-event estimation at a surface point: picks an emitting triangle in
// proportion to its power and a point on it (uniform, or by solid angle
// where it looks large: emitter_seen_from), and returns the
// radiance it sends back along -incoming through the material, if nothing
// is in between (its shadow ray: ShadowedLight), weighted by MIS against
// the material's own sampling (whose hits on emitters carry the
// complementary weight). facing_normal is the shading normal the material
// is evaluated with, facing_geometric the triangle's normal on the
// incoming side (the side the light must be on, and the shadow ray leaves
// from); both the same for a flat triangle.
// magnitude is hit_magnitude of position; u_pick chooses the light (with
// the light tree: a distant one or the tree, and u_tree the way down it)
// and u the point on it (or the direction to it).
T0_FORCE_INLINE ShadowedLight sample_light(const SceneView* scene,
                                           T0_GLOBAL const MaterialRecord* m, float3 texture,
                                           float2 rm, int front, float3 incoming,
                                           float3 facing_normal, float3 facing_geometric,
                                           float3 position, float magnitude, float u_pick,
                                           float u_tree, float2 u) {
    const LightChoice choice = choose_light(scene, position, facing_normal, u_pick, u_tree);
    if (!(choice.pick > 0.0f)) {
        return no_light_sample();
    }
    T0_GLOBAL const LightRecord* light = &scene->lights[choice.light];
    const float pick = choice.pick;  // the light's probability
    const float pick_per_area = choice.pick_per_area;
    if ((T0_HAS_FEATURE(scene, T0_FEATURE_LAMPS) ||
         T0_HAS_FEATURE(scene, T0_FEATURE_ENVIRONMENT)) &&
        light->ids.y != T0_LIGHT_TRIANGLE) {
        return sample_lamp(scene, light, pick, m, texture, rm, front, incoming, facing_normal,
                           facing_geometric, position, magnitude, u);
    }
    T0_GLOBAL const TriangleRecord* tri = &scene->triangles[light->ids.x];
    float b1 = 0.0f;
    float b2 = 0.0f;
    const float3 v0 = xyz(tri->v0);
    const float3 v1 = xyz(tri->v1);
    const float3 v2 = xyz(tri->v2);
    // A triangle that looks large is sampled by solid angle: the nearest
    // part of a lamp is then no likelier to be missed than the rest.
    const SphericalTriangle seen = emitter_seen_from(tri, position);
    const float omega = seen.solid_angle;
    const int by_solid_angle = sample_by_solid_angle(omega);
    if (by_solid_angle) {
        if (!sample_spherical_triangle(seen, position, v0, v1, v2, u, &b1, &b2)) {
            return no_light_sample();
        }
    } else {
        sample_triangle_barycentrics(u.x, u.y, &b1, &b2);
    }
    const float3 point = v0 + (v1 - v0) * b1 + (v2 - v0) * b2;
    const float3 to_light = point - position;
    const float distance2 = dot(to_light, to_light);
    if (!(distance2 > 0.0f)) {
        return no_light_sample();
    }
    const float distance = sqrt(distance2);
    const float3 direction = to_light / distance;
    const float3 light_normal = xyz(tri->normal);
    const float cos_light = fabs(dot(direction, light_normal));
    const MaterialEval e =
        eval_material(scene, m, texture, rm, front, incoming, facing_normal, direction);
    if (!(cos_light > 0.0f) || !(e.pdf > 0.0f)) {
        return no_light_sample();  // edge-on, or outside the material's lobe
    }
    if ((T0_HAS_FEATURE(scene, T0_FEATURE_SMOOTH) || T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) &&
        on_other_side(direction, facing_normal, facing_geometric)) {
        return no_light_sample();  // in the shading normal's lobe, across the triangle
    }
    T0_GLOBAL const MaterialRecord* emitter = &scene->materials[tri->ids.x];
    if (T0_HAS_FEATURE(scene, T0_FEATURE_ONE_SIDED) && material_one_sided(emitter) &&
        !(dot(direction, light_normal) < 0.0f)) {
        return no_light_sample();  // the back of a one-sided emitter
    }
    // The shadow ray runs between the two points, each moved off its surface
    // towards the other, so neither surface can block it.
    const float3 light_side = dot(direction, light_normal) < 0.0f ? light_normal : -light_normal;
    const float3 target = offset_ray_origin(point, light_side, hit_magnitude(tri, point));
    const float3 origin =
        offset_ray_origin(position, leaving_side(scene, direction, facing_geometric), magnitude);
    const float3 shadow = target - origin;
    const float shadow_length = length(shadow);
    if (!(shadow_length > 0.0f)) {
        return no_light_sample();
    }
    if (occluded_now(scene, origin, shadow / shadow_length, shadow_length)) {
        return no_light_sample();
    }
    const float light_pdf =
        by_solid_angle ? pick / omega : area_to_solid_angle(pick_per_area, distance2, cos_light);
    float3 emitted = material_emission(emitter);
    if (T0_HAS_FEATURE(scene, T0_FEATURE_TEXTURE)) {
        Hit at;
        at.t = distance;
        at.u = b1;
        at.v = b2;
        at.triangle = (int)light->ids.x;
        emitted *= emission_texture(scene, emitter, at);  // its emission texture there
    }
    return shadowed_light(e.f_cos * emitted * (power_heuristic(light_pdf, e.pdf) / light_pdf),
                          origin, shadow / shadow_length, shadow_length);
}

T0_NAMESPACE_END

#endif
