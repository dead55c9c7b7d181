#include "window.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <sys/stat.h>

namespace trac0r_viewer {

namespace {

std::string sdl_error() {
    const char* e = SDL_GetError();
    return e && *e ? e : "unknown SDL error";
}

const char* const no_display_advice =
    "; to render without a window use --headless (with --output FILE or --benchmark N)";

bool is_set(const char* variable) {
    const char* value = std::getenv(variable);
    return value && *value;
}

// Whether WAYLAND_DISPLAY names a socket that exists (an absolute path, or
// a name in XDG_RUNTIME_DIR): where it does not, libwayland prints its own
// error lines before SDL gives up on it.
bool wayland_socket_exists() {
    const std::string name = std::getenv("WAYLAND_DISPLAY");
    std::string path = name;
    if (name[0] != '/') {
        if (!is_set("XDG_RUNTIME_DIR")) {
            return false;
        }
        path = std::string(std::getenv("XDG_RUNTIME_DIR")) + "/" + name;
    }
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISSOCK(st.st_mode);
}

// Without a display, SDL would try Wayland (which prints its own noise) and
// then settle for its invisible "offscreen" driver: say so instead, unless
// the user picked a driver with SDL_VIDEODRIVER.
void open_video() {
    const bool driver_chosen = is_set("SDL_VIDEODRIVER");
    if (!driver_chosen && !is_set("DISPLAY") && !is_set("WAYLAND_DISPLAY")) {
        throw WindowError(std::string("no display: DISPLAY and WAYLAND_DISPLAY are not set") +
                          no_display_advice);
    }
    const bool wayland = is_set("WAYLAND_DISPLAY") && wayland_socket_exists();
    if (!driver_chosen && is_set("WAYLAND_DISPLAY") && !wayland && !is_set("DISPLAY")) {
        throw WindowError(
            std::string("no display: WAYLAND_DISPLAY=") + std::getenv("WAYLAND_DISPLAY") +
            " names no Wayland socket" +
            (is_set("XDG_RUNTIME_DIR") ? " in XDG_RUNTIME_DIR" : " (XDG_RUNTIME_DIR is not set)") +
            ", and DISPLAY is not set" + no_display_advice);
    }
    if (!driver_chosen && !wayland) {
        // Only X11 can work: an unreachable DISPLAY must not fall through to
        // Wayland's own error lines and SDL's offscreen driver.
        SDL_SetHint(SDL_HINT_VIDEODRIVER, "x11");
    }
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
        const std::string display = is_set("DISPLAY") ? std::getenv("DISPLAY") : "";
        throw WindowError("cannot open a window" +
                          (display.empty() ? std::string() : " on DISPLAY=" + display) + " (" +
                          sdl_error() + ")" + no_display_advice);
    }
    const std::string driver = SDL_GetCurrentVideoDriver();
    if (!driver_chosen && (driver == "offscreen" || driver == "dummy")) {
        SDL_QuitSubSystem(SDL_INIT_VIDEO);
        throw WindowError("no display: SDL found only its '" + driver + "' video driver" +
                          no_display_advice);
    }
}

}  // namespace

Window::Window(const std::string& title, int render_width, int render_height, bool vsync)
    : render_width_(render_width), render_height_(render_height) {
    open_video();
    // Large renders open scaled down to fit the screen; the render keeps
    // its resolution.
    int width = render_width;
    int height = render_height;
    SDL_Rect usable;
    if (SDL_GetDisplayUsableBounds(0, &usable) == 0 && usable.w > 0 && usable.h > 0) {
        const double scale = std::min({1.0, 0.95 * usable.w / width, 0.95 * usable.h / height});
        width = std::max(1, static_cast<int>(width * scale));
        height = std::max(1, static_cast<int>(height * scale));
    }
    window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width,
                               height, SDL_WINDOW_RESIZABLE);
    if (!window_) {
        const std::string error = sdl_error();
        SDL_QuitSubSystem(SDL_INIT_VIDEO);
        throw WindowError("cannot create a window: " + error);
    }
    renderer_ = SDL_CreateRenderer(window_, -1, vsync ? SDL_RENDERER_PRESENTVSYNC : 0);
    if (!renderer_) {
        const std::string error = sdl_error();
        SDL_DestroyWindow(window_);
        SDL_QuitSubSystem(SDL_INIT_VIDEO);
        throw WindowError("cannot create an SDL renderer for the window: " + error);
    }
}

Window::~Window() {
    if (texture_) {
        SDL_DestroyTexture(texture_);
    }
    SDL_DestroyRenderer(renderer_);
    SDL_DestroyWindow(window_);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

void Window::set_image(const trac0r::Rgb8Image& image) {
    if (!texture_ || texture_width_ != image.width || texture_height_ != image.height) {
        if (texture_) {
            SDL_DestroyTexture(texture_);
        }
        texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING,
                                     image.width, image.height);
        if (!texture_) {
            throw WindowError("cannot create a " + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + " texture: " + sdl_error());
        }
        texture_width_ = image.width;
        texture_height_ = image.height;
    }
    SDL_UpdateTexture(texture_, nullptr, image.bytes.data(), image.width * 3);
}

SDL_Rect Window::image_rect() const {
    int out_w = 0;
    int out_h = 0;
    SDL_GetRendererOutputSize(renderer_, &out_w, &out_h);
    const double scale = std::min(static_cast<double>(out_w) / render_width_,
                                  static_cast<double>(out_h) / render_height_);
    SDL_Rect r;
    r.w = std::max(1, static_cast<int>(std::lround(render_width_ * scale)));
    r.h = std::max(1, static_cast<int>(std::lround(render_height_ * scale)));
    r.x = (out_w - r.w) / 2;
    r.y = (out_h - r.h) / 2;
    return r;
}

bool Window::window_to_render(int x, int y, float* render_x, float* render_y) const {
    const SDL_Rect r = image_rect();
    if (x < r.x || y < r.y || x >= r.x + r.w || y >= r.y + r.h) {
        return false;
    }
    *render_x = (static_cast<float>(x - r.x) + 0.5f) * render_width_ / r.w;
    *render_y = (static_cast<float>(y - r.y) + 0.5f) * render_height_ / r.h;
    return true;
}

SDL_FPoint Window::render_to_window(float render_x, float render_y) const {
    const SDL_Rect r = image_rect();
    return SDL_FPoint{r.x + render_x * r.w / render_width_, r.y + render_y * r.h / render_height_};
}

void Window::draw_image() {
    SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
    SDL_RenderClear(renderer_);
    if (texture_) {
        const SDL_Rect r = image_rect();
        SDL_RenderCopy(renderer_, texture_, nullptr, &r);
    }
}

trac0r::Rgb8Image Window::read_image_area() const {
    SDL_Rect r = image_rect();
    trac0r::Rgb8Image image;
    image.width = r.w;
    image.height = r.h;
    image.bytes.resize(static_cast<std::size_t>(r.w) * r.h * 3);
    if (SDL_RenderReadPixels(renderer_, &r, SDL_PIXELFORMAT_RGB24, image.bytes.data(), r.w * 3) !=
        0) {
        throw WindowError("cannot read the window's pixels: " + sdl_error());
    }
    return image;
}

}  // namespace trac0r_viewer
