// A scene packed once per change into the flat arrays both backends read,
// with the feature mask of what it uses.
#ifndef TRAC0R_PACKED_SCENE_H
#define TRAC0R_PACKED_SCENE_H

#include "trac0r/kernel/types.h"
#include "trac0r/render_options.h"
#include "trac0r/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace trac0r {

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
    // A sphere around every packed triangle (xyz: centre, w: radius; a unit
    // sphere at the origin without triangles): where bidirectional path
    // tracing's light subpaths from distant lights start (SceneView.sphere).
    glm::vec4 sphere = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);

    kernel::SceneView view() const;
};

// Packs the scene: the acceleration structure (flat shapes with AABBs, or a
// BVH), triangles (vertices, normal), materials, the light list, and the
// feature mask (with T0_FEATURE_NEE for Integrator::nee when anything emits,
// T0_FEATURE_BDPT for Integrator::bdpt, whose lights are always picked by
// power,
// T0_FEATURE_SOBOL for SamplerKind::sobol, T0_FEATURE_SMOOTH when a
// triangle has vertex normals).
// Degenerate triangles (zero area, non-finite vertices) can never be hit
// and are left out.
PackedScene pack_scene(const Scene& scene, const PackOptions& options = PackOptions());

// The camera in a packed scene's coordinates: its position times the
// scene's scale (PackedScene::scale), and the lens' aperture radius and focus
// distance with it (extent.z, w); its directions and field of view stay.
kernel::CameraRecord scaled_camera(const kernel::CameraRecord& camera, float scale);

// "diffuse glass emittance flat" etc.: the names of the set bits.
std::string feature_names(std::uint32_t features);
// The names of the bits a full build has and this mask does not.
std::string left_out_feature_names(std::uint32_t features);

}  // namespace trac0r

#endif
