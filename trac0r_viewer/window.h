// The SDL2 window: shows an image scaled to fit (aspect kept), and reads
// back what was drawn for screenshots. Text and wireframes: overlay.h.
#ifndef TRAC0R_VIEWER_WINDOW_H
#define TRAC0R_VIEWER_WINDOW_H

#include "trac0r/image_io.h"

#include <SDL.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace trac0r_viewer {

// No display, or SDL cannot make a window or a renderer.
class WindowError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class Window {
  public:
    // A window for images of render_width x render_height (smaller previews
    // are stretched to the same place). Resizable: the image is scaled to
    // fit. vsync off for benchmarks. Throws WindowError.
    Window(const std::string& title, int render_width, int render_height, bool vsync);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    std::uint32_t id() const { return SDL_GetWindowID(window_); }
    SDL_Renderer* renderer() const { return renderer_; }
    int render_width() const { return render_width_; }
    int render_height() const { return render_height_; }
    // The size of the render from now on (the window's, after a resize).
    void set_render_size(int width, int height) {
        render_width_ = width;
        render_height_ = height;
    }
    // The drawable area in pixels.
    void output_size(int* width, int* height) const {
        SDL_GetRendererOutputSize(renderer_, width, height);
    }
    void hide() { SDL_HideWindow(window_); }

    // The image to draw from now on (its size may change).
    void set_image(const trac0r::Rgb8Image& image);
    // Where the image lies in the window, in window pixels.
    SDL_Rect image_rect() const;
    // Window position -> render pixel (continuous); false outside the image.
    bool window_to_render(int x, int y, float* render_x, float* render_y) const;
    // Render pixel (continuous) -> window position.
    SDL_FPoint render_to_window(float render_x, float render_y) const;

    // Clears and draws the image; then draw on top, then present().
    void draw_image();
    // The image area as drawn so far (overlay included).
    trac0r::Rgb8Image read_image_area() const;
    void present() { SDL_RenderPresent(renderer_); }

  private:
    int render_width_;
    int render_height_;
    SDL_Window* window_ = nullptr;
    SDL_Renderer* renderer_ = nullptr;
    SDL_Texture* texture_ = nullptr;
    int texture_width_ = 0;
    int texture_height_ = 0;
};

}  // namespace trac0r_viewer

#endif
