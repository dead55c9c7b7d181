// Reading a user's input file whole (scenes, meshes, replay scripts):
// only a regular file, and at most a size limit, so that a path naming
// /dev/zero, a FIFO or a terminal is one clear message, not a read that
// grows without end or waits for ever.
#ifndef TRAC0R_INPUT_FILE_H
#define TRAC0R_INPUT_FILE_H

#include <cstdint>
#include <string>

namespace trac0r {

// The largest input file read, in bytes: 4,000 MB unless set (trac0r_viewer's
// --max-input-mb sets it for the whole process).
std::uint64_t input_size_limit();
void set_input_size_limit(std::uint64_t bytes);

// The whole of the file at path. `what` names it in messages ("scene
// file", "OBJ mesh"): on failure throws std::runtime_error
// "PATH: cannot open WHAT: REASON" (the system's) or "PATH: cannot read
// WHAT: REASON" (it is a directory; it is a device,
// FIFO or socket, not a regular file; it is N MB, over the input size
// limit ...; or the system's reason).
std::string read_input_file(const std::string& path, const std::string& what);

// A path that a file in base_dir names: file itself where it is absolute
// or base_dir is empty, else base_dir/file.
std::string resolve_path(const std::string& base_dir, const std::string& file);

}  // namespace trac0r

#endif
