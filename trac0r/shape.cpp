#include "trac0r/shape.h"

#include "trac0r/file_materials.h"
#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/isolated_call.h"
#include "trac0r/obj_checker.h"

#include <tiny_obj_loader.h>

#include <assimp/BaseImporter.h>
#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/scene.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <istream>
#include <streambuf>
#include <stdexcept>
#include <utility>

namespace trac0r {

glm::mat4 model_matrix(const glm::vec3& position, const glm::vec3& orientation,
                       const glm::vec3& scale) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
    m = glm::rotate(m, orientation.x, glm::vec3(1, 0, 0));
    m = glm::rotate(m, orientation.y, glm::vec3(0, 1, 0));
    m = glm::rotate(m, orientation.z, glm::vec3(0, 0, 1));
    return glm::scale(m, scale);
}

Shape make_shape(std::vector<Triangle> local_triangles, const glm::mat4& model, int material,
                 const std::vector<VertexNormalTriple>& local_normals,
                 const std::vector<TriangleUv>& local_uvs) {
    // A mirroring transform turns the winding inside out; swap two vertices
    // so normals keep pointing out of closed shapes (glass needs that).
    const bool mirrored = glm::determinant(glm::mat3(model)) < 0.0f;
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
    Shape shape;
    shape.material = material;
    shape.triangles.reserve(local_triangles.size());
    for (const Triangle& t : local_triangles) {
        const glm::vec3 a = glm::vec3(model * glm::vec4(t.v0, 1.0f));
        const glm::vec3 b = glm::vec3(model * glm::vec4(t.v1, 1.0f));
        const glm::vec3 c = glm::vec3(model * glm::vec4(t.v2, 1.0f));
        shape.triangles.push_back(mirrored ? Triangle(a, c, b) : Triangle(a, b, c));
        shape.aabb.extend(shape.triangles.back().bounds());
    }
    shape.normals.reserve(local_normals.size());
    for (const VertexNormalTriple& n : local_normals) {
        VertexNormalTriple world = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
        const VertexNormalTriple moved = {normal_matrix * n[0], normal_matrix * n[1],
                                          normal_matrix * n[2]};
        // Flat stays flat (zero); a normal the transform makes unusable
        // (not finite, or of no length) makes the triangle flat.
        bool usable = glm::length(n[0]) > 0.0f;
        for (const glm::vec3& m : moved) {
            const float length = glm::length(m);
            usable = usable && is_finite(m) && length > 0.0f && std::isfinite(length);
        }
        if (usable) {
            world = {glm::normalize(moved[0]), glm::normalize(moved[mirrored ? 2 : 1]),
                     glm::normalize(moved[mirrored ? 1 : 2])};
        }
        shape.normals.push_back(world);
    }
    shape.uvs = local_uvs;
    if (mirrored) {
        for (TriangleUv& t : shape.uvs) {
            std::swap(t.uv[1], t.uv[2]);
        }
    }
    return shape;
}

namespace {

// Two triangles of the quad centre +- u/2 +- v/2, wound so their normal is
// cross(u, v).
void add_quad(std::vector<Triangle>& out, const glm::vec3& centre, const glm::vec3& u,
              const glm::vec3& v) {
    const glm::vec3 a = centre - 0.5f * u - 0.5f * v;
    const glm::vec3 b = centre + 0.5f * u - 0.5f * v;
    const glm::vec3 c = centre + 0.5f * u + 0.5f * v;
    const glm::vec3 d = centre - 0.5f * u + 0.5f * v;
    out.emplace_back(a, b, c);
    out.emplace_back(a, c, d);
}

std::vector<Triangle> unit_icosphere(int subdivisions) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : v) {
        p = glm::normalize(p);
    }
    std::vector<std::array<int, 3>> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<int, int>, int> midpoints;
        auto midpoint = [&](int i, int j) {
            const std::pair<int, int> key(std::min(i, j), std::max(i, j));
            auto found = midpoints.find(key);
            if (found != midpoints.end()) {
                return found->second;
            }
            v.push_back(glm::normalize(v[i] + v[j]));
            const int index = static_cast<int>(v.size()) - 1;
            midpoints[key] = index;
            return index;
        };
        std::vector<std::array<int, 3>> next;
        next.reserve(faces.size() * 4);
        for (const auto& f : faces) {
            const int ab = midpoint(f[0], f[1]);
            const int bc = midpoint(f[1], f[2]);
            const int ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces.swap(next);
    }
    std::vector<Triangle> out;
    out.reserve(faces.size());
    for (const auto& f : faces) {
        Triangle tri(v[f[0]], v[f[1]], v[f[2]]);
        // Convex and centred on the origin: outward means away from it.
        if (glm::dot(tri.normal, tri.centroid) < 0.0f) {
            tri = Triangle(v[f[0]], v[f[2]], v[f[1]]);
        }
        out.push_back(tri);
    }
    return out;
}

}  // namespace

