// How a scene is rendered, besides the scene itself: the acceleration
// structure, the integrator, the sampler and the light sampler
// (PackOptions), with their names as the programs' flags take them.
#ifndef TRAC0R_RENDER_OPTIONS_H
#define TRAC0R_RENDER_OPTIONS_H

#include <cstddef>
#include <string>

namespace trac0r {

enum class Accel {
    flat,       // the thesis' list of shapes with one AABB each
    bvh,        // a BVH over all triangles
    automatic,  // the flat list for tiny scenes, else the BVH
};

// Below how many triangles `automatic` keeps the flat list, where it is
// faster: measured by benchmarks/accel_crossover.cpp (docs/performance.md,
// "Flat list or BVH"). With 8-wide BVH nodes the BVH is as fast or faster
// from the smallest scene measured (12 triangles: 1.02 to 1.22 times the
// flat list's paths per second on the CPU backend, 1.04 to 1.05 on PoCL,
// three runs) on both backends; with 4-wide nodes PoCL's crossover was
// at 24.
// Backend::auto_bvh_min_triangles lets a backend have its own.
const std::size_t auto_bvh_min_triangles = 12;

enum class Integrator {
    naive,  // the thesis' algorithm: emission is found by scattering alone
    nee,    // next-event estimation (a light sample at each diffuse or rough
            // glossy hit) combined with scattering by MIS
    bdpt,   // bidirectional path tracing: a light subpath and a camera
            // subpath joined in every way, weighted by MIS (kernel/bdpt.h)
};

// Where a path's random numbers come from (kernel/sampler.h).
enum class SamplerKind {
    random,  // the thesis' xorshift1024*, independent samples
    sobol,   // Owen-scrambled Sobol points: stratified, less error per sample
};

// How next-event estimation, and bidirectional path tracing's light
// samples, pick a light (light_list.h).
enum class LightSampler {
    power,      // in proportion to power alone, from one CDF
    tree,       // the light tree: by power, distance and orientation
    automatic,  // the tree from light_tree_min_lights lights with a position
};

// From how many lights with a position (emitting triangles, point and
// spot lamps) `automatic` builds the light tree.
const std::size_t light_tree_min_lights = 32;

// How a scene is packed for the kernel. The defaults are trac0r's, the same
// for the library and every program (trac0r_viewer's flags start from
// them): next-event estimation with MIS and Owen-scrambled Sobol points. The
// thesis' algorithm is Integrator::naive with SamplerKind::random.
struct PackOptions {
    Accel accel = Accel::automatic;
    // For automatic: from how many triangles a BVH is built; 0 for
    // auto_bvh_min_triangles, or with a Renderer its backend's.
    std::size_t auto_bvh_min_triangles = 0;
    Integrator integrator = Integrator::nee;
    SamplerKind sampler = SamplerKind::sobol;
    LightSampler light_sampler = LightSampler::automatic;
};

// "flat", "bvh", "auto" and back; parse_accel throws std::invalid_argument.
Accel parse_accel(const std::string& name);
const char* to_string(Accel accel);

// "naive", "nee", "bdpt" and back; parse_integrator throws std::invalid_argument.
Integrator parse_integrator(const std::string& name);
const char* to_string(Integrator integrator);

// "power", "tree", "auto" and back; parse_light_sampler throws
// std::invalid_argument.
LightSampler parse_light_sampler(const std::string& name);
const char* to_string(LightSampler sampler);

// "random", "sobol" and back; parse_sampler throws std::invalid_argument.
SamplerKind parse_sampler(const std::string& name);
const char* to_string(SamplerKind sampler);

}  // namespace trac0r

#endif
