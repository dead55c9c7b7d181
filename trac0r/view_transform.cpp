#include "trac0r/view_transform.h"

#include "trac0r/enum_names.h"

#include <algorithm>
#include <cmath>

namespace trac0r {

namespace {

const EnumName<ViewTransform> view_names[] = {{ViewTransform::standard, "standard"},
                                              {ViewTransform::filmic, "filmic"}};

// Negative and NaN count as 0 (the comparison is false for NaN).
float non_negative(float v) { return v > 0.0f ? v : 0.0f; }

// ---- AgX --------------------------------------------------------------------
//
// The minimal AgX of three.js (`AgXToneMapping` in
// src/renderers/shaders/ShaderChunk/tonemapping_pars_fragment.glsl.js,
// r160 and later), which follows Filament's port of Blender's AgX
// (github.com/google/filament/pull/7236) and takes its sigmoid from
// Benjamin Wrensch's polynomial fit (iolite-engine.com/blog_posts/
// minimal_agx_implementation). Blender's AgX (Troy Sobotka's,
// github.com/sobotka/AgX) works in Rec.2020 primaries: the "inset" matrix
// pulls every colour a little towards the achromatic axis, so that a
// saturated colour's weaker channels grow along with its strongest one and
// the colour goes to white as it brightens instead of clipping to a
// primary; each channel is then encoded as log2 around middle grey
// (0.18 x 2^-10 to 0.18 x 2^6.5), shaped by the sigmoid, and the "outset"
// matrix gives back part of the saturation.
//
// The matrices are written row by row here (three.js writes GLSL mat3s,
// column by column): the same numbers, transposed.

using Matrix = float[3][3];

glm::vec3 times(const Matrix& m, const glm::vec3& v) {
    return glm::vec3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                     m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                     m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

// Linear sRGB (Rec.709 primaries) to linear Rec.2020 and back, rounded to
// four digits as three.js has them (ITU-R BT.2407).
// clang-format off
const Matrix srgb_to_rec2020 = {{0.6274f, 0.3293f, 0.0433f},
                                {0.0691f, 0.9195f, 0.0113f},
                                {0.0164f, 0.0880f, 0.8956f}};
const Matrix rec2020_to_srgb = {{ 1.6605f, -0.5876f, -0.0728f},
                                {-0.1246f,  1.1329f, -0.0083f},
                                {-0.0182f, -0.1006f,  1.1187f}};
const Matrix agx_inset = {{0.856627153315983f,  0.0951212405381588f, 0.0482516061458583f},
                          {0.137318972929847f,  0.761241990602591f,  0.101439036467562f},
                          {0.11189821299995f,   0.0767994186031903f, 0.811302368396859f}};
const Matrix agx_outset = {{ 1.1271005818144368f,  -0.11060664309660323f, -0.016493938717834573f},
                           {-0.1413297634984383f,   1.157823702216272f,   -0.016493938717834257f},
                           {-0.14132976349843826f, -0.11060664309660294f,  1.2519364065950405f}};
// clang-format on

// log2(0.18 x 2^-10) and log2(0.18 x 2^6.5): the range of exposures the
// curve spans, 16.5 stops, middle grey 10 stops above its foot.
const float agx_min_ev = -12.47393f;
const float agx_max_ev = 4.026069f;

// The sigmoid on the log encoding x in [0, 1]: rising throughout, from
// -0.00232 at 0 (the black below which every channel is 0) to 0.99858 at 1.
float agx_sigmoid(float x) {
    const float x2 = x * x;
    const float x4 = x2 * x2;
    return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 +
           0.1191f * x - 0.00232f;
}

glm::vec3 agx(const glm::vec3& radiance) {
    glm::vec3 c = times(agx_inset, times(srgb_to_rec2020, radiance));
    for (int i = 0; i < 3; ++i) {
        // Below 1e-10 as 1e-10: log2 of 0 would be -infinity (both clamp to
        // the curve's foot anyway).
        const float ev = std::log2(std::max(c[i], 1e-10f));
        const float x =
            std::min(1.0f, std::max(0.0f, (ev - agx_min_ev) / (agx_max_ev - agx_min_ev)));
        c[i] = agx_sigmoid(x);
    }
    c = times(agx_outset, c);
    // The sigmoid's output is display-encoded with a 2.2 power: back to
    // linear, then to sRGB primaries.
    for (int i = 0; i < 3; ++i) {
        c[i] = std::pow(std::max(c[i], 0.0f), 2.2f);
    }
    c = times(rec2020_to_srgb, c);
    // What lies outside the sRGB gamut after that (a little, for the most
    // saturated colours) is clamped, as three.js and Filament do.
    return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f));
}

}  // namespace

const char* to_string(ViewTransform view) { return enum_name(view_names, view, "standard"); }

ViewTransform parse_view_transform(const std::string& name) {
    return enum_value(view_names, name, "view transform");
}

std::vector<std::string> view_transform_names() { return enum_names(view_names); }

glm::vec3 apply_view(ViewTransform view, const glm::vec3& radiance) {
    const glm::vec3 v(non_negative(radiance.x), non_negative(radiance.y), non_negative(radiance.z));
    if (view == ViewTransform::filmic) {
        return agx(v);
    }
    return glm::min(v, glm::vec3(1.0f));
}

}  // namespace trac0r
