#include "session.h"

#include "trac0r/fly_camera.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace trac0r_viewer {

bool Session::handle_camera_key(SDL_Keycode k) {
    switch (k) {
    case SDLK_c: {
        const std::string block = trac0r::camera_block_json(camera_, origin_);
        std::printf("%s\n", block.c_str());
        std::fflush(stdout);
        say("camera (printed to stdout; load it with --camera FILE.json):\n" + block, "",
            "camera");
        return true;
    }
    case SDLK_HOME:
        change_camera(start_camera_);
        say("back to the scene's camera", "", "camera");
        return true;
    case SDLK_LEFTBRACKET:
    case SDLK_RIGHTBRACKET: {
        // Half a stop of aperture per press; opening a pinhole starts at a
        // five-hundredth of the scene's size, closing below it is a pinhole.
        trac0r::Camera c = camera_;
        const float smallest = 0.002f * scene_size_;
        if (k == SDLK_RIGHTBRACKET) {
            c.aperture_radius = std::max(smallest, c.aperture_radius * std::sqrt(2.0f));
        } else {
            c.aperture_radius /= std::sqrt(2.0f);
            c.aperture_radius = c.aperture_radius < smallest ? 0.0f : c.aperture_radius;
        }
        change_camera(c);
        char text[128];
        std::snprintf(text, sizeof text,
                      c.aperture_radius > 0.0f ? "aperture radius %.3g m, focus at %.3g m"
                                               : "aperture closed: a pinhole, all in focus",
                      c.aperture_radius, c.focus_distance);
        say(text, "", "aperture");
        return true;
    }
    case SDLK_g:
        focus_under_mouse();
        return true;
    default:
        return false;
    }
}

void Session::focus_under_mouse() {
    float x = 0.0f;
    float y = 0.0f;
    if (!window_.window_to_render(mouse_x_, mouse_y_, &x, &y)) {
        say("focus: point the mouse at the surface to focus on", "", "focus");
        return;
    }
    focus_generation_ = requested_generation_ =
        worker_->focus_at(static_cast<int>(x), static_cast<int>(y));
}

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

void Session::move(float seconds, std::uint32_t now_ms) {
    const glm::vec3 direction = move_direction();
    const bool keys_move = direction != glm::vec3(0.0f);
    // A drag's motion events come a few milliseconds apart; a pause as long
    // as drag_hold_ms ends the move, though the button is still held.
    const bool moving = keys_move || (looking_ && now_ms - looked_ms_ < drag_hold_ms);
    if (moving != moving_) {
        // While the view moves, the thread renders previews only.
        moving_ = moving;
        requested_generation_ = worker_->set_moving(moving);
    }
    if (!keys_move || seconds <= 0.0f) {
        return;
    }
    // A quarter of the scene's diagonal per second; Shift five times that,
    // Alt a fifth (as Blender's walk navigation).
    const float fast = (held(SDLK_LSHIFT) || held(SDLK_RSHIFT)) ? 5.0f : 1.0f;
    const float slow = (held(SDLK_LALT) || held(SDLK_RALT)) ? 0.2f : 1.0f;
    const float distance = 0.25f * scene_size_ * fast * slow * seconds;
    change_camera(trac0r::move_camera(camera_, glm::normalize(direction) * distance));
}

void Session::change_camera(const trac0r::Camera& camera) {
    camera_ = camera;
    requested_generation_ = worker_->set_camera(camera_);
    dirty_ = dirty_ || overlay_;  // the wireframes follow at once
}

}  // namespace trac0r_viewer