Shape make_plane(const glm::vec3& position, const glm::vec3& orientation, const glm::vec2& size,
                 int material) {
    std::vector<Triangle> local;
    // Normal +y = cross(+z, +x).
    add_quad(local, glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0));
    return make_shape(local, model_matrix(position, orientation, glm::vec3(size.x, 1.0f, size.y)),
                      material);
}

Shape make_box(const glm::vec3& position, const glm::vec3& orientation, const glm::vec3& size,
               int material) {
    const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    std::vector<Triangle> local;
    // Each face's (u, v) has cross(u, v) along its outward normal.
    add_quad(local, 0.5f * x, y, z);
    add_quad(local, -0.5f * x, z, y);
    add_quad(local, 0.5f * y, z, x);
    add_quad(local, -0.5f * y, x, z);
    add_quad(local, 0.5f * z, x, y);
    add_quad(local, -0.5f * z, y, x);
    return make_shape(local, model_matrix(position, orientation, size), material);
}

Shape make_icosphere(const glm::vec3& position, const glm::vec3& orientation, float radius,
                     int subdivisions, int material) {
    return make_shape(unit_icosphere(subdivisions),
                      model_matrix(position, orientation, glm::vec3(radius)), material);
}

namespace {

// A read-only stream over a string that outlives it, for tinyobjloader:
// no second copy of a mesh's text.
class TextBuffer : public std::streambuf {
  public:
    explicit TextBuffer(std::string& text) { setg(&text[0], &text[0], &text[0] + text.size()); }
};

// tinyobjloader's reader of the mtllib files: each one's text checked
// (checked_mtl_text) first, relative to the OBJ's directory; which file
// each material came from is kept.
class CheckedMtlReader : public tinyobj::MaterialReader {
  public:
    CheckedMtlReader(const std::string& obj_path, const std::vector<ObjNameRef>& libraries)
        : obj_path_(obj_path), libraries_(libraries) {
        const std::size_t slash = obj_path.find_last_of('/');
        dir_ = slash == std::string::npos ? "" : obj_path.substr(0, slash + 1);
    }
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* map, std::string* warn, std::string* err) override {
        // tinyobjloader asks for the first file of an mtllib line and stops
        // there: every file of the line is read here.
        long line = 0;
        for (const ObjNameRef& r : libraries_) {
            if (r.name == name) {
                line = r.line;
                break;
            }
        }
        for (const ObjNameRef& r : libraries_) {
            if (r.line == line) {
                load(r.name, line, materials, map, warn, err);
            }
        }
        return true;
    }
    std::vector<std::string> files;  // per material: its file

  private:
    void load(const std::string& name, long line, std::vector<tinyobj::material_t>* materials,
              std::map<std::string, int>* map, std::string* warn, std::string* err) {
        const std::string file = !name.empty() && name[0] == '/' ? name : dir_ + name;
        std::string text;
        try {
            text = checked_mtl_text(file);
        } catch (const std::runtime_error& e) {
            // Named by the OBJ's mtllib line as well.
            throw std::runtime_error(obj_path_ + ":" + std::to_string(line) + ": mtllib '" + name +
                                     "': " + e.what());
        }
        TextBuffer buffer(text);
        std::istream stream(&buffer);
        tinyobj::LoadMtl(map, materials, &stream, warn, err);
        files.resize(materials->size(), file);
    }

    std::string obj_path_;
    std::string dir_;
    const std::vector<ObjNameRef>& libraries_;
};

// Whether a PLY's text has the line that ends its header: "end_header"
// alone on a line (LF or CR LF), within the first megabyte.
bool has_ply_header_end(const std::string& text) {
    const std::size_t limit = std::min<std::size_t>(text.size(), 1u << 20);
    for (std::size_t at = text.find("\nend_header"); at != std::string::npos && at < limit;
         at = text.find("\nend_header", at + 1)) {
        const std::size_t after = at + 11;
        if (after < text.size() &&
            (text[after] == '\n' ||
             (text[after] == '\r' && after + 1 < text.size() && text[after + 1] == '\n'))) {
            return true;
        }
    }
    return false;
}

// The index in mesh.textures of the texture from `source`, made by
// load() the first time a material of the file uses it.
template <typename Load>
int texture_index(MeshParts& mesh, const std::string& source, Load load) {
    for (std::size_t i = 0; i < mesh.textures.size(); ++i) {
        if (mesh.textures[i].source == source) {
            return static_cast<int>(i);
        }
    }
    mesh.textures.push_back(load());
    return static_cast<int>(mesh.textures.size()) - 1;
}

