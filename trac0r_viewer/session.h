// The window's session: its event loop, input, and what it shows, over a
// RenderWorker. Internal to the viewer: window_session.cpp runs it (the
// window, the frames, the screenshots), session_camera.cpp holds its
// camera's movement and keys.
#ifndef TRAC0R_VIEWER_SESSION_H
#define TRAC0R_VIEWER_SESSION_H

#include "messages.h"
#include "options.h"
#include "overlay.h"
#include "replay.h"
#include "window.h"
#include "window_worker.h"

#include "trac0r/camera.h"
#include "trac0r/geometry.h"
#include "trac0r/view_transform.h"

#include <SDL.h>

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace trac0r_viewer {

// How long after a drag's last motion the view still counts as moving
// (Session::move): longer than the gaps between a moving mouse's events.
constexpr std::uint32_t drag_hold_ms = 250;

class Session {
  public:
    Session(const Options& options, Window& window, const Font& font,
            std::unique_ptr<trac0r::Renderer> renderer,
            const RenderWorker::BackendFactory& make_backend, std::vector<ReplayCommand> replay);
    int run();

  private:
    void handle(const SDL_Event& e);
    void handle_key(const SDL_KeyboardEvent& key);
    bool held(SDL_Keycode key) const { return held_.count(key) != 0; }
    // The held movement keys' direction: x right, y up, z forward; 0: none.
    glm::vec3 move_direction() const;
    // Moves the camera by the held keys over `seconds`, and tells the
    // render thread whether the view is moving (keys, or a drag whose
    // last motion is under drag_hold_ms before now_ms).
    void move(float seconds, std::uint32_t now_ms);
    void change_camera(const trac0r::Camera& camera);
    // The camera keys: C prints the camera block, Home returns to the
    // starting camera, [ and ] close and open the aperture, G (or the
    // middle button) focuses on the surface under the mouse.
    bool handle_camera_key(SDL_Keycode k);
    void focus_under_mouse();
    // A new window size: once it stays put, the render follows it.
    void follow_window_size(std::uint32_t now);
    void take_from_worker();
    // What the window shows of shown_: the filtered image where there is
    // one and the filter is on (F off shows the unfiltered one at once).
    const trac0r::Image& shown_image() const {
        return filter_ && !shown_.filtered.pixels.empty() ? shown_.filtered : shown_.image;
    }
    void set_filter(bool on);
    // Tone maps shown_image() into the window, with the exposure and view.
    void show_image();
    long shown_spp() const;
    void draw();
    OverlayFigures figures() const;
    void save_screenshot();
    // `text` goes to stderr and, unless `shown` is given, to the window,
    // where it replaces the message of the same `kind` (MessageList).
    void say(const std::string& text, const std::string& shown = "", const std::string& kind = "");

    const Options& options_;
    Window& window_;
    const Font& font_;
    std::vector<trac0r::AABB> boxes_;
    std::size_t triangles_;
    float scene_size_;
    trac0r::Camera camera_;
    const trac0r::Camera start_camera_;   // the scene's (or --camera's): Home
    const glm::dvec3 origin_;             // the scene's, for printing positions
    std::uint64_t focus_generation_ = 0;  // of the last focus request; 0: none waiting
    std::uint32_t frame_event_;
    std::unique_ptr<RenderWorker> worker_;  // after everything it may call
    ReplayPlayer replay_;
    bool replaying_;

    std::uint64_t requested_generation_ = 0;
    WorkerFrame shown_;  // the frame on screen
    bool have_frame_ = false;
    trac0r::Image last_full_image_;  // for --output at the end
    float exposure_;
    trac0r::ViewTransform view_;  // V; at first --view, else the scene's render.view
    // --output's PNGs get the first view, as they get --exposure, not + / -.
    trac0r::ViewTransform saved_view_;
    bool overlay_ = false;
    bool filter_ = false;  // the display filter (F, --filter)
    bool help_ = false;
    bool screenshot_requested_ = false;
    bool quit_ = false;
    bool dirty_ = true;
    std::set<SDL_Keycode> held_;   // from events, so replayed keys count too
    bool moving_ = false;          // what move() last told the worker
    bool looking_ = false;         // right button held
    std::uint32_t looked_ms_ = 0;  // SDL_GetTicks() of its last motion that turned the view
    int mouse_x_ = -1;
    int mouse_y_ = -1;
    MessageList messages_;
    int window_width_ = 0;  // the drawable size last seen, in pixels
    int window_height_ = 0;
    bool resize_pending_ = false;  // the window's size changed; the render's not yet
    std::uint32_t resize_at_ms_ = 0;
    std::uint64_t resize_generation_ = 0;  // of the last resize request; 0: none waiting
    int resize_width_ = 0;                 // its size
    int resize_height_ = 0;
};

}  // namespace trac0r_viewer

#endif
