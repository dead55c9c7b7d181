#include "trac0r/packed_scene.h"

#include "trac0r/bvh.h"
#include "trac0r/enum_names.h"
#include "trac0r/kernel/material.h"
#include "trac0r/kernel/ray_offset.h"
#include "trac0r/light_list.h"
#include "trac0r/tangents.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace trac0r {

namespace {

kernel::TriangleRecord pack_triangle(const Triangle& t, unsigned material, unsigned shape) {
    // The vertices themselves, not v0 and edges: v0 + (v1 - v0) need not
    // round back to v1, and the watertight test needs every triangle that
    // shares a vertex to see the same floats.
    return kernel::make_triangle_record(t.v0, t.v1, t.v2, t.normal, 2.0f * t.area, material, shape);
}

// The kernel's type: glass of roughness > 0 is rough glass.
unsigned kernel_material_type(const Material& m) {
    if (m.type == MaterialType::glass && m.roughness > 0.0f) {
        return T0_MATERIAL_ROUGH_GLASS;
    }
    return static_cast<unsigned>(m.type);
}

kernel::MaterialRecord pack_material(const Material& m) {
    kernel::MaterialRecord r = kernel::make_material_record(kernel_material_type(m), m.color,
                                                            m.emittance, m.roughness, m.ior);
    r.type.z = m.two_sided ? 0u : 1u;
    r.k.w = m.normal_scale;
    r.alpha = glm::vec4(m.alpha, m.alpha_cutoff, static_cast<float>(m.alpha_mode),
                        static_cast<float>(m.alpha_channel));
    if (m.type == MaterialType::conductor && !m.metal.empty()) {
        const Metal* metal = find_metal(m.metal);
        if (metal != nullptr) {
            r.type.w = 1u;
            r.eta = glm::vec4(metal->eta, 0.0f);
            r.k = glm::vec4(metal->k, 1.0f);
        }
    }
    if (m.type == MaterialType::plastic) {
        r.eta.w = plastic_diffuse_scale(m.ior);
    }
    if (m.type == MaterialType::principled) {
        r.color.w = m.metallic;
        r.eta.x = m.specular;
        r.emission = glm::vec4(m.emission, 0.0f);
    }
    return r;
}

std::uint32_t material_feature(const Material& m) {
    switch (kernel_material_type(m)) {
    case T0_MATERIAL_EMISSIVE:
        return T0_FEATURE_EMISSIVE;
    case T0_MATERIAL_DIFFUSE:
        return T0_FEATURE_DIFFUSE;
    case T0_MATERIAL_GLASS:
        return T0_FEATURE_GLASS;
    case T0_MATERIAL_GLOSSY:
        return T0_FEATURE_GLOSSY;
    case T0_MATERIAL_CONDUCTOR:
        return T0_FEATURE_CONDUCTOR;
    case T0_MATERIAL_PLASTIC:
        return T0_FEATURE_PLASTIC;
    case T0_MATERIAL_PRINCIPLED:
        return T0_FEATURE_PRINCIPLED;
    case T0_MATERIAL_ROUGH_GLASS:
        return T0_FEATURE_ROUGH_GLASS;
    }
    return 0;
}

const char* const feature_bit_names[T0_FEATURE_COUNT] = {
    "emissive",   "diffuse",   "glass",   "glossy",     "emittance",   "flat",  "bvh",
    "nee",        "sobol",     "smooth",  "texture",    "environment", "lamps", "one_sided",
    "light_tree", "conductor", "plastic", "principled", "rough_glass", "alpha", "bdpt"};

// What this build's kernel can do at all.
const std::uint32_t implemented_features =
    T0_FEATURE_EMISSIVE | T0_FEATURE_DIFFUSE | T0_FEATURE_GLASS | T0_FEATURE_GLOSSY |
    T0_FEATURE_EMITTANCE | T0_FEATURE_FLAT | T0_FEATURE_BVH | T0_FEATURE_NEE | T0_FEATURE_SOBOL |
    T0_FEATURE_SMOOTH | T0_FEATURE_TEXTURE | T0_FEATURE_ENVIRONMENT | T0_FEATURE_LAMPS |
    T0_FEATURE_ONE_SIDED | T0_FEATURE_LIGHT_TREE | T0_FEATURE_CONDUCTOR | T0_FEATURE_PLASTIC |
    T0_FEATURE_PRINCIPLED | T0_FEATURE_ROUGH_GLASS | T0_FEATURE_ALPHA | T0_FEATURE_BDPT;

}  // namespace