// A texture's file name as a material file gives it, relative to that
// file's directory (a Windows exporter's '\\' read as '/').
std::string texture_path_beside(const std::string& mtl_file, std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    while (name.compare(0, 2, "./") == 0) {
        name.erase(0, 2);
    }
    if (!name.empty() && name[0] == '/') {
        return name;
    }
    const std::size_t slash = mtl_file.find_last_of('/');
    return (slash == std::string::npos ? "" : mtl_file.substr(0, slash + 1)) + name;
}

// The texture of an assimp material of the first of `types` it has (for
// the base colour glTF's baseColorTexture: BASE_COLOR, then DIFFUSE) as an
// index into mesh.textures, or -1 for none: an image embedded in the file
// (a .glb's buffer, a data URI: "*N") or a file beside it. `what` names it
// in messages ("base colour").
int assimp_texture(const aiScene& scene, const aiMaterial& m, const std::string& path,
                   MeshParts& mesh, std::uint64_t texel_budget,
                   std::initializer_list<aiTextureType> types, const char* what) {
    // What the file's textures so far leave of the scene's room.
    const std::uint64_t room = texel_budget - texel_count(mesh.textures);
    aiString name;
    bool found = false;
    for (aiTextureType type : types) {
        if (!found && m.GetTexture(type, 0, &name) == AI_SUCCESS) {
            found = true;
        }
    }
    if (!found) {
        return -1;
    }
    aiString material_name;
    m.Get(AI_MATKEY_NAME, material_name);
    const std::string file = name.C_Str();
    const std::string where = path + ": material '" + printable(material_name.C_Str(), 60) +
                              "': " + what + " texture '" + printable(file, 200) + "'";
    const aiTexture* embedded = scene.GetEmbeddedTexture(name.C_Str());
    if (embedded != nullptr) {
        return texture_index(mesh, path + " " + file, [&] {
            if (embedded->mHeight != 0) {
                // Uncompressed: mWidth x mHeight texels, BGRA.
                if (embedded->mWidth == 0 ||
                    embedded->mWidth > static_cast<unsigned>(max_texture_side) ||
                    embedded->mHeight > static_cast<unsigned>(max_texture_side)) {
                    throw std::runtime_error(where + ": expected each side at most " +
                                             std::to_string(max_texture_side));
                }
                check_texture_room(where, static_cast<int>(embedded->mWidth),
                                   static_cast<int>(embedded->mHeight), room);
                Texture t;
                t.source = path + " " + file;
                t.width = static_cast<int>(embedded->mWidth);
                t.height = static_cast<int>(embedded->mHeight);
                t.texels.resize(static_cast<std::size_t>(t.width) * t.height);
                for (std::size_t i = 0; i < t.texels.size(); ++i) {
                    const aiTexel& c = embedded->pcData[i];
                    t.texels[i] = static_cast<std::uint32_t>(c.r) |
                                  static_cast<std::uint32_t>(c.g) << 8 |
                                  static_cast<std::uint32_t>(c.b) << 16 |
                                  static_cast<std::uint32_t>(c.a) << 24;
                }
                return t;
            }
            // Compressed (PNG, JPEG): mWidth bytes.
            return decode_texture(where, path + " " + file,
                                  reinterpret_cast<const unsigned char*>(embedded->pcData),
                                  embedded->mWidth, room);
        });
    }
    if (!file.empty() && file[0] == '*') {
        throw std::runtime_error(where + ": the file has no embedded image of that number");
    }
    const std::string texture = texture_path_beside(path, file);
    return texture_index(mesh, texture,
                         [&] { return load_texture_file(where, texture, room); });
}

// Faces grouped into parts by a material key (first use first), with
// their normals; what load_obj and load_assimp fill.
struct PartBuilder {
    std::vector<int> key;
    std::vector<std::vector<Triangle>> triangles;
    std::vector<std::vector<VertexNormalTriple>> normals;
    std::vector<std::vector<TriangleUv>> uvs;
    std::vector<bool> any_smooth;
    std::vector<bool> any_uv;

    void add(int material_key, const glm::vec3 p[3], VertexNormalTriple n, bool has_normals,
             bool smooth, const TriangleUv& uv) {
        std::size_t part =
            static_cast<std::size_t>(std::find(key.begin(), key.end(), material_key) - key.begin());
        if (part == key.size()) {
            key.push_back(material_key);
            triangles.emplace_back();
            normals.emplace_back();
            uvs.emplace_back();
            any_smooth.push_back(false);
            any_uv.push_back(false);
        }
        triangles[part].emplace_back(p[0], p[1], p[2]);
        if (!has_normals || !smooth) {
            n = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
        }
        any_smooth[part] = any_smooth[part] || (has_normals && smooth);
        normals[part].push_back(n);
        any_uv[part] = any_uv[part] || uv.present;
        // Coordinates of some corners only: none.
        uvs[part].push_back(uv.present ? uv : TriangleUv());
    }

