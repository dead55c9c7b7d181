// How many triangles a glTF's JSON promises, so that a file promising
// more than the machine can hold is refused before its reader allocates
// them (shared/repro: an indices accessor of 3 x 10^8 in a 1 GiB buffer
// took the reader past 6.7 GB before it failed).
#ifndef TRAC0R_GLTF_SIZE_H
#define TRAC0R_GLTF_SIZE_H

#include <cstdint>
#include <string>

namespace trac0r {

// The triangles of the default scene's nodes (each node's mesh, once per
// node that instances it with a transform of its own; the reader skips a
// repeated one): a triangle primitive's index count (or vertex
// count without indices) over 3, a strip's or fan's less 2. 0 where the
// JSON cannot be read. Throws GltfNodesTooDeep (gltf_nodes.h) naming
// `path` for nodes nested too deep for the reader.
std::uint64_t gltf_promised_triangles(const std::string& json_text, const std::string& path);

// About what trac0r holds a loaded triangle in, at its peak (loading,
// packing and the BVH: an OBJ of 10^7 triangles took 4.5 GB).
const std::uint64_t bytes_per_loaded_triangle = 450;

}  // namespace trac0r

#endif
