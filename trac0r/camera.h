// The camera of a scene: a pinhole, or a thin lens (depth of field).
#ifndef TRAC0R_CAMERA_H
#define TRAC0R_CAMERA_H

#include "trac0r/kernel_fwd.h"

#include <glm/glm.hpp>

#include <string>

namespace trac0r {

// How a camera forms its image: from a point (a pinhole or a thin lens), or
// with parallel rays (orthographic: no perspective, as an architect's
// elevation or glTF's orthographic camera).
enum class Projection { perspective = 0, orthographic = 1 };

struct Camera {
    glm::vec3 position{0.0f, 0.31f, 1.2f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 world_up{0.0f, 1.0f, 0.0f};
    Projection projection = Projection::perspective;
    float vertical_fov = 53.13f;  // degrees, a true field of view (perspective)
    // Orthographic: the height in metres of what the image shows (glTF's
    // 2 * ymag); its width follows from the image's aspect.
    float view_height = 2.0f;
    // A thin lens: the radius of its aperture in metres (0: a pinhole, all
    // in focus) and the distance along `direction` of the plane in focus.
    float aperture_radius = 0.0f;
    float focus_distance = 1.0f;
};

// Why a camera cannot form an image, or nullptr when it can: a zero or
// non-finite vector, direction parallel to world_up, fov outside (0, 180),
// a view height not positive and finite, a negative or non-finite
// aperture, a focus distance not positive.
const char* camera_problem(const Camera& camera);

// The camera as a scene file's block, on one line:
// {"camera": {"position": [...], ...}}, every key of its projection
// (perspective: vertical_fov; orthographic: projection and view_height),
// each number with the
// digits that read back to the same float; `origin` is the scene's
// (Scene::origin), added back to the position.
std::string camera_block_json(const Camera& camera, const glm::dvec3& origin);

// The kernel's view of the camera for a width x height image. Throws
// std::invalid_argument when camera_problem() reports one.
kernel::CameraRecord make_camera_record(const Camera& camera, int width, int height);

}  // namespace trac0r

#endif