    // The parts as shapes; `material_of(key, mesh)` maps a key to the
    // file's material (its index in mesh.materials, appended with its
    // texture), or -1.
    template <typename MaterialOf>
    MeshParts finish(const std::string& path, const char* what, const glm::mat4& model,
                     int material, MaterialOf material_of) {
        if (triangles.empty()) {
            throw std::runtime_error(path + ": " + what + " has no triangles");
        }
        MeshParts mesh;
        for (std::size_t part = 0; part < triangles.size(); ++part) {
            if (!any_smooth[part]) {
                normals[part].clear();
            }
            if (!any_uv[part]) {
                uvs[part].clear();
            }
            MeshPart p;
            p.shape = make_shape(triangles[part], model, material, normals[part], uvs[part]);
            p.material = material_of(key[part], mesh);
            mesh.parts.push_back(std::move(p));
        }
        return mesh;
    }
};

MeshParts load_obj(const std::string& path, const glm::vec3& position, const glm::vec3& orientation,
                   const glm::vec3& scale, int material, bool smooth, bool read_mtl,
                   std::uint64_t texel_budget) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn;
    std::string err;
    CheckedObj checked = check_obj(path);
    TextBuffer buffer(checked.text);
    std::istream text(&buffer);
    CheckedMtlReader reader(path, checked.libraries);
    // Triangulate polygons; the materials from the mtllib files, where
    // asked for.
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &text,
                          read_mtl ? &reader : nullptr, true)) {
        throw std::runtime_error(path + ": cannot read OBJ mesh" + (err.empty() ? "" : ": " + err));
    }
    // An OBJ without mtllib names materials it does not have: its usemtl
    // are ignored, and every face takes `material`.
    read_mtl = read_mtl && !checked.libraries.empty();
    if (read_mtl) {
        for (const ObjNameRef& used : checked.materials) {
            if (std::none_of(materials.begin(), materials.end(),
                             [&](const tinyobj::material_t& m) { return m.name == used.name; })) {
                std::string files;
                for (const ObjNameRef& lib : checked.libraries) {
                    files += (files.empty() ? "" : ", ") + lib.name;
                }
                throw std::runtime_error(path + ":" + std::to_string(used.line) + ": usemtl '" +
                                         used.name + "': no material of that name in its mtllib " +
                                         "files (" + files + ")");
            }
        }
    }
    const std::size_t vertex_count = attrib.vertices.size() / 3;
    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;
    PartBuilder parts;
    for (const tinyobj::shape_t& s : shapes) {
        for (std::size_t i = 0; i + 2 < s.mesh.indices.size(); i += 3) {
            glm::vec3 p[3];
            VertexNormalTriple n = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
            bool has_normals = true;
            TriangleUv uv;
            uv.present = true;
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& ref = s.mesh.indices[i + k];
                const int texcoord = ref.texcoord_index;
                if (texcoord >= 0 && static_cast<std::size_t>(texcoord) >= texcoord_count) {
                    throw std::runtime_error(path + ": face of shape '" + s.name +
                                             "' refers to texture coordinate " +
                                             std::to_string(texcoord + 1) + ", but the file has " +
                                             std::to_string(texcoord_count) + " (vt)");
                }
                if (texcoord < 0) {
                    uv.present = false;
                } else {
                    uv.uv[k] = glm::vec2(attrib.texcoords[2 * texcoord],
                                         attrib.texcoords[2 * texcoord + 1]);
                }
                const int index = ref.vertex_index;
                if (index < 0 || static_cast<std::size_t>(index) >= vertex_count) {
                    throw std::runtime_error(path + ": face of shape '" + s.name +
                                             "' refers to vertex " + std::to_string(index + 1) +
                                             ", but the file has " + std::to_string(vertex_count) +
                                             " vertices");
                }
                p[k] = glm::vec3(attrib.vertices[3 * index], attrib.vertices[3 * index + 1],
                                 attrib.vertices[3 * index + 2]);
                const int normal = ref.normal_index;
                if (normal >= 0 && static_cast<std::size_t>(normal) >= normal_count) {
                    throw std::runtime_error(path + ": face of shape '" + s.name +
                                             "' refers to normal " + std::to_string(normal + 1) +
                                             ", but the file has " + std::to_string(normal_count) +
                                             " normals (vn)");
                }
                if (normal < 0) {
                    has_normals = false;
                    continue;
                }
                n[k] = glm::vec3(attrib.normals[3 * normal], attrib.normals[3 * normal + 1],
                                 attrib.normals[3 * normal + 2]);
                // A zero normal (some exporters write "vn 0 0 0") shades flat.
                if (!(glm::length(n[k]) > 0.0f)) {
                    has_normals = false;
                }
            }
            const std::size_t face = i / 3;
            const int id =
                read_mtl && face < s.mesh.material_ids.size() ? s.mesh.material_ids[face] : -1;
            parts.add(id, p, n, has_normals, smooth, uv);
        }
    }
    return parts.finish(
        path, "OBJ mesh", model_matrix(position, orientation, scale), material,
        [&](int id, MeshParts& mesh) {
            if (id < 0) {
                return -1;
            }
            const std::size_t k = static_cast<std::size_t>(id);
            const std::string& file = k < reader.files.size() ? reader.files[k] : path;
            Material m = material_from_mtl(materials[k], file);
            // The texture a statement (key) of the material names, as
            // an index into mesh.textures; -1 where it names none.
            const auto load = [&](const std::string& map, const char* key) {
                if (map.empty()) {
                    return -1;
                }
                const std::string texture = texture_path_beside(file, map);
                return texture_index(mesh, texture, [&] {
                    return load_texture_file(file + ": material '" + printable(m.name, 60) +
                                                 "': " + key + " '" + printable(map, 200) + "'",
                                             texture, texel_budget - texel_count(mesh.textures));
                });
            };
            const tinyobj::material_t& mtl = materials[k];
            const char* key = "";
            const std::string map = mtl_texture_name(mtl, m, &key);
            m.texture = load(map, key);
            if (is_microfacet(m.type)) {
                m.roughness_texture = load(mtl.roughness_texname, "map_Pr");
                m.metallic_texture = load(mtl.metallic_texname, "map_Pm");
            }
            if (m.alpha_mode != AlphaMode::opaque) {
                m.alpha_texture = load(mtl.alpha_texname, "map_d");
            }
            if (m.type != MaterialType::emissive) {
                // A normal map: norm, or map_Bump as Blender reads it.
                m.normal_texture = mtl.normal_texname.empty()
                                       ? load(mtl.bump_texname, "map_Bump")
                                       : load(mtl.normal_texname, "norm");
            }
            mesh.materials.push_back(m);
            return static_cast<int>(mesh.materials.size()) - 1;
        });
}

