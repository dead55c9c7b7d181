#include "window_session.h"

#include "headless.h"
#include "screenshot_name.h"
#include "session.h"

#include "trac0r/fly_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

namespace trac0r_viewer {

namespace {

// How long the window's size must stay put before the render follows it:
// a drag of the window's edge re-renders once, at the end.
constexpr std::uint32_t resize_debounce_ms = 200;

// How far the camera moves per second, and the overlay's near plane: both
// follow the scene's size, so a scene in millimetres behaves like one in
// metres.
float scene_size(const std::vector<trac0r::AABB>& boxes) {
    trac0r::AABB all;
    for (const trac0r::AABB& b : boxes) {
        all.extend(b);
    }
    return all.empty() ? 1.0f : std::max(1e-6f, glm::length(all.max - all.min));
}

}  // namespace

Session::Session(const Options& options, Window& window, const Font& font,
                 std::unique_ptr<trac0r::Renderer> renderer,
                 const RenderWorker::BackendFactory& make_backend,
                 std::vector<ReplayCommand> replay)
    : options_(options),
      window_(window),
      font_(font),
      triangles_(renderer->packed().triangles.size()),
      camera_(renderer->scene().camera),
      start_camera_(camera_),
      origin_(renderer->scene().origin),
      frame_event_(SDL_RegisterEvents(1)),
      replay_(std::move(replay), options.replay_path),
      replaying_(!options.replay_path.empty()),
      exposure_(options.exposure),
      view_(renderer->scene().render.view),
      saved_view_(view_) {
    for (const trac0r::Shape& shape : renderer->scene().shapes) {
        boxes_.push_back(shape.aabb);
    }
    scene_size_ = scene_size(boxes_);
    // A large render opens scaled down to fit the screen: only a change of
    // this size is the user's resize.
    window_.output_size(&window_width_, &window_height_);
    WorkerSettings settings;
    settings.seed = options.seed;
    settings.pack = pack_options(options);
    settings.stop.spp = options.spp;
    settings.stop.seconds = options.seconds;
    settings.stop.target_error = options.target_error;
    const std::uint32_t event_type = frame_event_;
    worker_ = std::make_unique<RenderWorker>(std::move(renderer), make_backend, settings, [=] {
        // Wakes the event loop at once; SDL_PushEvent may be called from any thread.
        SDL_Event e;
        SDL_zero(e);
        e.type = event_type;
        SDL_PushEvent(&e);
    });
    if (options.filter) {
        set_filter(true);
    }
}

void Session::show_image() {
    window_.set_image(trac0r::tonemap_image(shown_image(), exposure_, view_));
}

void Session::set_filter(bool on) {
    filter_ = on;
    if (have_frame_) {
        show_image();
    }
    requested_generation_ = worker_->set_filter(on);
    say(on ? "filter on: edge-preserving, for display only (the accumulation is untouched)"
           : "filter off",
        "", "filter");
    dirty_ = true;
}

int Session::run() {
    std::uint32_t last_ms = SDL_GetTicks();
    while (!quit_) {
        // Block until input or a frame arrives; tick often only while keys
        // move the camera, a drag's hold runs, or a replay waits for its
        // time.
        const bool busy = replaying_ || !held_.empty() || (looking_ && moving_) ||
                          !messages_.empty() || resize_pending_;
        SDL_Event e;
        if (SDL_WaitEventTimeout(&e, busy ? 10 : 250)) {
            handle(e);
            // A screenshot shows the window as it was when P was pressed:
            // the events after it wait for the next round.
            while (!quit_ && !screenshot_requested_ && SDL_PollEvent(&e)) {
                handle(e);
            }
        }
        const std::uint32_t now = SDL_GetTicks();
        // A stall (a window drag, a slow draw) must not throw the camera far.
        move(std::min(0.1f, (now - last_ms) / 1000.0f), now);
        last_ms = now;
        follow_window_size(now);
        take_from_worker();
        const std::string failure = worker_->failure();
        if (!failure.empty()) {
            std::fprintf(stderr, "trac0r_viewer: error: rendering stopped: %s\n", failure.c_str());
            return 1;
        }
        if (replaying_) {
            replay_.step(window_.id(), now, shown_spp());
            replaying_ = !replay_.finished();
        }
        dirty_ = messages_.expire(now) || dirty_;
        if (dirty_ || screenshot_requested_) {
            draw();
        }
    }
    window_.hide();  // the window goes at once; the frame in flight may take a while
    if (!options_.outputs.empty()) {
        if (last_full_image_.pixels.empty()) {
            std::fprintf(stderr,
                         "trac0r_viewer: --output: no frame had finished yet; nothing "
                         "saved\n");
            return 1;
        }
        save_outputs(last_full_image_, options_, saved_view_);
    }
    return 0;
}

void Session::handle(const SDL_Event& e) {
    if (replay_.handled(e)) {
        return;  // --replay's events before it are handled: its next wait may start
    }
    switch (e.type) {
    case SDL_QUIT:
        quit_ = true;
        break;
    case SDL_WINDOWEVENT:
        if (e.window.event == SDL_WINDOWEVENT_FOCUS_LOST) {
            held_.clear();  // the key-up events will go elsewhere
            looking_ = false;
        }
        dirty_ = true;
        break;
    case SDL_RENDER_TARGETS_RESET:
    case SDL_RENDER_DEVICE_RESET:
        if (have_frame_) {
            show_image();
        }
        dirty_ = true;
        break;
    case SDL_KEYDOWN:
        held_.insert(e.key.keysym.sym);
        handle_key(e.key);
        break;
    case SDL_KEYUP:
        held_.erase(e.key.keysym.sym);
        break;
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP:
        if (e.button.button == SDL_BUTTON_RIGHT) {
            looking_ = e.type == SDL_MOUSEBUTTONDOWN;
        }
        if (e.button.button == SDL_BUTTON_MIDDLE && e.type == SDL_MOUSEBUTTONDOWN) {
            mouse_x_ = e.button.x;
            mouse_y_ = e.button.y;
            focus_under_mouse();
        }
        break;
    case SDL_MOUSEMOTION: {
        mouse_x_ = e.motion.x;
        mouse_y_ = e.motion.y;
        dirty_ = dirty_ || overlay_;
        if (looking_ && (e.motion.xrel != 0 || e.motion.yrel != 0)) {
            // The scene follows the pointer: one window pixel turns the view
            // by one pixel's share of the field of view.
            const float radians_per_pixel =
                glm::radians(camera_.vertical_fov) / std::max(1, window_.image_rect().h);
            looked_ms_ = SDL_GetTicks();
            move(0.0f, looked_ms_);  // previews from this motion on
            change_camera(trac0r::turn_camera(camera_, e.motion.xrel * radians_per_pixel,
                                              -e.motion.yrel * radians_per_pixel));
        }
        break;
    }
    case SDL_MOUSEWHEEL: {
        const int notches = e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e.wheel.y : e.wheel.y;
        if (notches != 0) {
            // Away from the user zooms in: a narrower field of view.
            change_camera(
                trac0r::zoom_camera(camera_, std::pow(0.9f, static_cast<float>(notches))));
        }
        break;
    }
    default:
        break;
    }
}

void Session::handle_key(const SDL_KeyboardEvent& key) {
    const SDL_Keycode k = key.keysym.sym;
    if (k == SDLK_PLUS || k == SDLK_EQUALS || k == SDLK_KP_PLUS || k == SDLK_MINUS ||
        k == SDLK_KP_MINUS) {
        // Half a stop per press; held keys repeat.
        const bool up = k == SDLK_PLUS || k == SDLK_EQUALS || k == SDLK_KP_PLUS;
        exposure_ *= up ? std::sqrt(2.0f) : 1.0f / std::sqrt(2.0f);
        if (have_frame_) {
            show_image();
        }
        char text[64];
        std::snprintf(text, sizeof text, "exposure %.3g", exposure_);
        say(text, "", "exposure");
        return;
    }
    if (key.repeat) {
        return;  // toggles and actions: once per press
    }
    if (handle_camera_key(k)) {
        return;
    }
    switch (k) {
    case SDLK_ESCAPE:
        quit_ = true;
        break;
    case SDLK_F1:
        overlay_ = !overlay_;
        dirty_ = true;
        break;
    case SDLK_f:
        set_filter(!filter_);
        break;
    case SDLK_v:
        view_ = view_ == trac0r::ViewTransform::standard ? trac0r::ViewTransform::filmic
                                                         : trac0r::ViewTransform::standard;
        if (have_frame_) {
            show_image();
        }
        say(view_ == trac0r::ViewTransform::filmic
                ? "view filmic: AgX, highlights roll off to white (for display only)"
                : "view standard: each channel clipped at 1",
            "", "view");
        break;
    case SDLK_h:
        help_ = !help_;
        dirty_ = true;
        break;
    case SDLK_p:
        if (have_frame_) {
            screenshot_requested_ = true;
        } else {
            say("no image yet: the first frame is still rendering");
        }
        break;
    case SDLK_r:
        requested_generation_ = worker_->restart();
        say("accumulation restarted");
        break;
    case SDLK_b: {
        const std::string current = have_frame_ ? shown_.backend : options_.backend;
        const std::string other = current == "cpu" ? "opencl" : "cpu";
        requested_generation_ = worker_->switch_backend(other);
        say("switching to the " + other + " backend...");
        break;
    }
    default:
        break;
    }
}

void Session::follow_window_size(std::uint32_t now) {
    int width = 0;
    int height = 0;
    window_.output_size(&width, &height);
    if (width <= 0 || height <= 0) {
        return;  // minimised
    }
    if (width != window_width_ || height != window_height_) {
        window_width_ = width;
        window_height_ = height;
        resize_pending_ = true;
        resize_at_ms_ = now + resize_debounce_ms;
        dirty_ = true;
    }
    if (!resize_pending_ || now < resize_at_ms_) {
        return;
    }
    resize_pending_ = false;
    // The window's pixels, one render pixel each (no smaller than a tile
    // or two: a window squeezed to nothing still renders something).
    const int w = std::max(16, width);
    const int h = std::max(16, height);
    // Against the size last asked for: a window dragged back to its
    // render's size while another size is still on its way must ask again.
    const bool waiting = resize_generation_ != 0;
    if (w == (waiting ? resize_width_ : window_.render_width()) &&
        h == (waiting ? resize_height_ : window_.render_height())) {
        return;
    }
    resize_width_ = w;
    resize_height_ = h;
    resize_generation_ = requested_generation_ = worker_->resize(w, h);
    say("rendering at " + std::to_string(w) + " x " + std::to_string(h) + " (the window's size)",
        "", "resize");
}

void Session::take_from_worker() {
    WorkerFrame frame;
    if (worker_->take_frame(&frame)) {
        shown_ = std::move(frame);
        have_frame_ = true;
        if (focus_generation_ != 0 && shown_.generation >= focus_generation_) {
            // The worker found the depth: the camera keeps it from now on.
            camera_.focus_distance = shown_.focus_distance;
            focus_generation_ = 0;
        }
        if (resize_generation_ != 0 && shown_.generation >= resize_generation_) {
            // The first frame at the new size: the window maps it 1:1.
            window_.set_render_size(resize_width_, resize_height_);
            resize_generation_ = 0;
        }
        show_image();
        if (!shown_.preview) {
            last_full_image_ = shown_.accumulation;
        }
        dirty_ = true;
    }
    for (const std::string& m : worker_->take_messages()) {
        say(m);
    }
}

// What --replay's wait_spp waits for: the newest view, at full resolution.
long Session::shown_spp() const {
    // While a movement key is held the view moves every tick: a frame of
    // the camera of one tick (two ticks in one millisecond move nothing)
    // is not the view the user is heading for.
    const bool current = have_frame_ && !shown_.preview && !resize_pending_ &&
                         move_direction() == glm::vec3(0.0f) &&
                         shown_.generation == requested_generation_;
    return current ? static_cast<long>(shown_.spp) : 0;
}

void Session::say(const std::string& text, const std::string& shown, const std::string& kind) {
    std::fprintf(stderr, "%s\n", text.c_str());
    messages_.add(shown.empty() ? text : shown, kind, SDL_GetTicks() + 4000);
    dirty_ = true;
}

OverlayFigures Session::figures() const {
    OverlayFigures f;
    f.frame_seconds = shown_.frame_seconds;
    f.accumulation_seconds = shown_.accumulation_seconds;
    f.integrator = options_.integrator;
    f.filter = filter_;
    f.pixels = static_cast<long>(shown_.image.width) * shown_.image.height;
    f.spp = shown_.spp;
    f.relative_mse = shown_.relative_mse;
    f.relative_mse_spp = shown_.relative_mse_spp;
    f.paused_by = shown_.paused_by;
    f.estimate_overflowed = shown_.estimate_overflowed;
    f.preview_factor =
        shown_.preview ? window_.render_width() / std::max(1, shown_.image.width) : 0;
    f.backend = have_frame_ ? shown_.backend : options_.backend;
    f.device = have_frame_ ? shown_.device : "(first frame rendering)";
    f.triangles = triangles_;
    f.shapes = boxes_.size();
    f.width = window_.render_width();
    f.height = window_.render_height();
    f.camera = camera_;
    f.exposure = exposure_;
    f.view = trac0r::to_string(view_);
    float x = 0.0f;
    float y = 0.0f;
    f.mouse_in_image = have_frame_ && window_.window_to_render(mouse_x_, mouse_y_, &x, &y);
    if (f.mouse_in_image) {
        f.mouse_x = static_cast<int>(x);
        f.mouse_y = static_cast<int>(y);
        // A preview is smaller: the same spot of it.
        const int ix =
            std::min(shown_.image.width - 1, static_cast<int>(x * shown_.image.width / f.width));
        const int iy =
            std::min(shown_.image.height - 1, static_cast<int>(y * shown_.image.height / f.height));
        f.mouse_radiance = shown_image().at(ix, iy);
    }
    return f;
}

void Session::draw() {
    window_.draw_image();
    int panels_bottom = 0;  // the help goes below the overlay's text, never over it
    if (overlay_) {
        draw_wireframes(window_, boxes_, camera_, 1e-4f * scene_size_);
        panels_bottom = 8 + font_.draw_panel(window_.renderer(), overlay_text(figures()), 8, 8);
    }
    // The screenshot is the image as shown with the overlay, without the
    // help and the messages, which only talk about the window.
    if (screenshot_requested_) {
        screenshot_requested_ = false;
        save_screenshot();
    }
    if (help_) {
        // What fits between the overlay and the bottom edge (a small
        // window gets the short list, cut where it must be).
        int out_w = 0;
        int out_h = 0;
        window_.output_size(&out_w, &out_h);
        const std::string help = fitting_help(font_, out_w - 16, out_h - panels_bottom - 16);
        if (!help.empty()) {
            font_.draw_panel(window_.renderer(), help, -8, panels_bottom + 8);
        }
    }
    if (!messages_.empty()) {
        font_.draw_panel(window_.renderer(), messages_.text(), 8, -8);
    }
    window_.present();
    dirty_ = false;
}

void Session::save_screenshot() {
    const std::string base = unused_screenshot_base();
    const std::string png = base + ".png";
    const std::string pfm = base + ".pfm";
    try {
        trac0r::write_png(png, window_.read_image_area());
        // The render itself: the running mean, not the display's blend.
        trac0r::write_pfm(pfm, shown_.preview ? shown_.image : shown_.accumulation);
    } catch (const std::exception& e) {
        say(std::string("screenshot failed: ") + e.what());
        return;
    }
    const char* preview = shown_.preview ? ", low-resolution preview" : "";
    char text[8192];
    std::snprintf(text, sizeof text, "screenshot: %s and %s (%u spp%s)", png.c_str(), pfm.c_str(),
                  shown_.spp, preview);
    // Full paths do not fit in a small window: the name, then the directory.
    const std::size_t slash = base.rfind('/');
    char shown[8192];
    std::snprintf(shown, sizeof shown, "screenshot: %s.png and .pfm (%u spp%s)\nin %s",
                  base.substr(slash + 1).c_str(), shown_.spp, preview,
                  slash == std::string::npos ? "." : base.substr(0, slash).c_str());
    say(text, shown);
}

int run_window(const Options& options, const std::string& title,
               const trac0r::RenderSettings& render, const RendererFactory& make_renderer,
               const RenderWorker::BackendFactory& make_backend) {
    std::vector<ReplayCommand> replay;
    if (!options.replay_path.empty()) {
        replay = load_replay(options.replay_path);
        check_replay_reachable(replay, options.replay_path, options.spp);
    }
    const bool benchmark = options.benchmark_frames > 0;
    // The benchmark shows only the image: no text, no font needed.
    std::unique_ptr<Font> font;
    if (!benchmark) {
        const int point_size = std::max(10, std::min(15, render.height / 40));
        font = std::make_unique<Font>(overlay_font_path(), point_size);
    }
    Window window(title, render.width, render.height, !benchmark);
    std::unique_ptr<trac0r::Renderer> renderer = make_renderer();
    if (benchmark) {
        return run_benchmark(*renderer, options, [&] {
            window.set_image(trac0r::tonemap_image(renderer->image(), options.exposure,
                                                   renderer->scene().render.view));
            window.draw_image();
            window.present();
            SDL_Event e;
            while (SDL_PollEvent(&e)) {
                if (e.type == SDL_QUIT ||
                    (e.type == SDL_KEYDOWN && e.key.keysym.sym == SDLK_ESCAPE)) {
                    return false;
                }
            }
            return true;
        });
    }
    Session session(options, window, *font, std::move(renderer), make_backend, std::move(replay));
    return session.run();
}

}  // namespace trac0r_viewer
