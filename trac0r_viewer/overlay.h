// What the window draws on top of the image: the debug overlay (F1: shape
// AABBs as yellow wireframes, timings, camera, the pixel under the mouse)
// and text panels (key help, messages) in DejaVu Sans Mono.
#ifndef TRAC0R_VIEWER_OVERLAY_H
#define TRAC0R_VIEWER_OVERLAY_H

#include "window.h"

#include "trac0r/camera.h"
#include "trac0r/geometry.h"

#include <SDL_ttf.h>

#include <string>
#include <vector>

namespace trac0r_viewer {

// The AABB wireframe colour; the tests look for it in screenshots.
constexpr SDL_Color overlay_aabb_color{255, 255, 0, 255};

// The font of every text panel, set at configure time (-DTRAC0R_FONT).
const char* overlay_font_path();

class Font {
  public:
    // Throws WindowError naming the file (and the Debian package) when it
    // is missing or unreadable.
    Font(const std::string& path, int point_size);
    ~Font();
    Font(const Font&) = delete;
    Font& operator=(const Font&) = delete;

    // Draws lines of text on a translucent dark panel whose top-left corner
    // is at (x, y); negative x or y measure from the right or bottom edge of
    // the window. Lines wider than the window wrap at a space. Returns the
    // panel's height.
    int draw_panel(SDL_Renderer* renderer, const std::string& text, int x, int y) const;
    // The size draw_panel's panel of `text` has where nothing wraps.
    void panel_size(const std::string& text, int* width, int* height) const;

  private:
    TTF_Font* font_ = nullptr;
};

// The key help for a panel of at most width x height pixels: the full
// list where it fits, else a short one, else the short one's first lines
// and a line that says the rest is left out; empty where not even that fits.
std::string fitting_help(const Font& font, int width, int height);

// Every box as a wireframe in overlay_aabb_color, clipped at the near plane
// and to the image (trac0r/projection.h), drawn where the image lies.
void draw_wireframes(const Window& window, const std::vector<trac0r::AABB>& boxes,
                     const trac0r::Camera& camera, float near_distance);

// The figures of the overlay's text.
struct OverlayFigures {
    double frame_seconds = 0.0;
    double accumulation_seconds = 0.0;  // WorkerFrame::accumulation_seconds
    std::string integrator;             // "nee", "naive" (--integrator)
    bool filter = false;                // the display filter is on (F)
    long pixels = 0;                    // of that frame
    long spp = 0;
    double relative_mse = 0.0;         // estimated; +inf when unknown (below 2 spp)
    long relative_mse_spp = 0;         // the samples per pixel it was estimated at
    int preview_factor = 0;            // 0: a full-resolution frame
    std::string paused_by;             // WorkerFrame::paused_by
    bool estimate_overflowed = false;  // WorkerFrame::estimate_overflowed
    std::string backend;
    std::string device;
    std::size_t triangles = 0;
    std::size_t shapes = 0;
    int width = 0;
    int height = 0;
    trac0r::Camera camera;
    float exposure = 1.0f;
    std::string view = "standard";  // the view transform (V, --view)
    bool mouse_in_image = false;
    int mouse_x = 0;  // render pixel
    int mouse_y = 0;
    glm::vec3 mouse_radiance{0.0f};
};

std::string overlay_text(const OverlayFigures& figures);

}  // namespace trac0r_viewer

#endif
