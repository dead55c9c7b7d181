#include "trac0r/image_io.h"

#include "trac0r/input_checks.h"
#include "trac0r/output_file.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace trac0r {

namespace {

bool host_is_little_endian() {
    const std::uint32_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

}  // namespace

std::uint8_t encode_srgb8(float display) {
    if (!(display > 0.0f)) {
        return 0;  // also NaN
    }
    const float v = std::min(display, 1.0f);
    const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(srgb * 255.0f));
}

std::uint8_t tonemap_channel(float linear, float exposure) {
    return encode_srgb8(linear * exposure);
}

Rgb8Image tonemap_image(const Image& image, float exposure, ViewTransform view) {
    Rgb8Image out;
    out.width = image.width;
    out.height = image.height;
    out.bytes.resize(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec3 display = apply_view(view, image.pixels[i] * exposure);
        for (int c = 0; c < 3; ++c) {
            out.bytes[3 * i + c] = encode_srgb8(display[c]);
        }
    }
    return out;
}

void write_png(const std::string& path, const Image& image, float exposure, ViewTransform view) {
    write_png(path, tonemap_image(image, exposure, view));
}

void write_png(const std::string& path, const Rgb8Image& image) {
    // Encoded in memory, then written whole (write_file_replacing): stb's
    // own file writer does not check its writes or its close.
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 3, image.bytes.data(),
                                image.width * 3)) {
        throw std::runtime_error(path + ": cannot encode PNG");
    }
    write_file_replacing(path, bytes.data(), bytes.size());
}

Rgb8Image read_png(const std::string& path) {
    int width = 0;
    int height = 0;
    int channels_in_file = 0;
    stbi_uc* pixels = stbi_load(path.c_str(), &width, &height, &channels_in_file, 3);
    if (!pixels) {
        throw std::runtime_error(path + ": cannot read PNG (" + stbi_failure_reason() + ")");
    }
    Rgb8Image out;
    out.width = width;
    out.height = height;
    out.bytes.assign(pixels, pixels + static_cast<std::size_t>(width) * height * 3);
    stbi_image_free(pixels);
    return out;
}

void write_pfm(const std::string& path, const Image& image) {
    ReplacingFile out(path);  // row by row: an image's bytes are not copied whole
    // A negative scale says little-endian.
    const std::string header = "PF\n" + std::to_string(image.width) + " " +
                               std::to_string(image.height) + "\n" +
                               (host_is_little_endian() ? "-1.0" : "1.0") + "\n";
    out.write(header.data(), header.size());
    const std::size_t row_bytes = sizeof(glm::vec3) * static_cast<std::size_t>(image.width);
    for (int y = image.height - 1; y >= 0; --y) {  // PFM stores the bottom row first
        out.write(&image.pixels[static_cast<std::size_t>(y) * image.width], row_bytes);
    }
    out.commit();
}

Image read_pfm(const std::string& path) {
    if (is_directory(path)) {
        throw std::runtime_error(path + ": cannot read PFM: it is a directory");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw std::runtime_error(path + ": cannot open PFM");
    }
    std::string magic;
    Image image;
    double scale = 0.0;
    in >> magic >> image.width >> image.height >> scale;
    if (!in || magic != "PF" || image.width <= 0 || image.height <= 0 || scale == 0.0) {
        throw std::runtime_error(path + ": not a colour PFM (expected 'PF', size and scale)");
    }
    in.get();  // the single whitespace after the scale
    const bool file_little = scale < 0.0;
    image.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
    for (int y = image.height - 1; y >= 0; --y) {
        char* row =
            reinterpret_cast<char*>(&image.pixels[static_cast<std::size_t>(y) * image.width]);
        const std::size_t bytes = sizeof(glm::vec3) * image.width;
        if (!in.read(row, static_cast<std::streamsize>(bytes))) {
            throw std::runtime_error(path + ": PFM data is truncated");
        }
        if (file_little != host_is_little_endian()) {
            for (std::size_t i = 0; i < bytes; i += 4) {
                std::swap(row[i], row[i + 3]);
                std::swap(row[i + 1], row[i + 2]);
            }
        }
    }
    return image;
}