// Leaves `importer` with only its reader named `name` (an
// aiImporterDesc::mName). With all of them, assimp guesses the format from
// the contents of a file its extension's reader cannot read: a .glb or
// .gltf that is no glTF went to whichever of its other readers (STL,
// OBJ, OFF, Blender, ...) claimed it, readers trac0r neither documents nor
// fuzzes. And glTF 1.0's reader, which also claims .gltf and .glb, is not
// the glTF 2.0 that docs/scene-format.md promises. The importer does not
// delete the readers it unregisters: deleted here.
void keep_only_reader(Assimp::Importer& importer, const char* name, const std::string& path) {
    bool kept = false;
    for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
        const aiImporterDesc* desc = importer.GetImporterInfo(i);
        if (!kept && desc != nullptr && std::strcmp(desc->mName, name) == 0) {
            kept = true;
            continue;
        }
        Assimp::BaseImporter* reader = importer.GetImporter(i);
        if (importer.UnregisterLoader(reader) == AI_SUCCESS) {
            delete reader;
        }
    }
    if (!kept) {
        throw std::runtime_error(path + ": cannot read mesh: this build of assimp has no " + name);
    }
}

// The plain result of a PLY or glTF import, as its child process sends it
// to the parent (in this machine's byte order: the same program reads
// it): per part its material (an index into the materials, or -1), its
// triangles as the file places them (before the shape's transform), their
// vertex normals and texture coordinates where the part has them; then the
// materials and the textures they use.
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

