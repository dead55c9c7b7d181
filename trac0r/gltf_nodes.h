// A glTF's node hierarchy as its JSON gives it, for what trac0r reads of
// a glTF itself (gltf_view.h, gltf_size.h): the default scene's nodes with
// their transforms.
#ifndef TRAC0R_GLTF_NODES_H
#define TRAC0R_GLTF_NODES_H

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r {

// The n numbers of `value`, each finite; throws std::runtime_error "what:
// expected ..." otherwise.
std::vector<double> gltf_numbers(const nlohmann::json& value, std::size_t n,
                                 const std::string& what);

// How deep nodes may nest: deeper, assimp's recursive import overflows its
// stack (a chain of 2 x 10^4 nodes crashed its process), so such a file
// is refused before the reader sees it.
const int max_gltf_node_depth = 256;

// A file whose nodes nest deeper than max_gltf_node_depth.
struct GltfNodesTooDeep : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Calls visit(index, node, world) for each node of the default scene (or
// scene 0; every node where the file has no scenes), depth first from its
// roots, with the node's transform to the file's coordinates (its
// parents' and its own: matrix, or translation x rotation x scale). A
// node met again (a cycle, or shared) is left out, as the mesh reader
// leaves it. Throws GltfNodesTooDeep ("PATH: cannot read mesh: its nodes
// nest deeper than 256") for a node nested deeper than that, and
// std::runtime_error naming `path` and the node for a transform that is
// not finite numbers.
void walk_gltf_nodes(
    const nlohmann::json& doc, const std::string& path,
    const std::function<void(std::size_t, const nlohmann::json&, const glm::dmat4&)>& visit);

// Calls visit(index, node, mesh, repeats) for each node of the walk
// (walk_gltf_nodes) that places a mesh: `repeats` is the earlier node that
// placed the same mesh with the same world transform (a coincident copy,
// which the reader draws once: gltf_repeats.h), or -1 where none did.
// Throws as walk_gltf_nodes does.
void walk_gltf_mesh_placements(
    const nlohmann::json& doc, const std::string& path,
    const std::function<void(std::size_t, const nlohmann::json&, std::size_t, long)>& visit);

}  // namespace trac0r

#endif
