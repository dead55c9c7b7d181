// A glTF file's own view of itself, from its JSON: its first camera and
// its lights (KHR_lights_punctual), where its nodes place them, for the
// scene made around a model opened on its own (model_scene.h).
#ifndef TRAC0R_GLTF_VIEW_H
#define TRAC0R_GLTF_VIEW_H

#include "trac0r/lights.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace trac0r {

struct GltfView {
    // The first camera of the default scene's nodes (depth first): where
    // its node puts it, looking along the node's -z with its +y up, as
    // glTF defines a camera.
    bool has_camera = false;
    bool orthographic = false;
    glm::dvec3 position{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double vertical_fov = 45.0;  // degrees (glTF's yfov), perspective
    double view_height = 2.0;    // metres (2 * glTF's ymag), orthographic
    // Its aspectRatio, or xmag / ymag; 0: not given.
    double aspect = 0.0;
    // The nodes' KHR_lights_punctual lights as lamps: point and spot
    // (their intensity in candela as W/sr, over 683 lm/W, as Blender's
    // importer converts), directional as a sun (lux as W/m^2, the same
    // way; a single direction). A spot's cone: its outer angle, the edge
    // fading from its inner one.
    std::vector<Lamp> lamps;
};

// The view in a glTF's JSON text (gltf_json_text); none where it cannot
// be read (assimp refuses it first). Throws std::runtime_error naming
// the file and what for a light or camera whose numbers are not finite
// or out of range.
GltfView gltf_view(const std::string& json_text, const std::string& path);

}  // namespace trac0r

#endif