// A result that does not read as WireWriter wrote it: the child's memory
// was corrupted (by the reader) or its message cut short.
struct WireError : std::runtime_error {
    using std::runtime_error::runtime_error;
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

// "the PLY reader (assimp)", for messages.
std::string assimp_reader_name(bool ply) {
    return ply ? "the PLY reader (assimp)" : "the glTF reader (assimp)";
}

// The import itself, in the child process: assimp's reader of the format
// alone, our conversion of its scene into plain parts, materials and
// textures; everything that touches assimp's structures is here. Throws
// std::runtime_error naming the file for what assimp or our checks refuse.
std::string import_assimp(const std::string& path, const std::string& text, bool ply,
                          bool smooth, bool file_materials, std::uint64_t texel_budget) {
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // No post-processing: assimp 5.2's steps trust the faces' indices,
    // and on a broken PLY face its triangulation aborts the process (an
    // ai_assert) and its vertex pre-transform reads out of bounds (both
    // found by tests/fuzz/fuzz_mesh). Indices are checked below, polygons
    // split into fans and the nodes' transforms applied here.
    const unsigned flags = 0;
    const bool gltf = has_extension(path, ".gltf");
    keep_only_reader(importer, ply ? "Stanford Polygon Library (PLY) Importer" : "glTF2 Importer",
                     path);
    const aiScene* scene =
        gltf ? importer.ReadFile(path, flags)
             : importer.ReadFileFromMemory(text.data(), text.size(), flags,
                                           has_extension(path, ".glb") ? "glb" : "ply");
    if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
        std::string reason = importer.GetErrorString();
        reason.erase(reason.find_last_not_of(" \n\r") + 1);
        throw std::runtime_error(path + ": cannot read mesh: " +
                                 (reason.empty() ? std::string("no scene in it") : reason));
    }
    // Each node's meshes, with the node's transform (and its parents'):
    // (mesh index, transform) in the order of a depth-first walk.
    std::vector<std::pair<unsigned, aiMatrix4x4>> instances;
    const int max_node_depth = 256;
    const std::function<void(const aiNode&, const aiMatrix4x4&, int)> walk =
        [&](const aiNode& node, const aiMatrix4x4& parent, int depth) {
            if (depth > max_node_depth) {
                throw std::runtime_error(path + ": cannot read mesh: its nodes nest deeper than " +
                                         std::to_string(max_node_depth));
            }
            const aiMatrix4x4 transform = parent * node.mTransformation;
            for (unsigned k = 0; k < node.mNumMeshes; ++k) {
                if (node.mMeshes[k] < scene->mNumMeshes) {
                    instances.emplace_back(node.mMeshes[k], transform);
                }
            }
            for (unsigned c = 0; c < node.mNumChildren; ++c) {
                if (node.mChildren[c] != nullptr) {
                    walk(*node.mChildren[c], transform, depth + 1);
                }
            }
        };
    if (scene->mRootNode != nullptr) {
        walk(*scene->mRootNode, aiMatrix4x4(), 0);
    }
    PartBuilder parts;
    for (const std::pair<unsigned, aiMatrix4x4>& instance : instances) {
        const aiMesh& mesh = *scene->mMeshes[instance.first];
        const aiMatrix4x4& to_world = instance.second;
        aiMatrix3x3 normal_matrix(to_world);
        // A mirroring node turns the winding inside out: two corners are
        // swapped (with their normals and coordinates), as make_shape does.
        const bool mirrored = aiMatrix3x3(to_world).Determinant() < 0.0f;
        normal_matrix.Inverse().Transpose();
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            // A polygon as a fan of triangles around its first corner;
            // points and lines (SortByPType leaves none) give none.
            for (unsigned fan = 1; fan + 1 < face.mNumIndices; ++fan) {
                const unsigned corners[3] = {face.mIndices[0],
                                             face.mIndices[mirrored ? fan + 1 : fan],
                                             face.mIndices[mirrored ? fan : fan + 1]};
                glm::vec3 p[3];
                VertexNormalTriple n = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
                bool has_normals = mesh.HasNormals();
                TriangleUv uv;
                uv.present = mesh.HasTextureCoords(0);
                for (int k = 0; k < 3; ++k) {
                    const unsigned index = corners[k];
                    if (index >= mesh.mNumVertices) {
                        throw std::runtime_error(
                            path + ": mesh '" + printable(mesh.mName.C_Str(), 60) +
                            "': a face refers to vertex " + std::to_string(index) +
                            ", but the mesh has " + std::to_string(mesh.mNumVertices));
                    }
                    const aiVector3D v = to_world * mesh.mVertices[index];
                    p[k] = glm::vec3(v.x, v.y, v.z);
                    if (!is_finite(p[k])) {
                        throw std::runtime_error(path + ": mesh '" +
                                                 printable(mesh.mName.C_Str(), 60) + "': vertex " +
                                                 std::to_string(index) + " is not finite");
                    }
                    if (uv.present) {
                        const aiVector3D& t = mesh.mTextureCoords[0][index];
                        uv.uv[k] = glm::vec2(t.x, t.y);
                        uv.present = std::isfinite(t.x) && std::isfinite(t.y);
                    }
                    if (has_normals) {
                        const aiVector3D vn = normal_matrix * mesh.mNormals[index];
                        n[k] = glm::vec3(vn.x, vn.y, vn.z);
                        has_normals = is_finite(n[k]) && glm::length(n[k]) > 0.0f;
                    }
                }
                // A PLY has no materials (assimp gives it a default one).
                parts.add(file_materials && !ply ? static_cast<int>(mesh.mMaterialIndex) : -1, p, n,
                          has_normals, smooth, uv);
            }
        }
    }
    if (parts.triangles.empty()) {
        throw std::runtime_error(path + ": mesh has no triangles");
    }
    // The file's materials (and their textures) as the parts use them.
    MeshParts files;
    const auto material_of = [&](int id) {
        if (id < 0 || static_cast<unsigned>(id) >= scene->mNumMaterials) {
            return -1;
        }
        const aiMaterial& m = *scene->mMaterials[id];
        if (is_default_material(m)) {
            return -1;
        }
        Material out = material_from_assimp(m, path);
        if (out.type == MaterialType::emissive) {
            out.texture = assimp_texture(*scene, m, path, files, texel_budget,
                                         {aiTextureType_EMISSIVE}, "emissive");
        } else if (takes_texture(out.type)) {
            out.texture = assimp_texture(*scene, m, path, files, texel_budget,
                                         {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE},
                                         "base colour");
        }
        if (is_microfacet(out.type)) {
            // glTF's metallicRoughnessTexture: roughness in green, metallic
            // in blue, one image for both.
            out.roughness_texture = assimp_texture(
                *scene, m, path, files, texel_budget,
                {aiTextureType_UNKNOWN, aiTextureType_DIFFUSE_ROUGHNESS, aiTextureType_METALNESS},
                "metallic-roughness");
            out.metallic_texture = out.roughness_texture;
        }
        if (out.alpha_mode != AlphaMode::opaque) {
            out.alpha_texture = out.texture;  // the base colour's alpha
        }
        if (out.type != MaterialType::emissive) {
            out.normal_texture = assimp_texture(*scene, m, path, files, texel_budget,
                                                {aiTextureType_NORMALS}, "normal");
            float scale = 1.0f;
            if (out.normal_texture >= 0 &&
                m.Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), scale) ==
                    AI_SUCCESS &&
                std::isfinite(scale)) {
                out.normal_scale = scale;
            }
        }
        files.materials.push_back(out);
        return static_cast<int>(files.materials.size()) - 1;
    };
    WireWriter w;
    w.u32(wire_begin);
    w.u64(parts.key.size());
    for (std::size_t part = 0; part < parts.key.size(); ++part) {
        w.i32(material_of(parts.key[part]));
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
    }
    w.u64(files.textures.size());
    for (const Texture& t : files.textures) {
        w.text(t.source);
        w.i32(t.width);
        w.i32(t.height);
        w.u64(t.texels.size());
        w.raw(t.texels.data(), t.texels.size() * sizeof(std::uint32_t));
    }
    w.u32(wire_end);
    return std::move(w.bytes);
}

