// The view transform: how linear radiance becomes the display values a
// screen shows (the window, PNG files). `standard` clips each channel at 1;
// `filmic` is AgX, as Blender 4 ships it, which rolls highlights off
// smoothly and desaturates them towards white. PFM and EXR files hold the
// radiance itself and never pass through a view transform.
#ifndef TRAC0R_VIEW_TRANSFORM_H
#define TRAC0R_VIEW_TRANSFORM_H

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace trac0r {

enum class ViewTransform { standard, filmic };

// "standard", "filmic" and back; parse_view_transform throws
// std::invalid_argument naming the names it knows.
const char* to_string(ViewTransform view);
ViewTransform parse_view_transform(const std::string& name);
std::vector<std::string> view_transform_names();

// Linear radiance (the exposure already applied) to linear display values
// in [0, 1], before the sRGB encoding. A channel that is negative or NaN
// counts as 0. `standard`: each channel clamped to [0, 1]. `filmic`: AgX
// (view_transform.cpp): 0 stays 0, a grey ramp never falls, and every
// colour tends to the same white, about 0.997, as it brightens. Along k
// times a colour a channel can dip, by less than 1e-6 near black or from
// above that white down to it, never by an 8-bit step.
glm::vec3 apply_view(ViewTransform view, const glm::vec3& radiance);

}  // namespace trac0r

#endif
