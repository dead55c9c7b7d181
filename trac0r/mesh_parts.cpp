#include "trac0r/mesh_parts.h"

#include "trac0r/assimp_mesh.h"
#include "trac0r/input_checks.h"
#include "trac0r/obj_mesh.h"

namespace trac0r {

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

MeshParts load_mesh_parts(const std::string& path, const glm::vec3& position,
                          const glm::vec3& orientation, const glm::vec3& scale, int material,
                          bool smooth, bool file_materials, std::uint64_t texel_budget,
                          ModelDefects* defects) {
    if (has_extension(path, ".ply") || has_extension(path, ".gltf") ||
        has_extension(path, ".glb")) {
        MeshParts mesh =
            load_assimp(path, position, orientation, scale, material, smooth, file_materials,
                        texel_budget, defects == nullptr || defects->strict());
        if (defects != nullptr) {
            defects->add_lines(mesh.warnings);
        }
        return mesh;
    }
    return load_obj(path, position, orientation, scale, material, smooth, file_materials,
                    texel_budget, defects);
}

}  // namespace trac0r