kernel::SceneView PackedScene::view() const {
    kernel::SceneView v;
    v.triangles = triangles.data();
    v.shapes = shapes.data();
    v.materials = materials.data();
    v.nodes = nodes.data();
    v.packets = packets.data();
    v.lights = lights.data();
    v.shape_count = static_cast<std::uint32_t>(shapes.size());
    v.light_count = static_cast<std::uint32_t>(lights.size());
    v.features = features;
    v.normals = normals.data();
    v.uvs = uvs.data();
    v.tangents = tangents.data();
    v.textures = textures.data();
    v.texels = texels.data();
    v.environment = environment.data();
    v.distant_count = distant_count;
    v.light_nodes = light_nodes.data();
    v.sphere = sphere;
    return v;
}

namespace {

struct UsableTriangle {
    const Triangle* triangle;
    unsigned material;
    unsigned shape;
    const VertexNormalTriple* normals;  // nullptr: flat
    const TriangleUv* uv;               // nullptr: none
    std::uint32_t index;                // in its shape
};

// The thesis' structure: each shape's usable triangles in a run, one AABB.
void pack_flat(const std::vector<UsableTriangle>& usable, PackedScene& packed) {
    for (std::size_t i = 0; i < usable.size();) {
        kernel::ShapeRecord record;
        record.range = glm::uvec4(static_cast<unsigned>(packed.triangles.size()), 0u,
                                  usable[i].material, usable[i].shape);
        AABB bounds;
        const unsigned shape = usable[i].shape;
        for (; i < usable.size() && usable[i].shape == shape; ++i) {
            packed.triangles.push_back(
                pack_triangle(*usable[i].triangle, usable[i].material, shape));
            bounds.extend(usable[i].triangle->bounds());
        }
        record.range.y = static_cast<unsigned>(packed.triangles.size()) - record.range.x;
        record.aabb_min = glm::vec4(bounds.min, 0.0f);
        record.aabb_max = glm::vec4(bounds.max, 0.0f);
        packed.shapes.push_back(record);
    }
}

// Returns, for each packed triangle, its index in `usable`.
std::vector<std::uint32_t> pack_bvh(const std::vector<UsableTriangle>& usable,
                                    PackedScene& packed) {
    std::vector<AABB> bounds;
    bounds.reserve(usable.size());
    for (const UsableTriangle& u : usable) {
        bounds.push_back(u.triangle->bounds());
    }
    Bvh bvh = build_bvh(bounds);
    packed.nodes = std::move(bvh.nodes);
    packed.bvh_depth = bvh.depth;
    packed.bvh_by_levels = bvh.by_levels;
    packed.triangles.reserve(usable.size());
    for (std::uint32_t index : bvh.order) {
        const UsableTriangle& u = usable[index];
        packed.triangles.push_back(pack_triangle(*u.triangle, u.material, u.shape));
    }
    // Each leaf's triangles side by side; unused lanes have zero vertices
    // and an infinite area, which no ray is ever upright enough to hit.
    packed.packets.assign(bvh.leaves.size(), kernel::TrianglePacket{});
    for (std::size_t i = 0; i < bvh.leaves.size(); ++i) {
        kernel::TrianglePacket& p = packed.packets[i];
        p.area = glm::vec4(std::numeric_limits<float>::infinity());
        for (std::uint32_t lane = 0; lane < bvh.leaves[i].count; ++lane) {
            const std::uint32_t index = bvh.leaves[i].first + lane;
            const kernel::TriangleRecord& t = packed.triangles[index];
            const glm::vec4* vertices[3] = {&t.v0, &t.v1, &t.v2};
            for (int k = 0; k < 3; ++k) {
                for (int axis = 0; axis < 3; ++axis) {
                    p.vertex[3 * k + axis][lane] = (*vertices[k])[axis];
                }
            }
            p.area[lane] = t.normal.w;
            p.triangle[lane] = index;
        }
    }
    return bvh.order;
}

// The vertex normals of the packed triangles (packed_index maps a usable
// triangle to its packed one), where any triangle has them.
void pack_normals(const std::vector<UsableTriangle>& usable,
                  const std::vector<std::uint32_t>& packed_index, PackedScene& packed) {
    for (std::size_t u = 0; u < usable.size(); ++u) {
        const VertexNormalTriple* n = usable[u].normals;
        if (n == nullptr) {
            continue;
        }
        if (packed.normals.empty()) {
            packed.normals.assign(usable.size(), kernel::VertexNormals{});
            packed.features |= T0_FEATURE_SMOOTH;
        }
        kernel::VertexNormals& record = packed.normals[packed_index[u]];
        record.n0 = glm::vec4((*n)[0], 1.0f);
        record.n1 = glm::vec4((*n)[1], 0.0f);
        record.n2 = glm::vec4((*n)[2], 0.0f);
    }
}

// The textures that the packed triangles use, with their texture
// coordinates (T0_FEATURE_TEXTURE), where any textured material's
// triangle has coordinates; each textured material's record names its
// texture (type.y, one past its index).
void pack_textures(const Scene& scene, const std::vector<UsableTriangle>& usable,
                   const std::vector<std::uint32_t>& packed_index, PackedScene& packed) {
    const auto valid = [&](int texture) {
        return texture >= 0 && static_cast<std::size_t>(texture) < scene.textures.size();
    };
    const auto textured_material = [&](const Material& m) {
        return (valid(m.texture) && takes_texture(m.type)) || valid(m.alpha_texture) ||
               (is_microfacet(m.type) &&
                (valid(m.roughness_texture) || valid(m.metallic_texture))) ||
               (m.type != MaterialType::emissive && valid(m.normal_texture)) ||
               (m.type == MaterialType::principled && valid(m.emission_texture));
    };
    const auto textured = [&](const UsableTriangle& u) {
        return u.uv != nullptr && textured_material(scene.materials[u.material]);
    };
    if (std::none_of(usable.begin(), usable.end(), textured)) {
        return;
    }
    packed.features |= T0_FEATURE_TEXTURE;
    for (const Texture& t : scene.textures) {
        kernel::TextureRecord record;
        record.info = glm::uvec4(static_cast<std::uint32_t>(packed.texels.size()),
                                 static_cast<std::uint32_t>(t.width),
                                 static_cast<std::uint32_t>(t.height),
                                 static_cast<std::uint32_t>(t.wrap_u) |
                                     static_cast<std::uint32_t>(t.wrap_v) << 2);
        packed.textures.push_back(record);
        packed.texels.insert(packed.texels.end(), t.texels.begin(), t.texels.end());
    }
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        const auto one_past = [&](int texture) {
            return valid(texture) ? static_cast<std::uint32_t>(texture) + 1u : 0u;
        };
        kernel::MaterialRecord& record = packed.materials[m];
        if (takes_texture(material.type)) {
            record.type.y = one_past(material.texture);
        }
        if (is_microfacet(material.type)) {
            record.maps.x = one_past(material.roughness_texture);
            record.maps.y = one_past(material.metallic_texture);
        }
        record.maps.w = one_past(material.alpha_texture);
        if (material.type != MaterialType::emissive) {
            record.maps.z = one_past(material.normal_texture);
            record.k.w = material.normal_scale;
        }
        if (material.type == MaterialType::principled) {
            record.emission.w = static_cast<float>(one_past(material.emission_texture));
        }
    }
    packed.uvs.assign(usable.size(), kernel::TriangleUVs{});
    for (std::size_t u = 0; u < usable.size(); ++u) {
        if (!textured(usable[u])) {
            continue;
        }
        const std::array<glm::vec2, 3>& uv = usable[u].uv->uv;
        kernel::TriangleUVs& record = packed.uvs[packed_index[u]];
        record.uv01 = glm::vec4(uv[0], uv[1]);
        record.uv2 = glm::vec4(uv[2], 1.0f, 0.0f);
    }
}

