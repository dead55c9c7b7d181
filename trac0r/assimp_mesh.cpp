#include "trac0r/assimp_mesh.h"

#include "trac0r/file_materials.h"
#include "trac0r/gltf_json.h"
#include "trac0r/gltf_nodes.h"
#include "trac0r/gltf_repeats.h"
#include "trac0r/gltf_size.h"
#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/isolated_call.h"
#include "trac0r/mesh_parts.h"
#include "trac0r/mesh_wire.h"
#include "trac0r/model_defects.h"
#include "trac0r/ply_header.h"

#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/importerdesc.h>
#include <assimp/scene.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <new>
#include <set>
#include <stdexcept>
#include <utility>

namespace trac0r {

namespace {

// A texture's wrap mode as assimp gives it (aiTextureMapMode; glTF's
// sampler wrapS and wrapT), repeat where the file has none.
TextureWrap texture_wrap(const aiMaterial& m, const char* key, unsigned type, unsigned index) {
    int mode = aiTextureMapMode_Wrap;
    if (m.Get(key, type, index, mode) != AI_SUCCESS) {
        return TextureWrap::repeat;
    }
    switch (mode) {
    case aiTextureMapMode_Clamp:
        return TextureWrap::clamp;
    case aiTextureMapMode_Mirror:
        return TextureWrap::mirror;
    default:
        return TextureWrap::repeat;
    }
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
    aiTextureType found_type = aiTextureType_NONE;
    for (aiTextureType type : types) {
        if (!found && m.GetTexture(type, 0, &name) == AI_SUCCESS) {
            found = true;
            found_type = type;
        }
    }
    if (!found) {
        return -1;
    }
    // The sampler's wrap modes (glTF's wrapS, wrapT; REPEAT where none).
    const TextureWrap wrap_u = texture_wrap(m, AI_MATKEY_MAPPINGMODE_U(found_type, 0));
    const TextureWrap wrap_v = texture_wrap(m, AI_MATKEY_MAPPINGMODE_V(found_type, 0));
    aiString material_name;
    m.Get(AI_MATKEY_NAME, material_name);
    const std::string file = name.C_Str();
    const std::string where = path + ": material '" + printable(material_name.C_Str(), 60) +
                              "': " + what + " texture '" + printable(file, 200) + "'";
    const aiTexture* embedded = scene.GetEmbeddedTexture(name.C_Str());
    if (embedded != nullptr) {
        const auto decode = [&] {
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
        };
        return texture_index(mesh, path + " " + file, decode, wrap_u, wrap_v);
    }
    if (!file.empty() && file[0] == '*') {
        throw std::runtime_error(where + ": the file has no embedded image of that number");
    }
    const std::string texture = texture_path_beside(path, file);
    return texture_index(
        mesh, texture, [&] { return load_texture_file(where, texture, room); }, wrap_u, wrap_v);
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

// "the PLY reader (assimp)", for messages.
std::string assimp_reader_name(bool ply) {
    return ply ? "the PLY reader (assimp)" : "the glTF reader (assimp)";
}

// An assimp file system that reads `path` from memory (the file as the
// reader is to see it) and every other file (buffers, images beside it)
// from disk, so that relative URIs still resolve beside `path`.
class OneFileInMemory : public Assimp::DefaultIOSystem {
  public:
    OneFileInMemory(std::string path, std::string bytes)
        : path_(std::move(path)), bytes_(std::move(bytes)) {}
    bool Exists(const char* file) const override {
        return path_ == file || DefaultIOSystem::Exists(file);
    }
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        if (path_ == file) {
            return new Assimp::MemoryIOStream(reinterpret_cast<const std::uint8_t*>(bytes_.data()),
                                              bytes_.size());
        }
        return DefaultIOSystem::Open(file, mode);
    }

  private:
    std::string path_;
    std::string bytes_;  // owned by the importer with this, as the streams it reads
};

// Nodes placing one mesh with the same transform (gltf_repeats.h) that
// were not left out of the file (they have children): each mesh drawn
// once at each place, and each node that repeated one counted once (it
// has an instance for each of its mesh's primitives). `owners`: each
// instance's node.
void skip_repeated_instances(std::vector<std::pair<unsigned, aiMatrix4x4>>* instances,
                             const std::vector<const aiNode*>& owners, const std::string& path,
                             ModelDefects* defects) {
    static_assert(sizeof(aiMatrix4x4) == sizeof(std::array<float, 16>),
                  "assimp's matrices compared as 16 floats");
    std::set<std::pair<unsigned, std::array<float, 16>>> seen;
    std::set<const aiNode*> repeating;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < instances->size(); ++i) {
        const std::pair<unsigned, aiMatrix4x4> instance = (*instances)[i];
        std::array<float, 16> m;
        std::memcpy(m.data(), &instance.second, sizeof m);
        if (!seen.emplace(instance.first, m).second) {
            if (repeating.insert(owners[i]).second) {
                defects->report(path, 0, gltf_repeat_defect, gltf_repeat_done);
            }
            continue;
        }
        (*instances)[kept++] = instance;
    }
    instances->resize(kept);
}

// The import itself, in the child process: assimp's reader of the format
// alone, our conversion of its scene into plain parts, materials and
// textures; everything that touches assimp's structures is here. Throws
// std::runtime_error naming the file for what assimp or our checks refuse.
std::string import_assimp(const std::string& path, const std::string& text, bool ply, bool smooth,
                          bool file_materials, std::uint64_t texel_budget, bool strict) {
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
    // The file as assimp is to see it: without the nodes that repeat
    // another's mesh and transform, where it has any.
    ModelDefects defects(strict);
    std::size_t repeated = 0;
    std::string first_repeat;
    const std::string pruned =
        ply ? "" : gltf_without_repeated_leaves(text, !gltf, path, &repeated, &first_repeat);
    if (repeated > 0) {
        if (strict) {
            throw std::runtime_error(path + ": " + first_repeat);  // the node, to find it by
        }
        defects.report(path, 0, gltf_repeat_defect, gltf_repeat_done, static_cast<long>(repeated));
        if (gltf) {
            importer.SetIOHandler(new OneFileInMemory(path, pruned));
        }
    }
    const std::string& bytes = pruned.empty() ? text : pruned;
    const aiScene* scene =
        gltf ? importer.ReadFile(path, flags)
             : importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags,
                                           has_extension(path, ".glb") ? "glb" : "ply");
    if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
        std::string reason = importer.GetErrorString();
        reason.erase(reason.find_last_not_of(" \n\r") + 1);
        if (reason == "std::bad_alloc") {
            throw std::bad_alloc();  // assimp's words for the memory limit's
        }
        throw std::runtime_error(path + ": cannot read mesh: " +
                                 (reason.empty() ? std::string("no scene in it") : reason));
    }
    // Each node's meshes, with the node's transform (and its parents'):
    // (mesh index, transform) in the order of a depth-first walk.
    std::vector<std::pair<unsigned, aiMatrix4x4>> instances;
    std::vector<const aiNode*> owners;  // each instance's node
    // The parent refused deeper glTF nodes (gltf_nodes.h); one level more
    // for the root assimp adds above a scene of several.
    const int max_node_depth = max_gltf_node_depth + 1;
    const std::function<void(const aiNode&, const aiMatrix4x4&, int)> walk =
        [&](const aiNode& node, const aiMatrix4x4& parent, int depth) {
            if (depth > max_node_depth) {
                throw std::runtime_error(path + ": cannot read mesh: its nodes nest deeper than " +
                                         std::to_string(max_gltf_node_depth));
            }
            const aiMatrix4x4 transform = parent * node.mTransformation;
            for (unsigned k = 0; k < node.mNumMeshes; ++k) {
                if (node.mMeshes[k] < scene->mNumMeshes) {
                    instances.emplace_back(node.mMeshes[k], transform);
                    owners.push_back(&node);
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
    skip_repeated_instances(&instances, owners, path, &defects);
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
                // glTF's TANGENT (assimp gives its xyz, and its w as the
                // bitangent cross(normal, xyz) w).
                VertexTangentTriple tangent{};
                bool has_tangents = has_normals && mesh.HasTangentsAndBitangents();
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
                    if (has_tangents) {
                        const aiVector3D& t = mesh.mTangents[index];
                        const aiVector3D& vn = mesh.mNormals[index];
                        const aiVector3D& b = mesh.mBitangents[index];
                        const float handedness = glm::dot(
                            glm::cross(glm::vec3(vn.x, vn.y, vn.z), glm::vec3(t.x, t.y, t.z)),
                            glm::vec3(b.x, b.y, b.z));
                        const aiVector3D moved = aiMatrix3x3(to_world) * t;
                        const float w = handedness < 0.0f ? -1.0f : 1.0f;
                        tangent[k] = glm::vec4(moved.x, moved.y, moved.z, mirrored ? -w : w);
                        has_tangents = is_finite(glm::vec3(tangent[k])) &&
                                       glm::length(glm::vec3(tangent[k])) > 0.0f;
                    }
                }
                // A PLY has no materials (assimp gives it a default one).
                parts.add(file_materials && !ply ? static_cast<int>(mesh.mMaterialIndex) : -1, p, n,
                          has_normals, smooth, uv, has_tangents ? &tangent : nullptr);
            }
        }
    }
    if (parts.triangles.empty()) {
        throw std::runtime_error(path + ": mesh has no triangles");
    }
    // The file's materials (and their textures) as the parts use them.
    MeshParts files;
    const std::vector<GltfMaterialExtras> json_extras =
        ply ? std::vector<GltfMaterialExtras>()
            : gltf_material_extras(gltf_json_text(text, !gltf), path);
    // The extras by assimp's material index: assimp 5.2 orders a glTF's
    // materials its own way (ClearCoatTest's and TextureTransformTest's
    // differ from the file's), so each is found by its name, the first
    // of that name not yet taken; by its index where no name matches.
    std::vector<GltfMaterialExtras> extras(scene->mNumMaterials);
    std::vector<bool> taken(json_extras.size(), false);
    for (unsigned i = 0; i < scene->mNumMaterials && !json_extras.empty(); ++i) {
        aiString name;
        scene->mMaterials[i]->Get(AI_MATKEY_NAME, name);
        std::size_t found = json_extras.size();
        for (std::size_t j = 0; j < json_extras.size() && found == json_extras.size(); ++j) {
            if (!taken[j] && !json_extras[j].name.empty() && json_extras[j].name == name.C_Str()) {
                found = j;
            }
        }
        if (found == json_extras.size() && i < json_extras.size() && !taken[i]) {
            found = i;
        }
        if (found < json_extras.size()) {
            taken[found] = true;
            extras[i] = json_extras[found];
        }
    }
    // A texture as assimp_texture reads it; one that is not there or does
    // not decode is a defect (-1: the material's factor alone).
    const auto texture_of = [&](const aiMaterial& m, std::initializer_list<aiTextureType> types,
                                const char* what) {
        try {
            return assimp_texture(*scene, m, path, files, texel_budget, types, what);
        } catch (const TextureUnreadable& e) {
            if (strict) {
                throw;
            }
            defects.report_message(path, e.what(), "its factor is used alone");
            return -1;
        }
    };
    const auto material_of = [&](int id) {
        if (id < 0 || static_cast<unsigned>(id) >= scene->mNumMaterials) {
            return -1;
        }
        const aiMaterial& m = *scene->mMaterials[id];
        if (is_default_material(m)) {
            return -1;
        }
        Material out = material_from_assimp(
            m, path,
            static_cast<std::size_t>(id) < extras.size() ? extras[id].emissive_strength : 1.0f);
        if (out.type == MaterialType::principled && out.emission != glm::vec3(0.0f)) {
            out.emission_texture = texture_of(m, {aiTextureType_EMISSIVE}, "emissive");
        }
        if (out.type == MaterialType::emissive) {
            out.texture = texture_of(m, {aiTextureType_EMISSIVE}, "emissive");
        } else if (takes_texture(out.type)) {
            out.texture =
                texture_of(m, {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}, "base colour");
        }
        if (is_microfacet(out.type)) {
            // glTF's metallicRoughnessTexture: roughness in green, metallic
            // in blue, one image for both.
            out.roughness_texture = texture_of(
                m,
                {aiTextureType_UNKNOWN, aiTextureType_DIFFUSE_ROUGHNESS, aiTextureType_METALNESS},
                "metallic-roughness");
            out.metallic_texture = out.roughness_texture;
        }
        if (out.alpha_mode != AlphaMode::opaque) {
            out.alpha_texture = out.texture;  // the base colour's alpha
        }
        if (out.type != MaterialType::emissive) {
            out.normal_texture = texture_of(m, {aiTextureType_NORMALS}, "normal");
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
    std::vector<int> part_materials;
    for (std::size_t part = 0; part < parts.key.size(); ++part) {
        const int key = parts.key[part];
        part_materials.push_back(material_of(key));
        // KHR_texture_transform, applied to the part's coordinates (in
        // glTF's, v down from the image's top; assimp gives v up).
        if (key >= 0 && static_cast<std::size_t>(key) < extras.size() &&
            extras[static_cast<std::size_t>(key)].uv_transform) {
            const std::vector<double>& m = extras[static_cast<std::size_t>(key)].uv_matrix;
            for (TriangleUv& t : parts.uvs[part]) {
                for (glm::vec2& uv : t.uv) {
                    const double u = uv.x;
                    const double v = 1.0 - static_cast<double>(uv.y);
                    uv = glm::vec2(static_cast<float>(m[0] * u + m[1] * v + m[2]),
                                   static_cast<float>(1.0 - (m[3] * u + m[4] * v + m[5])));
                }
            }
        }
    }
    files.warnings = defects.lines();
    return mesh_to_wire(parts, part_materials, files);
}

double mesh_import_seconds = 300.0;

// How much more memory than trac0r's own the reader's child may take:
// half the machine's, so that a file that drives it to allocate without
// end stops there.
std::uint64_t mesh_import_memory() { return half_machine_memory(); }

}  // namespace

