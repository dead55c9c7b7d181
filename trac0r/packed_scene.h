// A scene packed once per change into the flat arrays both backends read,
// with the feature mask of what it uses.
#ifndef TRAC0R_PACKED_SCENE_H
#define TRAC0R_PACKED_SCENE_H

#include "trac0r/kernel/types.h"
#include "trac0r/scene.h"

#include <cstdint>
#include <string>
#include <vector>

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
};

// Where a path's random numbers come from (kernel/sampler.h).
enum class SamplerKind {
    random,  // the thesis' xorshift1024*, independent samples
    sobol,   // Owen-scrambled Sobol points: stratified, less error per sample
};

// How next-event estimation picks a light (light_list.h).
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

struct PackedScene {
    std::vector<kernel::TriangleRecord> triangles;  // in BVH leaf order with a BVH
    std::vector<kernel::ShapeRecord> shapes;        // the flat structure (empty with a BVH)
    std::vector<kernel::BvhNode> nodes;             // empty with the flat structure
    std::vector<kernel::TrianglePacket> packets;    // the BVH's leaves (empty without)
    int bvh_depth = 0;
    bool bvh_by_levels = false;  // see Bvh::by_levels
    std::vector<kernel::MaterialRecord> materials;
    // Every light (environment, lamps, emitting triangles) with its power
    // CDF (light_list.h; built for both integrators: NEE samples them, and
    // a ray that leaves the scene looks up the distant ones).
    std::vector<kernel::LightRecord> lights;
    // By packed triangle, its vertex normals (T0_FEATURE_SMOOTH); empty when
    // no triangle has them.
    std::vector<kernel::VertexNormals> normals;
    // With T0_FEATURE_TEXTURE (else empty): by packed triangle, its texture
    // coordinates; the scene's textures, and their texels one after another.
    std::vector<kernel::TriangleUVs> uvs;
    std::vector<kernel::TextureRecord> textures;
    std::vector<std::uint32_t> texels;
    // By packed triangle, its tangents, where a material of the scene has
    // a normal map (the file's, else uv_tangents'); else empty.
    std::vector<kernel::VertexTangents> tangents;
    // With T0_FEATURE_ENVIRONMENT (else empty): the environment's texels
    // and CDFs (SceneView.environment); the lights list's distant lights
    // (environment and suns), first in it.
    std::vector<glm::vec4> environment;
    std::uint32_t distant_count = 0;
    // With T0_FEATURE_LIGHT_TREE (else empty): the light tree, root first.
    std::vector<kernel::LightTreeNode> light_nodes;
    std::uint32_t features = 0;
    std::size_t dropped_degenerate_triangles = 0;  // zero-area or non-finite
    // The power of two every coordinate was multiplied by: 1 for a scene of
    // ordinary size, else the one that brings the median triangle's largest
    // coordinate to between 1 and 2, or less where the largest must stay
    // within 2^38 (pack_scene, coordinate_scale). The backends multiply
    // the camera's position by it (scaled_camera); code that runs the kernel
    // on a packed scene itself must do the same.
    float scale = 1.0f;

    kernel::SceneView view() const;
};

// Packs the scene: the acceleration structure (flat shapes with AABBs, or a
// BVH), triangles (vertices, normal), materials, the light list, and the
// feature mask (with T0_FEATURE_NEE for Integrator::nee when anything emits,
// T0_FEATURE_SOBOL for SamplerKind::sobol, T0_FEATURE_SMOOTH when a
// triangle has vertex normals).
// Degenerate triangles (zero area, non-finite vertices) can never be hit
// and are left out.
PackedScene pack_scene(const Scene& scene, const PackOptions& options = PackOptions());

// The camera in a packed scene's coordinates: its position times the
// scene's scale (PackedScene::scale), and the lens' aperture radius and focus
// distance with it (extent.z, w); its directions and field of view stay.
kernel::CameraRecord scaled_camera(const kernel::CameraRecord& camera, float scale);

// "flat", "bvh", "auto" and back; parse_accel throws std::invalid_argument.
Accel parse_accel(const std::string& name);
const char* to_string(Accel accel);

// "naive", "nee" and back; parse_integrator throws std::invalid_argument.
Integrator parse_integrator(const std::string& name);
const char* to_string(Integrator integrator);

// "power", "tree", "auto" and back; parse_light_sampler throws
// std::invalid_argument.
LightSampler parse_light_sampler(const std::string& name);
const char* to_string(LightSampler sampler);

// "random", "sobol" and back; parse_sampler throws std::invalid_argument.
SamplerKind parse_sampler(const std::string& name);
const char* to_string(SamplerKind sampler);

// "diffuse glass emittance flat" etc.: the names of the set bits.
std::string feature_names(std::uint32_t features);
// The names of the bits a full build has and this mask does not.
std::string left_out_feature_names(std::uint32_t features);

}  // namespace trac0r

#endif
