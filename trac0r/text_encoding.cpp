#include "trac0r/text_encoding.h"

#include <cstdint>

namespace trac0r {

std::string utf8_of_utf16(const std::string& text) {
    if (text.size() < 2) {
        return text;
    }
    const unsigned char b0 = static_cast<unsigned char>(text[0]);
    const unsigned char b1 = static_cast<unsigned char>(text[1]);
    const bool big = b0 == 0xFE && b1 == 0xFF;
    if (!big && !(b0 == 0xFF && b1 == 0xFE)) {
        return text;
    }
    const auto unit = [&](std::size_t i) -> std::uint32_t {
        const unsigned char a = static_cast<unsigned char>(text[i]);
        const unsigned char b = static_cast<unsigned char>(text[i + 1]);
        return big ? (a << 8 | b) : (b << 8 | a);
    };
    std::string out;
    out.reserve(text.size() / 2);
    const auto put = [&out](std::uint32_t c) {
        if (c < 0x80) {
            out += static_cast<char>(c);
        } else if (c < 0x800) {
            out += static_cast<char>(0xC0 | c >> 6);
            out += static_cast<char>(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            out += static_cast<char>(0xE0 | c >> 12);
            out += static_cast<char>(0x80 | (c >> 6 & 0x3F));
            out += static_cast<char>(0x80 | (c & 0x3F));
        } else {
            out += static_cast<char>(0xF0 | c >> 18);
            out += static_cast<char>(0x80 | (c >> 12 & 0x3F));
            out += static_cast<char>(0x80 | (c >> 6 & 0x3F));
            out += static_cast<char>(0x80 | (c & 0x3F));
        }
    };
    std::size_t i = 2;
    for (; i + 1 < text.size(); i += 2) {
        const std::uint32_t u = unit(i);
        if (u >= 0xD800 && u < 0xDC00 && i + 3 < text.size()) {
            const std::uint32_t low = unit(i + 2);
            if (low >= 0xDC00 && low < 0xE000) {
                put(0x10000 + ((u - 0xD800) << 10) + (low - 0xDC00));
                i += 2;
                continue;
            }
        }
        put(u >= 0xD800 && u < 0xE000 ? 0xFFFD : u);
    }
    if (i < text.size()) {
        put(0xFFFD);
    }
    return out;
}

}  // namespace trac0r