// The tangents of the packed triangles whose material has a normal map
// (MaterialRecord.maps.z, set by pack_textures): their shape's file's, or
// uv_tangents' where it gives none (computed once per shape).
void pack_tangents(const Scene& scene, const std::vector<UsableTriangle>& usable,
                   const std::vector<std::uint32_t>& packed_index, PackedScene& packed) {
    const auto mapped = [&](const UsableTriangle& u) {
        return u.uv != nullptr && packed.materials[u.material].maps.z != 0u;
    };
    if (std::none_of(usable.begin(), usable.end(), mapped)) {
        return;
    }
    packed.tangents.assign(usable.size(), kernel::VertexTangents{});
    std::vector<std::vector<VertexTangentTriple>> computed(scene.shapes.size());
    for (std::size_t u = 0; u < usable.size(); ++u) {
        if (!mapped(usable[u])) {
            continue;
        }
        const Shape& shape = scene.shapes[usable[u].shape];
        const std::uint32_t index = usable[u].index;
        const VertexTangentTriple* t = nullptr;
        if (index < shape.tangents.size() && shape.tangents[index][0].w != 0.0f) {
            t = &shape.tangents[index];
        } else {
            std::vector<VertexTangentTriple>& own = computed[usable[u].shape];
            if (own.empty()) {
                own = uv_tangents(shape);
            }
            t = &own[index];
        }
        kernel::VertexTangents& record = packed.tangents[packed_index[u]];
        record.t0 = (*t)[0];
        record.t1 = (*t)[1];
        record.t2 = (*t)[2];
    }
}

