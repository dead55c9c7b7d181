// Light that does not come from a scene's surfaces, as authored: the
// environment (a constant colour or an equirectangular map) and lamps
// (point, spot, sun). The kernel's side: kernel/environment.h, lamps.h.
#ifndef TRAC0R_LIGHTS_H
#define TRAC0R_LIGHTS_H

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace trac0r {

// The radiance from every direction a ray leaves the scene in. Without
// one (present false), such rays find black.
struct Environment {
    bool present = false;
    float strength = 1.0f;  // multiplies the colour or the map
    float rotation = 0.0f;  // degrees about +y, counter-clockwise seen from above
    glm::vec3 color{1.0f};  // a constant environment's colour (no map)
    // A map: its path (for messages), size and linear RGB texels, row 0 at
    // the top (v = 0); empty for a constant environment.
    std::string map;
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> texels;
};

enum class LampType : unsigned { point, spot, sun };

// The sun's angular diameter unless a scene says otherwise: the real sun's.
const float default_sun_angle = 0.53f;

struct Lamp {
    LampType type = LampType::point;
    glm::vec3 position{0.0f};  // point and spot
    // Spot: where its cone points; sun: towards the sun. Unit.
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec3 color{1.0f};
    // Point and spot: intensity in W/sr (times color; a spot's on its
    // axis); sun: irradiance in W/m^2 on a surface facing it.
    float power = 1.0f;
    // Degrees. Spot: the cone's full angle; sun: its angular diameter (0:
    // a single direction).
    float angle = 0.0f;
    float blend = 0.0f;  // spot: the share of the cone's half-angle its edge fades over
};

// "point", "spot", "sun" and back; parse_lamp_type throws
// std::invalid_argument.
const char* to_string(LampType type);
LampType parse_lamp_type(const std::string& name);
std::vector<std::string> lamp_type_names();

// The most texels an environment map may have (2^25: 8192 x 4096, which
// the packed scene holds in 512 MiB), and the most on a side.
const long long max_environment_texels = 1ll << 25;
const int max_environment_side = 16384;

// Reads an environment map: .exr (tinyexr, the library's OpenEXR reader)
// or .hdr (Radiance RGBE, flat or run-length encoded: lights.cpp's own
// reader), by the extension in any case. Throws std::runtime_error naming
// the file: unreadable, another format, too large, truncated, or a texel
// that is negative or not finite (with its position).
Environment read_environment_map(const std::string& path);

}  // namespace trac0r

#endif
