#include "trac0r/lights.h"

#include "trac0r/enum_names.h"
#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"

#include <tinyexr.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <memory>
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

// The RGB of `width` x `height` RGBA floats, each texel checked: finite
// and not negative.
void take_texels(const std::string& path, const float* rgba, int width, int height,
                 Environment& e) {
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
}

// The EXR in `bytes`, its size checked from the header first (a small
// file may claim a huge image, or a data window that is upside down).
void decode_exr(const std::string& path, const std::string& bytes, Environment& e) {
    const auto* memory = reinterpret_cast<const unsigned char*>(bytes.data());
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, memory, bytes.size()) != TINYEXR_SUCCESS) {
        throw std::runtime_error(path + ": cannot read environment map: not an OpenEXR file");
    }
    if (version.multipart || version.non_image) {
        throw std::runtime_error(path + ": cannot read environment map: multi-part and deep "
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
    const auto side = [](long long v) {
        return static_cast<int>(std::max(0ll, std::min(v, 1ll << 30)));
    };
    check_size(path, side(w), side(h));
    float* raw = nullptr;
    int width = 0;
    int height = 0;
    if (LoadEXRFromMemory(&raw, &width, &height, memory, bytes.size(), &err) != TINYEXR_SUCCESS) {
        throw std::runtime_error(path + ": cannot read environment map (" + exr_error(err) + ")");
    }
    const std::unique_ptr<float, void (*)(void*)> rgba(raw, std::free);
    check_size(path, width, height);
    take_texels(path, rgba.get(), width, height, e);
}

// A Radiance RGBE (.hdr) file, read here rather than by stb_image, which
// fills a truncated file's missing texels with zeros without a word:
// header lines up to a blank one, the size "-Y H +X W" (rows from the top,
// the only orientation maps use), then each scanline flat (4 bytes a
// texel) or run-length encoded per channel (it starts 2, 2, W). A texel
// is (r, g, b) x 2^(e - 136), zero where e is 0, as stb_image and the
// format's own reader decode it.
void decode_hdr(const std::string& path, const std::string& bytes, Environment& e) {
    const auto fail = [&](const std::string& why) -> void {
        throw std::runtime_error(path + ": cannot read environment map: " + why);
    };
    if (bytes.compare(0, 2, "#?") != 0) {
        fail("not a Radiance .hdr file (it does not start \"#?\")");
    }
    std::size_t at = 0;
    bool blank = false;
    while (!blank) {
        const std::size_t end = bytes.find('\n', at);
        if (end == std::string::npos || end - at > 4096) {
            fail("its header does not end (no blank line)");
        }
        const std::string line = bytes.substr(at, end - at);
        if (line.compare(0, 7, "FORMAT=") == 0 && line != "FORMAT=32-bit_rle_rgbe") {
            fail("format " + line.substr(7, 40) + " (expected 32-bit_rle_rgbe)");
        }
        blank = line.empty();
        at = end + 1;
    }
    const std::size_t end = bytes.find('\n', at);
    int width = 0;
    int height = 0;
    char tail = 0;
    if (end == std::string::npos ||
        std::sscanf(bytes.substr(at, end - at).c_str(), "-Y %d +X %d%c", &height, &width, &tail) !=
            2) {
        fail("expected its size as \"-Y HEIGHT +X WIDTH\" after the header");
    }
    at = end + 1;
    check_size(path, width, height);
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const std::size_t size = bytes.size();
    std::vector<unsigned char> row(static_cast<std::size_t>(width) * 4);
    std::vector<float> rgba(static_cast<std::size_t>(width) * height * 4);
    for (int y = 0; y < height; ++y) {
        const std::string where = " in scanline " + std::to_string(y);
        if (at + 4 > size) {
            fail("the file ends" + where + " (truncated)");
        }
        const bool rle = width >= 8 && width < 32768 && data[at] == 2 && data[at + 1] == 2 &&
                         ((data[at + 2] << 8) | data[at + 3]) == width;
        if (!rle) {
            if (at + row.size() > size) {
                fail("the file ends" + where + " (truncated)");
            }
            std::copy(data + at, data + at + row.size(), row.begin());
            at += row.size();
        } else {
            at += 4;
            for (int c = 0; c < 4; ++c) {
                int x = 0;
                while (x < width) {
                    if (at >= size) {
                        fail("the file ends" + where + " (truncated)");
                    }
                    int count = data[at++];
                    const bool run = count > 128;
                    count = run ? count - 128 : count;
                    if (count == 0 || x + count > width || at + (run ? 1 : count) > size) {
                        fail("a bad run length" + where + " (corrupt or truncated)");
                    }
                    for (int k = 0; k < count; ++k) {
                        row[static_cast<std::size_t>(x + k) * 4 + c] = data[run ? at : at + k];
                    }
                    at += run ? 1 : count;
                    x += count;
                }
            }
        }
        for (int x = 0; x < width; ++x) {
            const unsigned char* t = &row[static_cast<std::size_t>(x) * 4];
            const float f = t[3] != 0 ? std::ldexp(1.0f, t[3] - 136) : 0.0f;
            float* out = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
            out[0] = t[0] * f;
            out[1] = t[1] * f;
            out[2] = t[2] * f;
        }
    }
    take_texels(path, rgba.data(), width, height, e);
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
    Environment e;
    e.present = true;
    e.map = path;
    if (exr) {
        decode_exr(path, bytes, e);
    } else {
        decode_hdr(path, bytes, e);
    }
    return e;
}

}  // namespace trac0r