// The power of two the packer multiplies a scene's coordinates by. The
// triangle test's distance has a numerator that grows as the cube of the
// scene's size (kernel/triangle.h): a scene 1e13 across overflowed it and
// one 1e-13 across was flushed to zero, and neither was ever hit.
// Multiplying every coordinate by a power of two is exact, and the kernel
// is the same at every scale (its offsets and thresholds are relative, and
// a light's density per area times a squared distance does not change), so
// a scaled scene renders as the same scene at ordinary size.
// 1 (the floats as they are) where the largest coordinate is at most 2^38
// (2.7e11: the numerator stays below 24 (2 M)^3, far from FLT_MAX) and the
// typical one (the median over the triangles of their largest coordinate)
// at least 2^-40: every scene of ordinary size, and one with fine detail
// too. Otherwise the power of two that brings the typical coordinate to
// between 1 and 2, or less, so that the largest stays within 2^38: the
// median, not the largest, decides, so that a huge backdrop does not shrink
// the rest below float's smallest normals (a room beside a slab 1e15 wide
// rendered black when the largest decided).
float coordinate_scale(double typical, double largest) {
    const double top = std::ldexp(1.0, 38);
    if (!(typical > 0.0) || (largest <= top && typical >= std::ldexp(1.0, -40))) {
        return 1.0f;
    }
    int exponent = 0;
    std::frexp(typical, &exponent);  // typical = f 2^exponent, f in [0.5, 1)
    int power = 1 - exponent;
    int largest_exponent = 0;
    std::frexp(largest, &largest_exponent);  // largest < 2^largest_exponent
    power = std::min(power, 38 - largest_exponent);
    return std::ldexp(1.0f, power);
}

// A sphere around the triangles: their box's centre and half its
// diagonal, a little more (a unit sphere at the origin for none).
glm::vec4 bounding_sphere(const std::vector<kernel::TriangleRecord>& triangles) {
    if (triangles.empty()) {
        return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    }
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (const kernel::TriangleRecord& t : triangles) {
        for (const glm::vec4& v : {t.v0, t.v1, t.v2}) {
            lo = glm::min(lo, glm::vec3(v));
            hi = glm::max(hi, glm::vec3(v));
        }
    }
    const float radius = 0.5f * glm::length(hi - lo) * 1.001f;
    return glm::vec4(0.5f * (lo + hi), radius > 0.0f ? radius : 1.0f);
}

}  // namespace

