// glTF nodes that repeat another node's mesh and transform: coincident
// copies, which draw nothing new (and glass met twice refracts twice). The
// reader draws each mesh once at each place; those that are leaves are
// left out of the file before assimp sees it, which would otherwise make
// about 2 KB of nodes for each (shared/repro's nodes_flat_1e6: 10^6 of
// them, 2 GB).
#ifndef TRAC0R_GLTF_REPEATS_H
#define TRAC0R_GLTF_REPEATS_H

#include <cstddef>
#include <string>

namespace trac0r {

// The words of the defect (model_defects.h) and what is done about it.
extern const char* const gltf_repeat_defect;
extern const char* const gltf_repeat_done;

// `text`, a .gltf's or a .glb's bytes (`glb`), without its leaf nodes (a
// mesh, no children, skin or camera) that repeat an earlier node's mesh
// and transform in the default scene's depth-first walk
// (walk_gltf_nodes): their indices taken out of their parents' and the
// scenes' lists, the JSON written again (a .glb's JSON chunk replaced,
// its binary chunk kept). *removed: how many; *first: which was the first
// and which node it repeats ("node 3 repeats node 0's mesh and
// transform"). "" where none is, or where the JSON or its nodes cannot be
// read (the reader says why). A node listed in two places (against the
// format) is never left out.
std::string gltf_without_repeated_leaves(const std::string& text, bool glb, const std::string& path,
                                         std::size_t* removed, std::string* first);

}  // namespace trac0r

#endif
