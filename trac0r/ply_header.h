// A PLY file's header, checked against the file before assimp reads it:
// assimp 5.2 trusts the header's counts, and a 343-byte file whose header
// promises 10^9 vertices drove its reader past 18 GB.
#ifndef TRAC0R_PLY_HEADER_H
#define TRAC0R_PLY_HEADER_H

#include <string>

namespace trac0r {

// Throws std::runtime_error "path: cannot read mesh: ..." where the PLY
// text's header has no end_header line (alone on a line, within the first
// megabyte; assimp then allocated or looped without end), a format other
// than ascii and binary (little or big endian) 1.0, an element count that
// is no whole number below 2^32, a property of a type PLY does not have,
// or elements that need more bytes than follow the header: at least the
// size of each property in binary (a list: its count), and two characters
// (a digit and a blank) for each in ascii.
void check_ply_header(const std::string& path, const std::string& text);

}  // namespace trac0r

#endif
