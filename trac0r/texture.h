// Base-colour textures as the kernel reads them (kernel/texture.h): 8-bit
// sRGB texels, decoded from the image files and bytes that meshes name.
#ifndef TRAC0R_TEXTURE_H
#define TRAC0R_TEXTURE_H

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r {

// How a texture continues outside [0, 1) in u or v (glTF's sampler wrap
// modes: REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT). The kernel reads them
// from TextureRecord::info.w (kernel/texture.h).
enum class TextureWrap : unsigned { repeat = 0, clamp = 1, mirror = 2 };

struct Texture {
    std::string source;  // the file, or the mesh file and its embedded image
    int width = 0;
    int height = 0;
    TextureWrap wrap_u = TextureWrap::repeat;
    TextureWrap wrap_v = TextureWrap::repeat;
    // Row by row from the image's top row, RGBA8 in sRGB, red in the low
    // byte (alpha is kept but not used).
    std::vector<std::uint32_t> texels;
};

// The largest texture side, and the most texels a scene's textures may
// have in all on any machine (the kernel indexes them with 32 bits).
const int max_texture_side = 16384;
const std::uint64_t max_scene_texels = std::uint64_t(1) << 31;

// The bytes a texel takes at the peak of loading and packing a scene: 4
// (RGBA8) in up to four places at once (the decoder's image, its copy
// through the reader's pipe, the scene's texture, the packed scene's
// texels).
const std::uint64_t scene_texel_peak_bytes = 16;

// The most texels a scene's textures may have on this machine: those
// whose peak fits half its memory (half_machine_memory), at most
// max_scene_texels (all of them where the memory cannot be known). The
// scene loader counts each image against it from its header.
std::uint64_t scene_texel_budget();

// A texture that is not there, or whose bytes do not decode as an image:
// a defect lenient loading passes over (model_defects.h), where a texture
// over the scene's room or of the wrong kind (HDR) stays an error.
struct TextureUnreadable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// An image file (PNG, JPEG, BMP, TGA or GIF, through stb_image; HDR is
// refused) as a texture; `where` starts each message ("mesh.mtl:
// material 'wood': map_Kd 'wood.png'"). Throws std::runtime_error
// "WHERE: cannot open/read texture ..." or "WHERE: cannot decode ..."
// (both TextureUnreadable).
// An image of more than `max_texels` texels (what the scene has room for)
// is refused from its header, before it is decoded.
Texture load_texture_file(const std::string& where, const std::string& path,
                          std::uint64_t max_texels = max_scene_texels);

// The same for an image file's bytes in memory (an embedded glTF image).
Texture decode_texture(const std::string& where, const std::string& source,
                       const unsigned char* bytes, std::size_t size,
                       std::uint64_t max_texels = max_scene_texels);

// The texels of these textures in all.
std::uint64_t texel_count(const std::vector<Texture>& textures);

// Throws std::runtime_error "WHERE: texture is W x H ..." when an image of
// that size is more than the `max_texels` the scene has room for.
void check_texture_room(const std::string& where, int width, int height,
                        std::uint64_t max_texels);

}  // namespace trac0r

#endif