// The parts import_assimp sent, each made a shape (model, `material` for
// the faces without the file's), checked again here: the child's memory
// may have been corrupted by the reader without its crashing. Throws
// WireError for what does not read as import_assimp writes it.
MeshParts mesh_from_wire(const std::string& bytes, const glm::mat4& model, int material) {
    WireReader r(bytes);
    if (r.get<std::uint32_t>() != wire_begin) {
        throw WireError("it does not begin as one");
    }
    MeshParts mesh;
    const std::size_t part_count = r.count(4 + 8 + 36 + 2, "parts");
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
        MeshPart p;
        p.shape = make_shape(std::move(triangles), model, material, normals, uvs);
        p.material = id;
        part_materials.push_back(id);
        mesh.parts.push_back(std::move(p));
    }
    const std::size_t material_count = r.count(8 + 4 + 12 + 12 + 4 + 1 + 8 + 16 + 20, "materials");
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
        if (alpha_mode > 2u || !(m.alpha >= 0.0f && m.alpha <= 1.0f) ||
            !(m.alpha_cutoff >= 0.0f && m.alpha_cutoff <= 1.0f) || m.alpha_texture < -1 ||
            (m.alpha_channel != 0 && m.alpha_channel != 3)) {
            throw WireError("material " + std::to_string(i) + " with a bad alpha");
        }
        m.alpha_mode = static_cast<AlphaMode>(alpha_mode);
        if (!(std::min({m.color.x, m.color.y, m.color.z}) >= 0.0f) || !(std::max({m.color.x, m.color.y, m.color.z}) <= 1.0f) ||
            !(m.metallic >= 0.0f && m.metallic <= 1.0f) ||
            !(m.specular >= 0.0f && m.specular <= 1.0f) ||
            !(m.emittance >= 0.0f && m.emittance <= max_emitted_radiance) ||
            !(m.roughness >= 0.0f && m.roughness <= 1.0f) ||
            !(m.ior > 0.0f && std::isfinite(m.ior))) {
            throw WireError("material " + std::to_string(i) + " with a value out of range");
        }
        if (!std::isfinite(m.normal_scale) || m.roughness_texture < -1 ||
            m.metallic_texture < -1 || m.normal_texture < -1) {
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
    const std::size_t texture_count = r.count(8 + 4 + 4 + 8, "textures");
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
        for (int texture : {m.texture, m.roughness_texture, m.metallic_texture, m.normal_texture,
                            m.alpha_texture}) {
            if (texture >= static_cast<int>(mesh.textures.size())) {
                throw WireError("a material of texture " + std::to_string(texture) + " of " +
                                std::to_string(mesh.textures.size()));
            }
        }
    }
    if (r.get<std::uint32_t>() != wire_end || !r.done()) {
        throw WireError("it does not end as one");
    }
    return mesh;
}

