// Texture files as trac0r decodes them (trac0r/texture.h): the formats
// the docs list, a reason in every refusal (printable), and an image cut
// short refused from its header, before anything is decoded (stb_image
// would fill the rest with zeros). The inputs are shared/repro's.
#include "test_support.h"

#include "trac0r/isolated_call.h"
#include "trac0r/isolated_texture.h"
#include "trac0r/texture.h"

#include <algorithm>
#include <cstdint>

using namespace trac0r;
using Catch::Matchers::Contains;

namespace {

std::string decode_error(const std::string& bytes) {
    try {
        decode_texture("t", "t", reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(),
                       max_scene_texels);
    } catch (const TextureUnreadable& e) {
        return e.what();
    }
    return "";
}

// An uncompressed 24-bit TGA of w x h texels, `data` bytes of texels.
std::string tga(int w, int h, std::size_t data) {
    const unsigned char header[18] = {0,
                                      0,
                                      2,
                                      0,
                                      0,
                                      0,
                                      0,
                                      0,
                                      0,
                                      0,
                                      0,
                                      0,
                                      static_cast<unsigned char>(w & 255),
                                      static_cast<unsigned char>(w >> 8),
                                      static_cast<unsigned char>(h & 255),
                                      static_cast<unsigned char>(h >> 8),
                                      24,
                                      0};
    return std::string(reinterpret_cast<const char*>(header), 18) + std::string(data, '\x40');
}

}  // namespace

TEST_CASE("an image cut short is refused from its header", "[texture]") {
    // A whole 2 x 2 TGA decodes; one byte short, it is cut short.
    CHECK(decode_error(tga(2, 2, 12)).empty());
    CHECK(decode_error(tga(2, 2, 11)) ==
          "t: cannot decode texture: it is cut short (its header needs 30 bytes for 2 x 2 "
          "texels, the file has 29)");
    // The reproducer: an 18-byte header naming 16384 x 16384 texels (4 GB
    // decoded), refused at once.
    CHECK_THAT(decode_error(tga(16384, 16384, 0)),
               Contains("its header needs 805306386 bytes for 16384 x 16384 texels, the file "
                        "has 18"));
    // A BMP (BITMAPINFOHEADER, 24 bits, 2 x 2: rows of 8 bytes) of 38 bytes
    // whose data would end at 70.
    std::string bmp(38, '\0');
    const auto put32 = [&](std::size_t at, std::uint32_t v) {
        for (int k = 0; k < 4; ++k) {
            bmp[at + k] = static_cast<char>((v >> (8 * k)) & 255);
        }
    };
    bmp[0] = 'B';
    bmp[1] = 'M';
    put32(2, 70);
    put32(10, 54);
    put32(14, 40);
    put32(18, 2);
    put32(22, 2);
    bmp[26] = 1;
    bmp[28] = 24;
    CHECK_THAT(decode_error(bmp), Contains("it is cut short (its header needs 70 bytes"));
}

TEST_CASE("only the formats the docs list; every refusal has a printable reason", "[texture]") {
    CHECK(decode_error("8BPS" + std::string(40, '\0')) ==
          "t: cannot decode texture: it is a PSD image: expected a PNG, JPEG, BMP, TGA or GIF "
          "image");
    CHECK_THAT(decode_error("P6\n1 1\n255\n\x01\x02\x03"),
               Contains("it is a PNM (PPM, PGM) image"));
    // A PNG whose chunk name is an escape sequence: escaped in the message.
    const std::string esc_png = std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16) +
                                std::string("\0\0\0\x01\0\0\0\x01\x08\x02\0\0\0", 13) +
                                std::string("\0\0\0\0", 4) + std::string("\0\0\0\0\x1b[2J", 8) +
                                std::string(16, '\0');
    const std::string esc = decode_error(esc_png);
    CAPTURE(esc);
    CHECK(esc.find('\x1b') == std::string::npos);
    CHECK_THAT(esc, Contains("cannot decode texture ("));
    // Where stb_image gives no reason (a 25-byte PNG), one is still given.
    const std::string short_png = std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16) +
                                  std::string("\0\0\0\x01\0\0\0\x01\x08", 9);
    const std::string none = decode_error(short_png);
    CAPTURE(none);
    CHECK_THAT(none, Contains("cannot decode texture ("));
    CHECK(none.find("()") == std::string::npos);
}

TEST_CASE("an image decoded in a child process: the same texture, the same refusals",
          "[texture][isolated]") {
    TempDir dir;
    Rgb8Image image;
    image.width = 2;
    image.height = 1;
    image.bytes = {255, 0, 0, 10, 20, 30};
    const std::string png = dir.path() + "/a.png";
    write_png(png, image);
    const Texture here = load_texture_file("w", png);
    const Texture there = load_texture_file_isolated("w", png, max_scene_texels);
    CHECK(there.width == 2);
    CHECK(there.height == 1);
    CHECK(there.texels == here.texels);
    CHECK(there.source == here.source);
    const std::string short_tga = dir.write("s.tga", tga(2, 2, 11));
    const auto message = [&](bool isolated) {
        try {
            if (isolated) {
                load_texture_file_isolated("w", short_tga, max_scene_texels);
            } else {
                load_texture_file("w", short_tga);
            }
        } catch (const TextureUnreadable& e) {
            return std::string(e.what());
        }
        return std::string("no TextureUnreadable");
    };
    CHECK(message(true) == message(false));
    CHECK_THAT(message(true), Contains("it is cut short"));
    // Over the scene's room: an error, not a defect, from the child too.
    CHECK_THROWS_WITH(load_texture_file_isolated("w", png, 1),
                      Contains("more than the scene has room"));
    CHECK_THROWS_AS(load_texture_file_isolated("w", dir.path() + "/none.png", max_scene_texels),
                    TextureUnreadable);
}

TEST_CASE("a scene's texel budget is sized to the machine's memory", "[texture]") {
    // Half the memory at 16 bytes a texel, never past what the kernel
    // indexes (2^31).
    const std::uint64_t memory = half_machine_memory();
    REQUIRE(memory > 0);  // Linux: sysconf(_SC_PHYS_PAGES)
    CHECK(scene_texel_budget() == std::min(max_scene_texels, memory / scene_texel_peak_bytes));
    CHECK(scene_texel_budget() > 0);
    CHECK(scene_texel_budget() <= max_scene_texels);
}
