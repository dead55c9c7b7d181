#include "trac0r/lights.h"

#include "trac0r/enum_names.h"
#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"

#include <stb_image.h>
#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace trac0r {

namespace {

const EnumName<LampType> lamp_type_table[] = {
    {LampType::point, "point"}, {LampType::spot, "spot"}, {LampType::sun, "sun"}};

void check_size(const std::string& path, int width, int height) {
    const long long texels = static_cast<long long>(width) * height;
    if (width < 1 || height < 1 || width > max_environment_side || height > max_environment_side ||
        texels > max_environment_texels) {
        throw std::runtime_error(path + ": environment map is " + std::to_string(width) + " x " +
                                 std::to_string(height) + ": expected at most " +
                                 std::to_string(max_environment_texels) +
                                 " texels (8192 x 4096), each side in [1, " +
                                 std::to_string(max_environment_side) + "]");
    }
}

std::string exr_error(const char* err) {
    std::string text = err ? err : "unknown reason";
    if (err) {
        FreeEXRErrorMessage(err);
    }
    return text;
}

// RGBA floats of the EXR in `bytes`, size checked from the header first
// (a small file may claim a huge image).
std::vector<float> decode_exr(const std::string& path, const std::string& bytes, int* width,
                              int* height) {
    const auto* memory = reinterpret_cast<const unsigned char*>(bytes.data());
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, memory, bytes.size()) != TINYEXR_SUCCESS) {
        throw std::runtime_error(path + ": cannot read environment map: not an OpenEXR file");
    }
    if (version.multipart || version.non_image) {
        throw std::runtime_error(path +
                                 ": cannot read environment map: multi-part and deep "
                                 "OpenEXR files are not supported (expected one RGB image)");
    }
    EXRHeader header;
    InitEXRHeader(&header);
    const char* err = nullptr;
    if (ParseEXRHeaderFromMemory(&header, &version, memory, bytes.size(), &err) !=
        TINYEXR_SUCCESS) {
        throw std::runtime_error(path + ": cannot read environment map (" + exr_error(err) + ")");
    }
    const long long w =
        static_cast<long long>(header.data_window.max_x) - header.data_window.min_x + 1;
    const long long h =
        static_cast<long long>(header.data_window.max_y) - header.data_window.min_y + 1;
    FreeEXRHeader(&header);
    check_size(path, static_cast<int>(std::min<long long>(w, 1ll << 30)),
               static_cast<int>(std::min<long long>(h, 1ll << 30)));
    float* rgba = nullptr;
    if (LoadEXRFromMemory(&rgba, width, height, memory, bytes.size(), &err) != TINYEXR_SUCCESS) {
        throw std::runtime_error(path + ": cannot read environment map (" + exr_error(err) + ")");
    }
    check_size(path, *width, *height);
    std::vector<float> out(rgba, rgba + static_cast<std::size_t>(*width) * *height * 4);
    std::free(rgba);
    return out;
}

std::vector<float> decode_hdr(const std::string& path, const std::string& bytes, int* width,
                              int* height) {
    const auto* memory = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int n = static_cast<int>(std::min<std::size_t>(bytes.size(), 0x7fffffff));
    int channels = 0;
    if (!stbi_is_hdr_from_memory(memory, n) ||
        !stbi_info_from_memory(memory, n, width, height, &channels)) {
        throw std::runtime_error(path + ": cannot read environment map: not a Radiance .hdr file");
    }
    check_size(path, *width, *height);
    float* rgb = stbi_loadf_from_memory(memory, n, width, height, &channels, 4);
    if (rgb == nullptr) {
        throw std::runtime_error(path + ": cannot read environment map (" +
                                 std::string(stbi_failure_reason()) + ")");
    }
    std::vector<float> out(rgb, rgb + static_cast<std::size_t>(*width) * *height * 4);
    stbi_image_free(rgb);
    return out;
}

}  // namespace

const char* to_string(LampType type) { return enum_name(lamp_type_table, type, "unknown"); }

LampType parse_lamp_type(const std::string& name) {
    return enum_value(lamp_type_table, name, "light type");
}

std::vector<std::string> lamp_type_names() { return enum_names(lamp_type_table); }

Environment read_environment_map(const std::string& path) {
    const bool exr = has_extension(path, ".exr");
    if (!exr && !has_extension(path, ".hdr")) {
        throw std::runtime_error(path +
                                 ": cannot read environment map: expected an .exr or .hdr "
                                 "file (equirectangular, linear RGB)");
    }
    const std::string bytes = read_input_file(path, "environment map");
    int width = 0;
    int height = 0;
    const std::vector<float> rgba =
        exr ? decode_exr(path, bytes, &width, &height) : decode_hdr(path, bytes, &width, &height);
    Environment e;
    e.present = true;
    e.map = path;
    e.width = width;
    e.height = height;
    e.texels.resize(static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < e.texels.size(); ++i) {
        const glm::vec3 t(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]);
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(t[c]) || t[c] < 0.0f) {
                throw std::runtime_error(
                    path + ": environment map texel (" + std::to_string(i % width) + ", " +
                    std::to_string(i / width) + ") has " +
                    (std::isfinite(t[c]) ? "a negative" : "a non-finite") + " value in channel " +
                    "RGB"[c] + ": expected radiance >= 0 in every channel");
            }
        }
        e.texels[i] = t;
    }
    return e;
}

}  // namespace trac0r