MeshParts load_assimp(const std::string& path, const glm::vec3& position,
                      const glm::vec3& orientation, const glm::vec3& scale, int material,
                      bool smooth, bool file_materials, std::uint64_t texel_budget, bool strict) {
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
    // allocates or loops without end (found by tests/fuzz/fuzz_mesh), and
    // it trusts the header's counts (10^9 vertices in a 343-byte file took
    // it past 18 GB): such a file is refused before it sees it.
    if (ply) {
        check_ply_header(path, text);
    } else {
        // A glTF that promises more triangles than the machine can hold
        // is refused before its reader allocates them.
        const std::uint64_t triangles =
            gltf_promised_triangles(gltf_json_text(text, has_extension(path, ".glb")), path);
        const std::uint64_t memory = 2 * mesh_import_memory();
        if (memory > 0 && triangles > memory / bytes_per_loaded_triangle) {
            throw std::runtime_error(
                path + ": cannot read mesh: it promises " + std::to_string(triangles) +
                " triangles, which would take about " +
                std::to_string(triangles * bytes_per_loaded_triangle >> 30) +
                " GB, more than this " + "machine's " + std::to_string(memory >> 30) + " GB");
        }
    }
    const std::string reader = assimp_reader_name(ply);
    const IsolatedOutcome outcome = run_isolated(
        [&] {
            return import_assimp(path, text, ply, smooth, file_materials, texel_budget, strict);
        },
        mesh_import_seconds, mesh_import_memory());
    using Kind = IsolatedOutcome::Kind;
    switch (outcome.kind) {
    case Kind::result:
        break;
    case Kind::error:
        throw std::runtime_error(outcome.payload);
    case Kind::out_of_memory:
        throw std::runtime_error(path + ": " + reader + " ran out of memory on this file (it " +
                                 "may take " + std::to_string(mesh_import_memory() >> 20) +
                                 " MB, half the machine's): it is malformed or too large");
    case Kind::exception:
        throw std::runtime_error(path + ": " + reader + " failed on this file (" +
                                 printable(outcome.detail, 200) + "): it is malformed");
    case Kind::crashed:
        throw std::runtime_error(path + ": " + reader + " crashed on this file (" + outcome.detail +
                                 "): it is malformed");
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
        throw std::runtime_error(path + ": " + reader + " sent back a broken result (" + e.what() +
                                 "): the file is malformed");
    }
}

void set_mesh_import_time_limit(double seconds) {
    if (!(seconds > 0.0 && seconds <= 1e6)) {
        throw std::invalid_argument("set_mesh_import_time_limit: expected seconds in (0, 1e6]");
    }
    mesh_import_seconds = seconds;
}

double mesh_import_time_limit() { return mesh_import_seconds; }

}  // namespace trac0r