double mesh_import_seconds = 300.0;

// A PLY or glTF 2.0 file through assimp (its PLY or glTF 2.0 reader only,
// by the extension), in a child process of its own (isolated_call.h):
// assimp 5.2's readers crash on some malformed files (a heap overrun in
// the PLY reader, a null dereference in the glTF one: tests/fuzz/fuzz_mesh
// found them), and such a crash, a hang or a corrupted result is one clear
// error here, never the program's. Its meshes with their node transforms
// applied, polygons as fans of triangles, points and lines left out.
MeshParts load_assimp(const std::string& path, const glm::vec3& position,
                      const glm::vec3& orientation, const glm::vec3& scale, int material,
                      bool smooth, bool file_materials, std::uint64_t texel_budget) {
    // Only a regular file within the size limit (input_file.h). A .gltf
    // may refer to other files (its buffers), which assimp opens beside
    // it; the others are read from memory.
    const std::string text = read_input_file(path, "mesh");
    if (text.empty()) {
        throw std::runtime_error(path + ": cannot read mesh: the file is empty");
    }
    const bool ply = has_extension(path, ".ply");
    // assimp 5.2's PLY reader, given a header without its end_header
    // line, or with one that does not end the line ("end_header0"),
    // allocates or loops without end (found by tests/fuzz/fuzz_mesh):
    // such a file is refused before it sees it (the time limit below
    // would stop it, later).
    if (ply && !has_ply_header_end(text)) {
        throw std::runtime_error(path +
                                 ": cannot read mesh: the PLY header has no end_header "
                                 "line (a line of its own)");
    }
    const std::string reader = assimp_reader_name(ply);
    const IsolatedOutcome outcome = run_isolated(
        [&] { return import_assimp(path, text, ply, smooth, file_materials, texel_budget); },
        mesh_import_seconds);
    using Kind = IsolatedOutcome::Kind;
    switch (outcome.kind) {
    case Kind::result:
        break;
    case Kind::error:
        throw std::runtime_error(outcome.payload);
    case Kind::out_of_memory:
        throw std::runtime_error(path + ": " + reader + " ran out of memory on this file");
    case Kind::exception:
        throw std::runtime_error(path + ": " + reader + " failed on this file (" +
                                 printable(outcome.detail, 200) + "): it is malformed");
    case Kind::crashed:
        throw std::runtime_error(path + ": " + reader + " crashed on this file (" +
                                 outcome.detail + "): it is malformed");
    case Kind::exited:
        // A sanitizer's report in the child ends it so (exit status 1).
        throw std::runtime_error(path + ": " + reader + " failed on this file (its process " +
                                 "ended with " + outcome.detail + "): it is malformed");
    case Kind::timed_out: {
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%g", mesh_import_seconds);
        throw std::runtime_error(path + ": " + reader + " did not finish within " + seconds +
                                 " s and was stopped: the file is malformed or too large");
    }
    case Kind::broken:
        throw std::runtime_error(path + ": " + reader + " sent back a broken result (" +
                                 outcome.detail + "): the file is malformed");
    case Kind::not_started:
        throw std::runtime_error(path + ": cannot read mesh: cannot start its import (" +
                                 outcome.detail + ")");
    }
    try {
        return mesh_from_wire(outcome.payload, model_matrix(position, orientation, scale),
                              material);
    } catch (const WireError& e) {
        throw std::runtime_error(path + ": " + reader + " sent back a broken result (" +
                                 e.what() + "): the file is malformed");
    }
}

}  // namespace

void set_mesh_import_time_limit(double seconds) {
    if (!(seconds > 0.0 && seconds <= 1e6)) {
        throw std::invalid_argument("set_mesh_import_time_limit: expected seconds in (0, 1e6]");
    }
    mesh_import_seconds = seconds;
}

double mesh_import_time_limit() { return mesh_import_seconds; }

MeshParts load_mesh_parts(const std::string& path, const glm::vec3& position,
                          const glm::vec3& orientation, const glm::vec3& scale, int material,
                          bool smooth, bool file_materials, std::uint64_t texel_budget) {
    if (has_extension(path, ".ply") || has_extension(path, ".gltf") ||
        has_extension(path, ".glb")) {
        return load_assimp(path, position, orientation, scale, material, smooth, file_materials,
                           texel_budget);
    }
    return load_obj(path, position, orientation, scale, material, smooth, file_materials,
                    texel_budget);
}

Shape load_obj_mesh(const std::string& path, const glm::vec3& position,
                    const glm::vec3& orientation, const glm::vec3& scale, int material,
                    bool smooth) {
    return load_obj(path, position, orientation, scale, material, smooth, false, max_scene_texels)
        .parts[0]
        .shape;
}

}  // namespace trac0r
