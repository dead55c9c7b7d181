// What the mesh readers share: faces grouped into parts by their
// material, and the textures their materials name, each loaded once.
#ifndef TRAC0R_MESH_PARTS_H
#define TRAC0R_MESH_PARTS_H

#include "trac0r/shape.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace trac0r {

// The index in mesh.textures of the texture from `source` with the wrap
// modes wrap_u and wrap_v, made by load() (and given those modes) the
// first time a material of the file uses the image so: the same image
// under another sampler is another texture.
template <typename Load>
int texture_index(MeshParts& mesh, const std::string& source, Load load,
                  TextureWrap wrap_u = TextureWrap::repeat,
                  TextureWrap wrap_v = TextureWrap::repeat) {
    for (std::size_t i = 0; i < mesh.textures.size(); ++i) {
        const Texture& t = mesh.textures[i];
        if (t.source == source && t.wrap_u == wrap_u && t.wrap_v == wrap_v) {
            return static_cast<int>(i);
        }
    }
    mesh.textures.push_back(load());
    mesh.textures.back().wrap_u = wrap_u;
    mesh.textures.back().wrap_v = wrap_v;
    return static_cast<int>(mesh.textures.size()) - 1;
}

// A texture's file name as a material file gives it, relative to that
// file's directory (a Windows exporter's '\\' read as '/').
std::string texture_path_beside(const std::string& mtl_file, std::string name);

// Faces grouped into parts by a material key (first use first), with
// their normals, texture coordinates and tangents; what load_obj and
// load_assimp fill.
struct PartBuilder {
    std::vector<int> key;
    std::vector<std::vector<Triangle>> triangles;
    std::vector<std::vector<VertexNormalTriple>> normals;
    std::vector<std::vector<TriangleUv>> uvs;
    std::vector<std::vector<VertexTangentTriple>> tangents;  // the file's
    std::vector<bool> any_smooth;
    std::vector<bool> any_uv;
    std::vector<bool> any_tangent;

    // `tangent`: the file's at the face's corners, or nullptr for none.
    void add(int material_key, const glm::vec3 p[3], VertexNormalTriple n, bool has_normals,
             bool smooth, const TriangleUv& uv, const VertexTangentTriple* tangent = nullptr) {
        std::size_t part =
            static_cast<std::size_t>(std::find(key.begin(), key.end(), material_key) - key.begin());
        if (part == key.size()) {
            key.push_back(material_key);
            triangles.emplace_back();
            normals.emplace_back();
            uvs.emplace_back();
            tangents.emplace_back();
            any_smooth.push_back(false);
            any_uv.push_back(false);
            any_tangent.push_back(false);
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
        any_tangent[part] = any_tangent[part] || tangent != nullptr;
        tangents[part].push_back(tangent != nullptr ? *tangent : VertexTangentTriple{});
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
            if (!any_tangent[part]) {
                tangents[part].clear();
            }
            MeshPart p;
            p.shape = make_shape(triangles[part], model, material, normals[part], uvs[part],
                                 tangents[part]);
            p.material = material_of(key[part], mesh);
            mesh.parts.push_back(std::move(p));
        }
        return mesh;
    }
};

}  // namespace trac0r

#endif
