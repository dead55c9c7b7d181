// A glTF's node hierarchy as its JSON gives it, for what trac0r reads of
// a glTF itself (gltf_view.h, gltf_size.h): the default scene's nodes with
// their transforms.
#ifndef TRAC0R_GLTF_NODES_H
#define TRAC0R_GLTF_NODES_H

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace trac0r {

// The n numbers of `value`, each finite; throws std::runtime_error "what:
// expected ..." otherwise.
std::vector<double> gltf_numbers(const nlohmann::json& value, std::size_t n,
                                 const std::string& what);

// Calls visit(index, node, world) for each node of the default scene (or
// scene 0; every node where the file has no scenes), depth first from its
// roots, with the node's transform to the file's coordinates (its
// parents' and its own: matrix, or translation x rotation x scale). A
// node met again (a cycle, or shared) and one nested deeper than 256 are
// left out, as the mesh reader leaves them. Throws std::runtime_error
// naming `path` and the node for a transform that is not finite numbers.
void walk_gltf_nodes(
    const nlohmann::json& doc, const std::string& path,
    const std::function<void(std::size_t, const nlohmann::json&, const glm::dmat4&)>& visit);

}  // namespace trac0r

#endif