void write_exr(const std::string& path, const Image& image, const std::vector<ExrChannel>& extra,
               ExrPrecision precision) {
    const std::size_t pixels = image.pixels.size();
    // R, G and B, then the extra channels; written in the order OpenEXR
    // sorts their names (byte order: B, G, R, Z, albedo.B, ...).
    std::vector<ExrChannel> rgb(3);
    const char* const rgb_names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        rgb[c].name = rgb_names[c];
        rgb[c].values.resize(pixels);
        for (std::size_t i = 0; i < pixels; ++i) {
            rgb[c].values[i] = image.pixels[i][c];
        }
    }
    std::vector<const ExrChannel*> order;
    for (const ExrChannel& c : rgb) {
        order.push_back(&c);
    }
    for (const ExrChannel& c : extra) {
        if (c.name.empty() || c.name.size() > 255) {
            throw std::invalid_argument(path +
                                        ": an EXR channel name must have 1 to 255 "
                                        "characters, got " +
                                        std::to_string(c.name.size()));
        }
        if (c.values.size() != pixels) {
            throw std::invalid_argument(path + ": EXR channel '" + c.name + "' has " +
                                        std::to_string(c.values.size()) + " values for " +
                                        std::to_string(pixels) + " pixels");
        }
        order.push_back(&c);
    }
    std::sort(order.begin(), order.end(),
              [](const ExrChannel* a, const ExrChannel* b) { return a->name < b->name; });
    for (std::size_t k = 1; k < order.size(); ++k) {
        if (order[k]->name == order[k - 1]->name) {
            throw std::invalid_argument(path + ": EXR channel '" + order[k]->name +
                                        "' given twice");
        }
    }
    const int count = static_cast<int>(order.size());
    const bool half = precision == ExrPrecision::Half;
    // For half, a copy clamped to the largest finite half (65504), which
    // tinyexr's conversion would otherwise round to infinity; NaN stays.
    std::vector<std::vector<float>> clamped(half ? order.size() : 0);
    for (std::size_t k = 0; k < clamped.size(); ++k) {
        clamped[k] = order[k]->values;
        for (float& v : clamped[k]) {
            if (v > 65504.0f) {
                v = 65504.0f;
            } else if (v < -65504.0f) {
                v = -65504.0f;
            }
        }
    }
    std::vector<unsigned char*> plane_pointers(order.size());
    std::vector<EXRChannelInfo> channels(order.size());
    std::vector<int> types(order.size(), TINYEXR_PIXELTYPE_FLOAT);
    std::vector<int> stored(order.size(), half ? TINYEXR_PIXELTYPE_HALF : TINYEXR_PIXELTYPE_FLOAT);
    std::memset(channels.data(), 0, sizeof(EXRChannelInfo) * channels.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        const float* values = half ? clamped[k].data() : order[k]->values.data();
        plane_pointers[k] = reinterpret_cast<unsigned char*>(const_cast<float*>(values));
        std::memcpy(channels[k].name, order[k]->name.c_str(), order[k]->name.size() + 1);
    }
    EXRImage exr;
    InitEXRImage(&exr);
    exr.images = plane_pointers.data();
    exr.width = image.width;
    exr.height = image.height;
    exr.num_channels = count;
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = count;
    header.channels = channels.data();
    header.pixel_types = types.data();
    header.requested_pixel_types = stored.data();  // float as computed, or half
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    unsigned char* memory = nullptr;
    const char* error = nullptr;
    const std::size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &error);
    if (size == 0) {
        const std::string reason = error ? error : "unknown error";
        FreeEXRErrorMessage(error);
        throw std::runtime_error(path + ": cannot encode the EXR image (" + reason + ")");
    }
    struct Freed {
        unsigned char* p;
        ~Freed() { std::free(p); }
    } freed{memory};
    write_file_replacing(path, memory, size);
}

bool is_supported_image_path(const std::string& path) {
    return is_png_path(path) || has_extension(path, ".pfm") || has_extension(path, ".exr");
}

bool is_png_path(const std::string& path) { return has_extension(path, ".png"); }

bool is_exr_path(const std::string& path) { return has_extension(path, ".exr"); }

void write_image(const std::string& path, const Image& image, float exposure, ViewTransform view) {
    if (is_png_path(path)) {
        write_png(path, image, exposure, view);
    } else if (has_extension(path, ".pfm")) {
        write_pfm(path, image);
    } else if (has_extension(path, ".exr")) {
        write_exr(path, image);
    } else {
        throw std::runtime_error(path + ": unknown image format (expected .png, .pfm or .exr)");
    }
}

}  // namespace trac0r
