#include "trac0r/obj_mesh.h"

#include "trac0r/file_materials.h"
#include "trac0r/input_checks.h"
#include "trac0r/isolated_texture.h"
#include "trac0r/mesh_parts.h"
#include "trac0r/mtl_checker.h"
#include "trac0r/obj_checker.h"
#include "trac0r/smoothing_groups.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <fstream>
#include <istream>
#include <map>
#include <stdexcept>
#include <streambuf>

namespace trac0r {

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
    CheckedMtlReader(const std::string& obj_path, const std::vector<ObjNameRef>& libraries,
                     ModelDefects* defects)
        : obj_path_(obj_path), libraries_(libraries), defects_(defects) {
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
        if (defects_ != nullptr && !defects_->strict() && !std::ifstream(file)) {
            defects_->report(
                obj_path_, line,
                "mtllib '" + printable(name, 200) + "': cannot open " + printable(file, 200),
                "its materials are left out");
            return;
        }
        std::string text;
        try {
            text = checked_mtl_text(file, defects_);
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
    ModelDefects* defects_;
};

}  // namespace

MeshParts load_obj(const std::string& path, const glm::vec3& position, const glm::vec3& orientation,
                   const glm::vec3& scale, int material, bool smooth, bool read_mtl,
                   std::uint64_t texel_budget, ModelDefects* defects) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn;
    std::string err;
    CheckedObj checked = check_obj(path, defects);
    TextBuffer buffer(checked.text);
    std::istream text(&buffer);
    CheckedMtlReader reader(path, checked.libraries, defects);
    // Triangulate polygons; the materials from the mtllib files, where
    // asked for.
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &text,
                          read_mtl ? &reader : nullptr, true)) {
        throw std::runtime_error(path + ": cannot read OBJ mesh" + (err.empty() ? "" : ": " + err));
    }
    for (tinyobj::material_t& m : materials) {
        m.name = decode_material_name(m.name);
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
                const std::string what = "usemtl '" + used.name +
                                         "': no material of that name in its mtllib files (" +
                                         files + ")";
                if (defects == nullptr) {
                    throw std::runtime_error(path + ":" + std::to_string(used.line) + ": " + what);
                }
                defects->report(path, used.line, what, "its faces take the shape's material");
            }
        }
    }
    const std::size_t vertex_count = attrib.vertices.size() / 3;
    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;
    // The faces, before they join their parts: those without normals (vn)
    // in a smoothing group get theirs from it.
    struct Face {
        glm::vec3 p[3];
        VertexNormalTriple n;
        bool has_normals;
        TriangleUv uv;
        int id;
    };
    std::vector<Face> faces;
    std::vector<GroupedTriangle> grouped;
    bool any_group = false;
    for (const tinyobj::shape_t& s : shapes) {
        for (std::size_t i = 0; i + 2 < s.mesh.indices.size(); i += 3) {
            GroupedTriangle corners;
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
                corners.vertex[k] = static_cast<std::uint32_t>(index);
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
            if (!has_normals && face < s.mesh.smoothing_group_ids.size()) {
                corners.group = s.mesh.smoothing_group_ids[face];
                any_group = any_group || corners.group != 0;
            }
            faces.push_back({{p[0], p[1], p[2]}, n, has_normals, uv, id});
            grouped.push_back(corners);
        }
    }
    std::vector<VertexNormalTriple> group_normals;
    if (smooth && any_group) {
        std::vector<glm::vec3> positions(vertex_count);
        for (std::size_t v = 0; v < vertex_count; ++v) {
            positions[v] = glm::vec3(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                     attrib.vertices[3 * v + 2]);
        }
        group_normals = smoothing_group_normals(positions, grouped);
    }
    PartBuilder parts;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        Face& face = faces[f];
        if (!group_normals.empty() && glm::length(group_normals[f][0]) > 0.0f) {
            face.n = group_normals[f];
            face.has_normals = true;
        }
        parts.add(face.id, face.p, face.n, face.has_normals, smooth, face.uv);
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
                try {
                    return texture_index(mesh, texture, [&] {
                        return load_texture_file_isolated(
                            file + ": material '" + printable(m.name, 60) + "': " + key + " '" +
                                printable(map, 200) + "'",
                            texture, texel_budget - texel_count(mesh.textures));
                    });
                } catch (const TextureUnreadable& e) {
                    if (defects == nullptr || defects->strict()) {
                        throw;
                    }
                    defects->report_message(file, e.what(), "its factor is used alone");
                    return -1;
                }
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
                m.normal_texture = mtl.normal_texname.empty() ? load(mtl.bump_texname, "map_Bump")
                                                              : load(mtl.normal_texname, "norm");
            }
            mesh.materials.push_back(m);
            return static_cast<int>(mesh.materials.size()) - 1;
        });
}

Shape load_obj_mesh(const std::string& path, const glm::vec3& position,
                    const glm::vec3& orientation, const glm::vec3& scale, int material,
                    bool smooth) {
    return load_obj(path, position, orientation, scale, material, smooth, false, max_scene_texels)
        .parts[0]
        .shape;
}

}  // namespace trac0r
