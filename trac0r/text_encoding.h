// Text files' encodings: what model readers accept besides UTF-8.
#ifndef TRAC0R_TEXT_ENCODING_H
#define TRAC0R_TEXT_ENCODING_H

#include <string>

namespace trac0r {

// `text` as UTF-8 where it begins with a UTF-16 byte-order mark (FE FF big
// endian, FF FE little endian; the mark is dropped); else `text`. A lone
// surrogate, or an odd byte at the end, becomes U+FFFD.
std::string utf8_of_utf16(const std::string& text);

}  // namespace trac0r

#endif
