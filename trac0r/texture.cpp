#include "trac0r/texture.h"

#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/isolated_call.h"

#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <stdexcept>

namespace trac0r {

std::uint64_t texel_count(const std::vector<Texture>& textures) {
    std::uint64_t texels = 0;
    for (const Texture& t : textures) {
        texels += t.texels.size();
    }
    return texels;
}

std::uint64_t scene_texel_budget() {
    const std::uint64_t memory = half_machine_memory();
    if (memory == 0) {
        return max_scene_texels;
    }
    return std::min(max_scene_texels, memory / scene_texel_peak_bytes);
}

void check_texture_room(const std::string& where, int width, int height,
                        std::uint64_t max_texels) {
    const std::uint64_t texels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    if (texels > max_texels) {
        throw std::runtime_error(where + ": texture is " + std::to_string(width) + " x " +
                                 std::to_string(height) + " texels, more than the scene has " +
                                 "room for (" + std::to_string(max_texels) + " more of the " +
                                 std::to_string(scene_texel_budget()) +
                                 " a scene may have on this machine)");
    }
}

namespace {

// stb_image's reason for its last failure, printable, never empty.
std::string failure_reason() {
    const char* reason = stbi_failure_reason();
    return reason != nullptr && *reason != '\0' ? printable(reason, 100)
                                                 : std::string("stb_image gives no reason");
}

// The format of an image stb_image reads but trac0r does not offer
// (docs: PNG, JPEG, BMP, TGA, GIF), by its first bytes; nullptr for none.
const char* unlisted_format(const unsigned char* b, std::size_t n) {
    if (n >= 4 && std::memcmp(b, "8BPS", 4) == 0) {
        return "a PSD";
    }
    if (n >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') {
        return "a PNM (PPM, PGM)";
    }
    if (n >= 4 && b[0] == 0x53 && b[1] == 0x80 && b[2] == 0xF6 && b[3] == 0x34) {
        return "a Softimage PIC";
    }
    return nullptr;
}

std::uint64_t le16(const unsigned char* p) { return p[0] | static_cast<std::uint64_t>(p[1]) << 8; }
std::uint64_t le32(const unsigned char* p) { return le16(p) | le16(p + 2) << 16; }

// The bytes an uncompressed BMP or TGA of w x h texels needs by its
// header (stb_image fills what is missing with zeros); 0 for another
// format or a compressed one (whose decoder finds a cut short).
std::uint64_t uncompressed_bytes(const unsigned char* b, std::size_t n, int w, int h) {
    const std::uint64_t texels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
    if (n >= 34 && b[0] == 'B' && b[1] == 'M') {
        const std::uint64_t bpp = le16(b + 28);
        if (le32(b + 14) < 40 || le32(b + 30) != 0) {
            return 0;  // an old header, or compressed
        }
        const std::uint64_t row = (static_cast<std::uint64_t>(w) * bpp + 31) / 32 * 4;
        return le32(b + 10) + row * static_cast<std::uint64_t>(h);
    }
    const bool other = (n >= 4 && std::memcmp(b, "\x89PNG", 4) == 0) ||
                       (n >= 3 && b[0] == 0xFF && b[1] == 0xD8) ||
                       (n >= 4 && std::memcmp(b, "GIF8", 4) == 0);
    if (!other && n >= 18 && (b[2] == 1 || b[2] == 2 || b[2] == 3)) {
        const std::uint64_t palette = b[1] != 0 ? le16(b + 5) * ((b[7] + 7u) / 8u) : 0;
        return 18 + b[0] + palette + texels * ((b[16] + 7u) / 8u);
    }
    return 0;
}

}  // namespace

Texture decode_texture(const std::string& where, const std::string& source,
                       const unsigned char* bytes, std::size_t size, std::uint64_t max_texels) {
    if (size == 0) {
        throw TextureUnreadable(where + ": cannot decode texture: it is empty");
    }
    if (size > static_cast<std::size_t>(INT_MAX)) {
        throw TextureUnreadable(where + ": cannot decode texture: it is over 2 GB");
    }
    const int n = static_cast<int>(size);
    int width = 0;
    int height = 0;
    int channels = 0;
    if (const char* format = unlisted_format(bytes, size)) {
        throw TextureUnreadable(where + ": cannot decode texture: it is " + format +
                                " image: expected a PNG, JPEG, BMP, TGA or GIF image");
    }
    if (!stbi_info_from_memory(bytes, n, &width, &height, &channels)) {
        throw TextureUnreadable(where + ": cannot decode texture (" + failure_reason() +
                                "): expected a PNG, JPEG, BMP, TGA or GIF image");
    }
    const std::uint64_t needed = uncompressed_bytes(bytes, size, width, height);
    if (needed > size) {
        throw TextureUnreadable(where + ": cannot decode texture: it is cut short (its header " +
                                "needs " + std::to_string(needed) + " bytes for " +
                                std::to_string(width) + " x " + std::to_string(height) +
                                " texels, the file has " + std::to_string(size) + ")");
    }
    if (stbi_is_hdr_from_memory(bytes, n)) {
        throw std::runtime_error(where + ": an HDR image cannot be a base-colour texture: " +
                                 "expected an 8-bit sRGB image (PNG, JPEG ...)");
    }
    if (width < 1 || height < 1 || width > max_texture_side || height > max_texture_side) {
        throw std::runtime_error(where + ": texture is " + std::to_string(width) + " x " +
                                 std::to_string(height) + ": expected each side in [1, " +
                                 std::to_string(max_texture_side) + "]");
    }
    // Before decoding: a small file can name a huge image, and many of
    // them would exhaust memory before the scene's total is known.
    check_texture_room(where, width, height, max_texels);
    stbi_uc* pixels = stbi_load_from_memory(bytes, n, &width, &height, &channels, 4);
    if (pixels == nullptr) {
        throw TextureUnreadable(where + ": cannot decode texture (" + failure_reason() + ")");
    }
    Texture t;
    t.source = source;
    t.width = width;
    t.height = height;
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    t.texels.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const stbi_uc* p = pixels + 4 * i;
        t.texels[i] = static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
                      static_cast<std::uint32_t>(p[2]) << 16 |
                      static_cast<std::uint32_t>(p[3]) << 24;
    }
    stbi_image_free(pixels);
    return t;
}

Texture load_texture_file(const std::string& where, const std::string& path,
                          std::uint64_t max_texels) {
    std::string bytes;
    try {
        bytes = read_input_file(path, "texture");
    } catch (const std::runtime_error& e) {
        throw TextureUnreadable(where + ": " + e.what());
    }
    return decode_texture(where, path, reinterpret_cast<const unsigned char*>(bytes.data()),
                          bytes.size(), max_texels);
}

}  // namespace trac0r
