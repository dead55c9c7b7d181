#include "trac0r/scene.h"

#include <cmath>

namespace trac0r {

std::size_t Scene::triangle_count() const {
    std::size_t n = 0;
    for (const Shape& s : shapes) {
        n += s.triangles.size();
    }
    return n;
}

glm::dvec3 local_origin(const glm::dvec3& position) {
    const double grid = 1024.0;
    return glm::dvec3(grid * std::round(position.x / grid), grid * std::round(position.y / grid),
                      grid * std::round(position.z / grid));
}

namespace {

class Fnv1a {
  public:
    void bytes(const void* data, std::size_t size) {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
        }
    }
    template <typename T>
    void value(T v) {
        bytes(&v, sizeof v);
    }
    void vec3(const glm::vec3& v) {
        value(v.x);
        value(v.y);
        value(v.z);
    }
    std::uint64_t hash() const { return hash_; }

  private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::uint64_t scene_digest(const Scene& scene) {
    Fnv1a h;
    h.value(scene.origin.x);
    h.value(scene.origin.y);
    h.value(scene.origin.z);
    h.vec3(scene.camera.position);
    h.vec3(scene.camera.direction);
    h.vec3(scene.camera.world_up);
    // The size of the view its projection uses (the other is not written
    // or read with it).
    h.value(scene.camera.projection == Projection::orthographic ? scene.camera.view_height
                                                                 : scene.camera.vertical_fov);
    h.value(scene.render.width);
    h.value(scene.render.height);
    h.value(scene.render.max_depth);
    h.value(scene.materials.size());
    for (const Material& m : scene.materials) {
        h.value(m.name.size());
        h.bytes(m.name.data(), m.name.size());
        h.value(static_cast<int>(m.type));
        h.vec3(m.color);
        h.value(m.emittance);
        h.value(m.roughness);
        h.value(m.ior);
        h.value(m.texture);
        h.value(static_cast<int>(m.two_sided));
        h.value(m.metal.size());
        h.bytes(m.metal.data(), m.metal.size());
        h.value(m.metallic);
        h.value(m.specular);
        h.value(m.roughness_texture);
        h.value(m.metallic_texture);
        h.value(m.normal_texture);
        h.value(m.normal_scale);
        h.value(static_cast<int>(m.alpha_mode));
        h.value(m.alpha);
        h.value(m.alpha_cutoff);
        h.value(m.alpha_texture);
        h.value(m.alpha_channel);
        h.vec3(m.emission);
        h.value(m.emission_texture);
    }
    h.value(scene.shapes.size());
    for (const Shape& s : scene.shapes) {
        h.value(s.material);
        h.value(s.triangles.size());
        for (const Triangle& t : s.triangles) {
            h.vec3(t.v0);
            h.vec3(t.v1);
            h.vec3(t.v2);
        }
        h.value(s.normals.size());
        for (const VertexNormalTriple& n : s.normals) {
            h.vec3(n[0]);
            h.vec3(n[1]);
            h.vec3(n[2]);
        }
        h.value(s.uvs.size());
        for (const TriangleUv& t : s.uvs) {
            h.value(static_cast<int>(t.present));
            for (const glm::vec2& uv : t.uv) {
                h.value(uv.x);
                h.value(uv.y);
            }
        }
        h.value(s.tangents.size());
        for (const VertexTangentTriple& t : s.tangents) {
            for (const glm::vec4& v : t) {
                h.vec3(glm::vec3(v));
                h.value(v.w);
            }
        }
    }
    h.value(scene.textures.size());
    for (const Texture& t : scene.textures) {
        h.value(t.width);
        h.value(t.height);
        h.value(static_cast<unsigned>(t.wrap_u));
        h.value(static_cast<unsigned>(t.wrap_v));
        h.bytes(t.texels.data(), t.texels.size() * sizeof(std::uint32_t));
    }
    const Environment& e = scene.environment;
    h.value(static_cast<int>(e.present));
    h.value(e.strength);
    h.value(e.rotation);
    h.vec3(e.color);
    h.value(e.width);
    h.value(e.height);
    for (const glm::vec3& t : e.texels) {
        h.vec3(t);
    }
    h.value(scene.lamps.size());
    for (const Lamp& l : scene.lamps) {
        h.value(static_cast<int>(l.type));
        h.vec3(l.position);
        h.vec3(l.direction);
        h.vec3(l.color);
        h.value(l.power);
        h.value(l.angle);
        h.value(l.blend);
    }
    return h.hash();
}

}  // namespace trac0r
