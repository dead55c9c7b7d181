#include "session.h"

#include "trac0r/fly_camera.h"

#include <glm/glm.hpp>

namespace trac0r_viewer {

glm::vec3 Session::move_direction() const {
    glm::vec3 direction(0.0f);  // x right, y up, z forward
    direction.z += held(SDLK_w) ? 1.0f : 0.0f;
    direction.z -= held(SDLK_s) ? 1.0f : 0.0f;
    direction.x += held(SDLK_d) ? 1.0f : 0.0f;
    direction.x -= held(SDLK_a) ? 1.0f : 0.0f;
    direction.y += (held(SDLK_e) || held(SDLK_SPACE)) ? 1.0f : 0.0f;
    direction.y -= (held(SDLK_q) || held(SDLK_LCTRL) || held(SDLK_RCTRL)) ? 1.0f : 0.0f;
    return direction;
}

void Session::move(float seconds) {
    const glm::vec3 direction = move_direction();
    if (direction == glm::vec3(0.0f) || seconds <= 0.0f) {
        return;
    }
    // A quarter of the scene's diagonal per second; Shift five times that.
    const float fast = (held(SDLK_LSHIFT) || held(SDLK_RSHIFT)) ? 5.0f : 1.0f;
    const float distance = 0.25f * scene_size_ * fast * seconds;
    change_camera(trac0r::move_camera(camera_, glm::normalize(direction) * distance));
}

void Session::change_camera(const trac0r::Camera& camera) {
    camera_ = camera;
    requested_generation_ = worker_->set_camera(camera_);
    dirty_ = dirty_ || overlay_;  // the wireframes follow at once
}

}  // namespace trac0r_viewer
