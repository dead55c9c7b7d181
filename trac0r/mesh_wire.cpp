#include "trac0r/mesh_wire.h"

#include "trac0r/input_checks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace trac0r {

namespace {

const std::uint32_t wire_begin = 0x54304d31;  // "T0M1"
const std::uint32_t wire_end = 0x54304d45;    // "T0ME"

class WireWriter {
  public:
    void raw(const void* data, std::size_t size) {
        bytes.append(static_cast<const char*>(data), size);
    }
    void u8(std::uint8_t v) { raw(&v, sizeof v); }
    void u32(std::uint32_t v) { raw(&v, sizeof v); }
    void i32(std::int32_t v) { raw(&v, sizeof v); }
    void u64(std::uint64_t v) { raw(&v, sizeof v); }
    void f32(float v) { raw(&v, sizeof v); }
    void vec3(const glm::vec3& v) { raw(&v[0], 3 * sizeof(float)); }
    void vec2(const glm::vec2& v) { raw(&v[0], 2 * sizeof(float)); }
    void text(const std::string& s) {
        u64(s.size());
        raw(s.data(), s.size());
    }
    std::string bytes;
};

class WireReader {
  public:
    explicit WireReader(const std::string& bytes) : bytes_(bytes) {}
    void raw(void* data, std::size_t size) {
        if (size > bytes_.size() - at_) {
            throw WireError("it ends early, at byte " + std::to_string(at_));
        }
        std::memcpy(data, bytes_.data() + at_, size);
        at_ += size;
    }
    template <typename T>
    T get() {
        T v;
        raw(&v, sizeof v);
        return v;
    }
    glm::vec3 vec3(const char* what) {
        glm::vec3 v;
        raw(&v[0], 3 * sizeof(float));
        if (!is_finite(v)) {
            throw WireError(std::string("a ") + what + " that is not finite");
        }
        return v;
    }
    glm::vec2 vec2(const char* what) {
        glm::vec2 v;
        raw(&v[0], 2 * sizeof(float));
        if (!std::isfinite(v.x) || !std::isfinite(v.y)) {
            throw WireError(std::string("a ") + what + " that is not finite");
        }
        return v;
    }
    // A count of items of at least `item_bytes` each, which the rest of
    // the message must be able to hold (so a corrupted count allocates
    // nothing).
    std::size_t count(std::size_t item_bytes, const char* what) {
        const std::uint64_t n = get<std::uint64_t>();
        if (n > (bytes_.size() - at_) / item_bytes) {
            throw WireError(std::string("a count of ") + std::to_string(n) + " " + what +
                            " that its " + std::to_string(bytes_.size() - at_) +
                            " bytes left cannot hold");
        }
        return static_cast<std::size_t>(n);
    }
    std::string text(const char* what) {
        std::string s(count(1, what), '\0');
        raw(&s[0], s.size());
        return s;
    }
    bool done() const { return at_ == bytes_.size(); }

  private:
    const std::string& bytes_;
    std::size_t at_ = 0;
};

}  // namespace

std::string mesh_to_wire(const PartBuilder& parts, const std::vector<int>& part_materials,
                         const MeshParts& files) {
    WireWriter w;
    w.u32(wire_begin);
    w.u64(parts.key.size());
    for (std::size_t part = 0; part < parts.key.size(); ++part) {
        w.i32(part_materials[part]);
        w.u64(parts.triangles[part].size());
        for (const Triangle& t : parts.triangles[part]) {
            w.vec3(t.v0);
            w.vec3(t.v1);
            w.vec3(t.v2);
        }
        w.u8(parts.any_smooth[part] ? 1 : 0);
        if (parts.any_smooth[part]) {
            for (const VertexNormalTriple& n : parts.normals[part]) {
                w.vec3(n[0]);
                w.vec3(n[1]);
                w.vec3(n[2]);
            }
        }
        w.u8(parts.any_uv[part] ? 1 : 0);
        if (parts.any_uv[part]) {
            for (const TriangleUv& t : parts.uvs[part]) {
                w.vec2(t.uv[0]);
                w.vec2(t.uv[1]);
                w.vec2(t.uv[2]);
                w.u8(t.present ? 1 : 0);
            }
        }
        w.u8(parts.any_tangent[part] ? 1 : 0);
        if (parts.any_tangent[part]) {
            for (const VertexTangentTriple& t : parts.tangents[part]) {
                for (const glm::vec4& v : t) {
                    w.vec3(glm::vec3(v));
                    w.f32(v.w);
                }
            }
        }
    }
    w.u64(files.materials.size());
    for (const Material& m : files.materials) {
        w.text(m.name);
        w.u32(static_cast<std::uint32_t>(m.type));
        w.vec3(m.color);
        w.f32(m.emittance);
        w.f32(m.roughness);
        w.f32(m.ior);
        w.i32(m.texture);
        w.u8(m.two_sided ? 1 : 0);
        w.f32(m.metallic);
        w.f32(m.specular);
        w.i32(m.roughness_texture);
        w.i32(m.metallic_texture);
        w.i32(m.normal_texture);
        w.f32(m.normal_scale);
        w.u32(static_cast<std::uint32_t>(m.alpha_mode));
        w.f32(m.alpha);
        w.f32(m.alpha_cutoff);
        w.i32(m.alpha_texture);
        w.i32(m.alpha_channel);
        w.vec3(m.emission);
        w.i32(m.emission_texture);
    }
    w.u64(files.textures.size());
    for (const Texture& t : files.textures) {
        w.text(t.source);
        w.i32(t.width);
        w.i32(t.height);
        w.u32(static_cast<std::uint32_t>(t.wrap_u));
        w.u32(static_cast<std::uint32_t>(t.wrap_v));
        w.u64(t.texels.size());
        w.raw(t.texels.data(), t.texels.size() * sizeof(std::uint32_t));
    }
    w.u64(files.warnings.size());
    for (const std::string& line : files.warnings) {
        w.text(line);
    }
    w.u32(wire_end);
    return std::move(w.bytes);
}

