#include "trac0r/texture.h"

#include "trac0r/input_file.h"

#include <stb_image.h>

#include <climits>
#include <stdexcept>

namespace trac0r {

std::uint64_t texel_count(const std::vector<Texture>& textures) {
    std::uint64_t texels = 0;
    for (const Texture& t : textures) {
        texels += t.texels.size();
    }
    return texels;
}

void check_texture_room(const std::string& where, int width, int height,
                        std::uint64_t max_texels) {
    const std::uint64_t texels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    if (texels > max_texels) {
        throw std::runtime_error(where + ": texture is " + std::to_string(width) + " x " +
                                 std::to_string(height) + " texels, more than the scene has " +
                                 "room for (" + std::to_string(max_texels) + " more of the " +
                                 std::to_string(max_scene_texels) + " a scene may have)");
    }
}

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
    if (!stbi_info_from_memory(bytes, n, &width, &height, &channels)) {
        throw TextureUnreadable(where + ": cannot decode texture (" + stbi_failure_reason() +
                                "): expected a PNG, JPEG, BMP, TGA or GIF image");
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
        throw TextureUnreadable(where + ": cannot decode texture (" + stbi_failure_reason() + ")");
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
