// Writing and reading images. Pixels are linear RGB, row 0 at the top.
#ifndef TRAC0R_IMAGE_IO_H
#define TRAC0R_IMAGE_IO_H

#include "trac0r/view_transform.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace trac0r {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;  // row-major, row 0 at the top

    glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
    const glm::vec3& at(int x, int y) const {
        return pixels[static_cast<std::size_t>(y) * width + x];
    }
};

// 8-bit sRGB pixels, RGB interleaved, row 0 at the top: what a screen or
// a PNG shows.
struct Rgb8Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> bytes;  // 3 per pixel
};

// Linear radiance to an 8-bit sRGB value: exposure, clamp, sRGB curve
// (the standard view).
std::uint8_t tonemap_channel(float linear, float exposure);
// A display value in [0, 1] (a view transform's) as 8-bit sRGB: the sRGB
// curve, rounded. Below 0 and NaN give 0, above 1 gives 255.
std::uint8_t encode_srgb8(float display);
// Every pixel: times the exposure, through the view transform, sRGB
// encoded. The standard view gives tonemap_channel of every channel.
Rgb8Image tonemap_image(const Image& image, float exposure,
                        ViewTransform view = ViewTransform::standard);

// True for the extensions write_image knows (.png, .pfm, .exr, any case).
bool is_supported_image_path(const std::string& path);
// Whether path names a PNG (ends in .png, in any case), as write_image reads it.
bool is_png_path(const std::string& path);
// Whether path names an EXR (ends in .exr, in any case).
bool is_exr_path(const std::string& path);

// .png (tone-mapped sRGB: exposure and view), .pfm or .exr (linear float,
// the pixels as they are, whatever the exposure and view), chosen by the
// extension.
// Throws std::runtime_error naming the file on failure or another extension.
void write_image(const std::string& path, const Image& image, float exposure = 1.0f,
                 ViewTransform view = ViewTransform::standard);
void write_png(const std::string& path, const Image& image, float exposure = 1.0f,
               ViewTransform view = ViewTransform::standard);
void write_png(const std::string& path, const Rgb8Image& image);
// Any 8-bit PNG, converted to RGB. Throws std::runtime_error naming the file.
Rgb8Image read_png(const std::string& path);
// PFM ("PF", little-endian scale -1), rows bottom first as the format says.
void write_pfm(const std::string& path, const Image& image);
Image read_pfm(const std::string& path);
// A channel of an EXR file beside R, G and B: its name ("albedo.R", "Z")
// and one value a pixel, row-major, row 0 at the top.
struct ExrChannel {
    std::string name;
    std::vector<float> values;
};

// How write_exr stores every channel: 32-bit float, or 16-bit half
// (OpenEXR's HALF, half the file). Half keeps about 3 decimal digits and
// values up to 65504: a value beyond that (infinity included) is stored as
// +-65504, the largest finite half, never as infinity; NaN stays NaN.
enum class ExrPrecision { Float, Half };

// OpenEXR, scanlines with ZIP compression: channels R, G, B, with Float
// the pixels exactly as the PFM of the same image holds them, with Half
// each rounded to the nearest half (clamped as ExrPrecision says), and the
// `extra` channels in the same precision. Throws std::invalid_argument for
// an extra channel of the wrong size or a name given twice.
void write_exr(const std::string& path, const Image& image,
               const std::vector<ExrChannel>& extra = {},
               ExrPrecision precision = ExrPrecision::Float);

}  // namespace trac0r

#endif