MeshParts mesh_from_wire(const std::string& bytes, const glm::mat4& model, int material) {
    WireReader r(bytes);
    if (r.get<std::uint32_t>() != wire_begin) {
        throw WireError("it does not begin as one");
    }
    MeshParts mesh;
    const std::size_t part_count = r.count(4 + 8 + 36 + 3, "parts");
    if (part_count == 0) {
        throw WireError("no parts");
    }
    std::vector<int> part_materials;
    for (std::size_t part = 0; part < part_count; ++part) {
        const int id = r.get<std::int32_t>();
        const std::size_t n = r.count(36, "triangles");
        if (n == 0) {
            throw WireError("a part without triangles");
        }
        std::vector<Triangle> triangles;
        triangles.reserve(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 a = r.vec3("vertex");
            const glm::vec3 b = r.vec3("vertex");
            const glm::vec3 c = r.vec3("vertex");
            triangles.emplace_back(a, b, c);
        }
        std::vector<VertexNormalTriple> normals;
        const std::uint8_t has_normals = r.get<std::uint8_t>();
        if (has_normals > 1) {
            throw WireError("a part's normals neither there nor not");
        }
        if (has_normals == 1) {
            normals.resize(n);
            for (VertexNormalTriple& t : normals) {
                for (glm::vec3& v : t) {
                    v = r.vec3("vertex normal");
                }
            }
        }
        std::vector<TriangleUv> uvs;
        const std::uint8_t has_uvs = r.get<std::uint8_t>();
        if (has_uvs > 1) {
            throw WireError("a part's texture coordinates neither there nor not");
        }
        if (has_uvs == 1) {
            uvs.resize(n);
            for (TriangleUv& t : uvs) {
                for (glm::vec2& v : t.uv) {
                    v = r.vec2("texture coordinate");
                }
                const std::uint8_t present = r.get<std::uint8_t>();
                if (present > 1) {
                    throw WireError("a triangle's texture coordinates neither there nor not");
                }
                t.present = present == 1;
            }
        }
        std::vector<VertexTangentTriple> tangents;
        const std::uint8_t has_tangents = r.get<std::uint8_t>();
        if (has_tangents > 1) {
            throw WireError("a part's tangents neither there nor not");
        }
        if (has_tangents == 1) {
            tangents.resize(n);
            for (VertexTangentTriple& t : tangents) {
                for (glm::vec4& v : t) {
                    const glm::vec3 direction = r.vec3("tangent");
                    v = glm::vec4(direction, r.get<float>());
                    if (v.w != 0.0f && v.w != 1.0f && v.w != -1.0f) {
                        throw WireError("a tangent's sign that is not -1, 0 or 1");
                    }
                }
            }
        }
        MeshPart p;
        p.shape = make_shape(std::move(triangles), model, material, normals, uvs, tangents);
        p.material = id;
        part_materials.push_back(id);
        mesh.parts.push_back(std::move(p));
    }
    const std::size_t material_count =
        r.count(8 + 4 + 12 + 12 + 4 + 1 + 8 + 16 + 20 + 16, "materials");
    for (std::size_t i = 0; i < material_count; ++i) {
        Material m;
        m.name = r.text("bytes of a material's name");
        const std::uint32_t type = r.get<std::uint32_t>();
        if (type != static_cast<std::uint32_t>(MaterialType::emissive) &&
            type != static_cast<std::uint32_t>(MaterialType::diffuse) &&
            type != static_cast<std::uint32_t>(MaterialType::glass) &&
            type != static_cast<std::uint32_t>(MaterialType::glossy) &&
            type != static_cast<std::uint32_t>(MaterialType::conductor) &&
            type != static_cast<std::uint32_t>(MaterialType::plastic) &&
            type != static_cast<std::uint32_t>(MaterialType::principled)) {
            throw WireError("a material of unknown type " + std::to_string(type));
        }
        m.type = static_cast<MaterialType>(type);
        m.color = r.vec3("colour");
        m.emittance = r.get<float>();
        m.roughness = r.get<float>();
        m.ior = r.get<float>();
        m.texture = r.get<std::int32_t>();
        m.two_sided = r.get<std::uint8_t>() != 0;
        m.metallic = r.get<float>();
        m.specular = r.get<float>();
        m.roughness_texture = r.get<std::int32_t>();
        m.metallic_texture = r.get<std::int32_t>();
        m.normal_texture = r.get<std::int32_t>();
        m.normal_scale = r.get<float>();
        const std::uint32_t alpha_mode = r.get<std::uint32_t>();
        m.alpha = r.get<float>();
        m.alpha_cutoff = r.get<float>();
        m.alpha_texture = r.get<std::int32_t>();
        m.alpha_channel = r.get<std::int32_t>();
        m.emission = r.vec3("emission");
        m.emission_texture = r.get<std::int32_t>();
        if (!(std::min({m.emission.x, m.emission.y, m.emission.z}) >= 0.0f) ||
            !(std::max({m.emission.x, m.emission.y, m.emission.z}) <= max_emitted_radiance) ||
            m.emission_texture < -1 ||
            (m.type != MaterialType::principled &&
             (m.emission != glm::vec3(0.0f) || m.emission_texture != -1))) {
            throw WireError("material " + std::to_string(i) + " with a bad emission");
        }
        if (alpha_mode > 2u || !(m.alpha >= 0.0f && m.alpha <= 1.0f) ||
            !(m.alpha_cutoff >= 0.0f && m.alpha_cutoff <= 1.0f) || m.alpha_texture < -1 ||
            (m.alpha_channel != 0 && m.alpha_channel != 3)) {
            throw WireError("material " + std::to_string(i) + " with a bad alpha");
        }
        m.alpha_mode = static_cast<AlphaMode>(alpha_mode);
        if (!(std::min({m.color.x, m.color.y, m.color.z}) >= 0.0f) ||
            !(std::max({m.color.x, m.color.y, m.color.z}) <= 1.0f) ||
            !(m.metallic >= 0.0f && m.metallic <= 1.0f) ||
            !(m.specular >= 0.0f && m.specular <= 1.0f) ||
            !(m.emittance >= 0.0f && m.emittance <= max_emitted_radiance) ||
            !(m.roughness >= 0.0f && m.roughness <= 1.0f) ||
            !(m.ior > 0.0f && std::isfinite(m.ior))) {
            throw WireError("material " + std::to_string(i) + " with a value out of range");
        }
        if (!std::isfinite(m.normal_scale) || m.roughness_texture < -1 || m.metallic_texture < -1 ||
            m.normal_texture < -1) {
            throw WireError("material " + std::to_string(i) + " with a bad map");
        }
        if (m.texture < -1 || (m.texture >= 0 && !takes_texture(m.type))) {
            throw WireError("material " + std::to_string(i) + " with texture " +
                            std::to_string(m.texture));
        }
        mesh.materials.push_back(std::move(m));
    }
    for (int id : part_materials) {
        if (id < -1 || id >= static_cast<int>(mesh.materials.size())) {
            throw WireError("a part of material " + std::to_string(id) + " of " +
                            std::to_string(mesh.materials.size()));
        }
    }
    const std::size_t texture_count = r.count(8 + 4 + 4 + 4 + 4 + 8, "textures");
    for (std::size_t i = 0; i < texture_count; ++i) {
        Texture t;
        t.source = r.text("bytes of a texture's name");
        t.width = r.get<std::int32_t>();
        t.height = r.get<std::int32_t>();
        if (t.width < 1 || t.height < 1 || t.width > max_texture_side ||
            t.height > max_texture_side) {
            throw WireError("a texture of " + std::to_string(t.width) + " x " +
                            std::to_string(t.height) + " texels");
        }
        const std::uint32_t wrap_u = r.get<std::uint32_t>();
        const std::uint32_t wrap_v = r.get<std::uint32_t>();
        if (wrap_u > 2u || wrap_v > 2u) {
            throw WireError("a texture wrap mode of " + std::to_string(std::max(wrap_u, wrap_v)));
        }
        t.wrap_u = static_cast<TextureWrap>(wrap_u);
        t.wrap_v = static_cast<TextureWrap>(wrap_v);
        t.texels.resize(r.count(sizeof(std::uint32_t), "texels"));
        if (t.texels.size() != static_cast<std::size_t>(t.width) * t.height) {
            throw WireError("a texture of " + std::to_string(t.width) + " x " +
                            std::to_string(t.height) + " with " + std::to_string(t.texels.size()) +
                            " texels");
        }
        r.raw(t.texels.data(), t.texels.size() * sizeof(std::uint32_t));
        mesh.textures.push_back(std::move(t));
    }
    for (const Material& m : mesh.materials) {
        for (int texture : texture_fields(m)) {
            if (texture >= static_cast<int>(mesh.textures.size())) {
                throw WireError("a material of texture " + std::to_string(texture) + " of " +
                                std::to_string(mesh.textures.size()));
            }
        }
    }
    const std::size_t warning_count = r.count(8, "warnings");
    for (std::size_t i = 0; i < warning_count; ++i) {
        mesh.warnings.push_back(printable(r.text("bytes of a warning"), 1000));
    }
    if (r.get<std::uint32_t>() != wire_end || !r.done()) {
        throw WireError("it does not end as one");
    }
    return mesh;
}

}  // namespace trac0r
