// Image files decoded in a child process of their own (isolated_call.h),
// as a glTF's images already are with its reader: a decoder that a
// malformed image crashes or drives to allocate without end is one clear
// message naming the image, never the program's end.
#ifndef TRAC0R_ISOLATED_TEXTURE_H
#define TRAC0R_ISOLATED_TEXTURE_H

#include "trac0r/texture.h"

#include <cstdint>
#include <string>

namespace trac0r {

// load_texture_file, with the decoding in a child process: the same
// texture and the same errors (TextureUnreadable for one that is not
// there or does not decode, a decoder that crashes on it included).
Texture load_texture_file_isolated(const std::string& where, const std::string& path,
                                   std::uint64_t max_texels);

}  // namespace trac0r

#endif