PackedScene pack_scene(const Scene& scene, const PackOptions& options) {
    PackedScene packed;
    std::vector<UsableTriangle> usable;
    std::vector<double> magnitudes;  // per usable triangle: its largest coordinate
    for (std::size_t s = 0; s < scene.shapes.size(); ++s) {
        const Shape& shape = scene.shapes[s];
        for (const Triangle& t : shape.triangles) {
            if (!usable_triangle(t)) {
                ++packed.dropped_degenerate_triangles;
                continue;
            }
            const std::size_t index = static_cast<std::size_t>(&t - shape.triangles.data());
            const VertexNormalTriple* normals =
                index < shape.normals.size() && glm::length(shape.normals[index][0]) > 0.0f
                    ? &shape.normals[index]
                    : nullptr;
            const TriangleUv* uv =
                index < shape.uvs.size() && shape.uvs[index].present ? &shape.uvs[index] : nullptr;
            usable.push_back({&t, static_cast<unsigned>(shape.material), static_cast<unsigned>(s),
                              normals, uv, static_cast<std::uint32_t>(index)});
            magnitudes.push_back(
                std::max({kernel::max_abs3(t.v0), kernel::max_abs3(t.v1), kernel::max_abs3(t.v2)}));
        }
    }
    double typical = 0.0;
    double largest = 0.0;
    if (!magnitudes.empty()) {
        largest = *std::max_element(magnitudes.begin(), magnitudes.end());
        const auto middle = magnitudes.begin() + static_cast<long>(magnitudes.size() / 2);
        std::nth_element(magnitudes.begin(), middle, magnitudes.end());
        typical = *middle;
    }
    packed.scale = coordinate_scale(typical, largest);
    // The usable triangles times packed.scale, where it is not 1 (reserved
    // once: usable points into it); one that the scaling made unusable is
    // dropped as well.
    std::vector<Triangle> scaled;
    if (packed.scale != 1.0f) {
        scaled.reserve(usable.size());
        std::vector<UsableTriangle> kept;
        for (const UsableTriangle& u : usable) {
            const Triangle& t = *u.triangle;
            scaled.emplace_back(t.v0 * packed.scale, t.v1 * packed.scale, t.v2 * packed.scale);
            if (!usable_triangle(scaled.back())) {
                ++packed.dropped_degenerate_triangles;
                continue;
            }
            kept.push_back({&scaled.back(), u.material, u.shape, u.normals, u.uv, u.index});
        }
        usable.swap(kept);
    }
    std::vector<bool> material_used(scene.materials.size(), false);
    for (const UsableTriangle& u : usable) {
        material_used[u.material] = true;
    }
    const bool use_bvh =
        !usable.empty() &&
        (options.accel == Accel::bvh ||
         (options.accel == Accel::automatic &&
          usable.size() >= (options.auto_bvh_min_triangles > 0 ? options.auto_bvh_min_triangles
                                                               : auto_bvh_min_triangles)));
    // packed_index[u]: where usable triangle u went (the flat list keeps
    // their order).
    std::vector<std::uint32_t> packed_index(usable.size());
    if (use_bvh) {
        packed.features |= T0_FEATURE_BVH;
        const std::vector<std::uint32_t> order = pack_bvh(usable, packed);
        for (std::size_t i = 0; i < order.size(); ++i) {
            packed_index[order[i]] = static_cast<std::uint32_t>(i);
        }
    } else {
        packed.features |= T0_FEATURE_FLAT;
        pack_flat(usable, packed);
        for (std::size_t u = 0; u < usable.size(); ++u) {
            packed_index[u] = static_cast<std::uint32_t>(u);
        }
    }
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        packed.materials.push_back(pack_material(material));
        if (!material_used[m]) {
            continue;
        }
        packed.features |= material_feature(material);
        if (material.alpha_mode != AlphaMode::opaque) {
            packed.features |= T0_FEATURE_ALPHA;
        }
        const glm::vec3 emitted = emitted_radiance(material);
        if (std::max({emitted.x, emitted.y, emitted.z}) > 0.0f) {
            packed.features |= T0_FEATURE_EMITTANCE;
            if (!material.two_sided) {
                packed.features |= T0_FEATURE_ONE_SIDED;
            }
        }
    }
    pack_normals(usable, packed_index, packed);
    pack_textures(scene, usable, packed_index, packed);
    pack_tangents(scene, usable, packed_index, packed);
    const bool bdpt = options.integrator == Integrator::bdpt;
    pack_lights(scene, packed, packed_index, options.light_sampler);
    if (options.integrator == Integrator::nee && !packed.lights.empty()) {
        packed.features |= T0_FEATURE_NEE;
    }
    if (bdpt) {
        packed.features |= T0_FEATURE_BDPT;
    }
    packed.sphere = bounding_sphere(packed.triangles);
    if (options.sampler == SamplerKind::sobol) {
        packed.features |= T0_FEATURE_SOBOL;
    }
    return packed;
}

kernel::CameraRecord scaled_camera(const kernel::CameraRecord& camera, float scale) {
    kernel::CameraRecord c = camera;
    c.position = glm::vec4(glm::vec3(c.position) * scale, c.position.w);
    c.extent.z *= scale;  // the lens' aperture radius and focus distance: lengths too
    c.extent.w *= scale;
    if (kernel::camera_is_orthographic(c)) {
        c.extent.x *= scale;  // an orthographic view's size
        c.extent.y *= scale;
    }
    return c;
}

std::string feature_names(std::uint32_t features) {
    std::string out;
    for (int bit = 0; bit < T0_FEATURE_COUNT; ++bit) {
        if (features & (1u << bit)) {
            out += (out.empty() ? "" : " ") + std::string(feature_bit_names[bit]);
        }
    }
    return out.empty() ? "none" : out;
}

std::string left_out_feature_names(std::uint32_t features) {
    return feature_names(implemented_features & ~features);
}

}  // namespace trac0r
