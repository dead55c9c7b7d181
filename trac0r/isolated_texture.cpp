#include "trac0r/isolated_texture.h"

#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/isolated_call.h"
#include "trac0r/shape.h"

#include <cstring>
#include <stdexcept>

namespace trac0r {

Texture load_texture_file_isolated(const std::string& where, const std::string& path,
                                   std::uint64_t max_texels) {
    std::string bytes;
    try {
        bytes = read_input_file(path, "texture");
    } catch (const std::runtime_error& e) {
        throw TextureUnreadable(where + ": " + e.what());
    }
    // The child's answer: width and height, then the texels; an error as
    // "U" (unreadable) or "E" (another) and its message.
    const IsolatedOutcome outcome = run_isolated(
        [&] {
            Texture t;
            try {
                t = decode_texture(where, path,
                                   reinterpret_cast<const unsigned char*>(bytes.data()),
                                   bytes.size(), max_texels);
            } catch (const TextureUnreadable& e) {
                throw std::runtime_error(std::string("U") + e.what());
            } catch (const std::runtime_error& e) {
                throw std::runtime_error(std::string("E") + e.what());
            }
            std::string out(8 + 4 * t.texels.size(), '\0');
            std::memcpy(&out[0], &t.width, 4);
            std::memcpy(&out[4], &t.height, 4);
            std::memcpy(&out[8], t.texels.data(), 4 * t.texels.size());
            return out;
        },
        mesh_import_time_limit(), half_machine_memory());
    using Kind = IsolatedOutcome::Kind;
    switch (outcome.kind) {
    case Kind::result:
        break;
    case Kind::error:
        if (!outcome.payload.empty() && outcome.payload[0] == 'U') {
            throw TextureUnreadable(outcome.payload.substr(1));
        }
        throw std::runtime_error(outcome.payload.empty() ? where : outcome.payload.substr(1));
    case Kind::out_of_memory:
        throw std::runtime_error(where + ": the image decoder ran out of memory on this image");
    case Kind::timed_out:
        throw TextureUnreadable(where + ": the image decoder did not finish and was stopped: " +
                                "the image is malformed");
    default:
        throw TextureUnreadable(where + ": the image decoder failed on this image (" +
                                printable(outcome.detail, 100) + "): it is malformed");
    }
    Texture t;
    t.source = path;
    const std::string& p = outcome.payload;
    if (p.size() < 8) {
        throw TextureUnreadable(where + ": the image decoder sent back a broken result");
    }
    std::memcpy(&t.width, &p[0], 4);
    std::memcpy(&t.height, &p[4], 4);
    if (t.width < 1 || t.height < 1 || t.width > max_texture_side || t.height > max_texture_side ||
        p.size() !=
            8 + 4 * static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height)) {
        throw TextureUnreadable(where + ": the image decoder sent back a broken result");
    }
    t.texels.resize(static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height));
    std::memcpy(t.texels.data(), &p[8], 4 * t.texels.size());
    return t;
}

}  // namespace trac0r
