#include "trac0r/shape.h"

#include "trac0r/obj_checker.h"

#include <tiny_obj_loader.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
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
                 const std::vector<VertexNormalTriple>& local_normals) {
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

}  // namespace

namespace {

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
        const std::string file = !name.empty() && name[0] == '/' ? name : dir_ + name;
        std::string text;
        try {
            text = checked_mtl_text(file);
        } catch (const std::runtime_error& e) {
            // Named by the OBJ's mtllib line as well.
            long line = 0;
            for (const ObjNameRef& r : libraries_) {
                if (r.name == name) {
                    line = r.line;
                    break;
                }
            }
            throw std::runtime_error(obj_path_ + ":" + std::to_string(line) + ": mtllib '" + name +
                                     "': " + e.what());
        }
        TextBuffer buffer(text);
        std::istream stream(&buffer);
        tinyobj::LoadMtl(map, materials, &stream, warn, err);
        files.resize(materials->size(), file);
        return true;
    }
    std::vector<std::string> files;  // per material: its file

  private:
    std::string obj_path_;
    std::string dir_;
    const std::vector<ObjNameRef>& libraries_;
};

MtlMaterial mtl_material(const tinyobj::material_t& m, const std::string& file) {
    MtlMaterial out;
    out.name = m.name;
    out.file = file;
    out.diffuse = glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    out.specular = glm::vec3(m.specular[0], m.specular[1], m.specular[2]);
    out.emission = glm::vec3(m.emission[0], m.emission[1], m.emission[2]);
    out.transmission = glm::vec3(m.transmittance[0], m.transmittance[1], m.transmittance[2]);
    out.shininess = m.shininess;
    out.ior = m.ior;
    out.dissolve = m.dissolve;
    out.illum = m.illum;
    return out;
}

ObjMesh load_obj(const std::string& path, const glm::vec3& position, const glm::vec3& orientation,
                 const glm::vec3& scale, int material, bool smooth, bool read_mtl) {
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
    // Per part (by material id, -1 first seen where it is): its triangles
    // and normals.
    std::vector<int> part_material;
    std::vector<std::vector<Triangle>> local;
    std::vector<std::vector<VertexNormalTriple>> normals;
    std::vector<bool> any_smooth;
    for (const tinyobj::shape_t& s : shapes) {
        for (std::size_t i = 0; i + 2 < s.mesh.indices.size(); i += 3) {
            glm::vec3 p[3];
            VertexNormalTriple n = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
            bool has_normals = true;
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& ref = s.mesh.indices[i + k];
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
            std::size_t part = static_cast<std::size_t>(
                std::find(part_material.begin(), part_material.end(), id) - part_material.begin());
            if (part == part_material.size()) {
                part_material.push_back(id);
                local.emplace_back();
                normals.emplace_back();
                any_smooth.push_back(false);
            }
            local[part].emplace_back(p[0], p[1], p[2]);
            if (!has_normals || !smooth) {
                n = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
            }
            any_smooth[part] = any_smooth[part] || (has_normals && smooth);
            normals[part].push_back(n);
        }
    }
    if (local.empty()) {
        throw std::runtime_error(path + ": OBJ mesh has no triangles");
    }
    ObjMesh mesh;
    const glm::mat4 model = model_matrix(position, orientation, scale);
    for (std::size_t part = 0; part < local.size(); ++part) {
        if (!any_smooth[part]) {
            normals[part].clear();
        }
        ObjPart p;
        p.shape = make_shape(local[part], model, material, normals[part]);
        const int id = part_material[part];
        if (id >= 0) {
            p.mtl = static_cast<int>(mesh.materials.size());
            mesh.materials.push_back(mtl_material(materials[static_cast<std::size_t>(id)],
                                                  static_cast<std::size_t>(id) < reader.files.size()
                                                      ? reader.files[static_cast<std::size_t>(id)]
                                                      : ""));
        }
        mesh.parts.push_back(std::move(p));
    }
    return mesh;
}

}  // namespace

ObjMesh load_obj_parts(const std::string& path, const glm::vec3& position,
                       const glm::vec3& orientation, const glm::vec3& scale, int material,
                       bool smooth) {
    return load_obj(path, position, orientation, scale, material, smooth, true);
}

Shape load_obj_mesh(const std::string& path, const glm::vec3& position,
                    const glm::vec3& orientation, const glm::vec3& scale, int material,
                    bool smooth) {
    return load_obj(path, position, orientation, scale, material, smooth, false).parts[0].shape;
}

}  // namespace trac0r
