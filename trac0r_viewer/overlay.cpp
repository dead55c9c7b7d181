#include "overlay.h"

#include "options.h"

#include "trac0r/projection.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>

namespace trac0r_viewer {

namespace {

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

std::string format(const char* fmt, ...) {
    char buffer[512];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(buffer, sizeof buffer, fmt, args);
    va_end(args);
    return buffer;
}

}  // namespace

const char* overlay_font_path() { return TRAC0R_FONT; }

Font::Font(const std::string& path, int point_size) {
    if (!std::ifstream(path)) {
        throw WindowError("font " + path +
                          " not found: install Debian's fonts-dejavu-core, or "
                          "configure with -DTRAC0R_FONT=/path/to/a/monospace.ttf");
    }
    if (TTF_Init() != 0) {
        throw WindowError(std::string("cannot start SDL_ttf: ") + TTF_GetError());
    }
    font_ = TTF_OpenFont(path.c_str(), point_size);
    if (!font_) {
        const std::string error = TTF_GetError();
        TTF_Quit();
        throw WindowError("font " + path + ": cannot open it: " + error);
    }
}

Font::~Font() {
    TTF_CloseFont(font_);
    TTF_Quit();
}

void Font::panel_size(const std::string& text, int* width, int* height) const {
    const int margin = 4;  // as draw_panel's
    int widest = 0;
    int lines = 0;
    for (std::size_t start = 0; start <= text.size(); ++lines) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        int w = 0;
        int h = 0;
        if (TTF_SizeUTF8(font_, text.substr(start, end - start).c_str(), &w, &h) == 0) {
            widest = std::max(widest, w);
        }
        start = end + 1;
    }
    *width = widest + 2 * margin;
    *height = lines * TTF_FontLineSkip(font_) + 2 * margin;
}

std::string fitting_help(const Font& font, int width, int height) {
    const auto fits = [&](const std::string& text) {
        int w = 0;
        int h = 0;
        font.panel_size(text, &w, &h);
        return w <= width && h <= height;
    };
    const std::string full = "Keys and mouse\n" + std::string(key_help_text());
    const std::string all = full.substr(0, full.find_last_not_of('\n') + 1);
    if (fits(all)) {
        return all;
    }
    std::vector<std::string> lines{"Keys and mouse"};
    const std::string short_text = key_help_short_text();
    for (std::size_t start = 0; start < short_text.size();) {
        const std::size_t end = std::min(short_text.find('\n', start), short_text.size());
        lines.push_back(short_text.substr(start, end - start));
        start = end + 1;
    }
    const auto joined = [&](std::size_t n, bool cut) {
        std::string text;
        for (std::size_t i = 0; i < n; ++i) {
            text += (i ? "\n" : "") + lines[i];
        }
        return cut ? text + "\n... (a larger window shows all)" : text;
    };
    if (fits(joined(lines.size(), false))) {
        return joined(lines.size(), false);
    }
    for (std::size_t n = lines.size() - 1; n >= 2; --n) {
        if (fits(joined(n, true))) {
            return joined(n, true);
        }
    }
    return "";
}

int Font::draw_panel(SDL_Renderer* renderer, const std::string& text, int x, int y) const {
    const SDL_Color white{235, 235, 235, 255};
    const int margin = 4;
    int out_w = 0;
    int out_h = 0;
    SDL_GetRendererOutputSize(renderer, &out_w, &out_h);
    // Lines wider than the window (8 pixels off each edge) wrap at a space,
    // so that a narrow window cuts nothing off (at least 120 pixels wide).
    // Only then: SDL_ttf makes a wrapped panel as wide as the wrap length.
    const int wrap = std::max(120, out_w - 2 * margin - 16);
    int widest = 0;
    for (std::size_t start = 0; start <= text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        int w = 0;
        int h = 0;
        if (TTF_SizeUTF8(font_, text.substr(start, end - start).c_str(), &w, &h) == 0) {
            widest = std::max(widest, w);
        }
        start = end + 1;
    }
    // Wrap length 0: break at the newlines only.
    SDL_Surface* surface = TTF_RenderUTF8_Blended_Wrapped(
        font_, text.c_str(), white, widest > wrap ? static_cast<Uint32>(wrap) : 0u);
    if (!surface) {
        return 0;  // nothing drawable (empty text); the image is still shown
    }
    SDL_Texture* texture = SDL_CreateTextureFromSurface(renderer, surface);
    SDL_Rect panel{0, 0, surface->w + 2 * margin, surface->h + 2 * margin};
    panel.x = x >= 0 ? x : out_w + x - panel.w;
    panel.y = y >= 0 ? y : out_h + y - panel.h;
    SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_BLEND);
    SDL_SetRenderDrawColor(renderer, 0, 0, 0, 170);
    SDL_RenderFillRect(renderer, &panel);
    SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_NONE);
    if (texture) {
        const SDL_Rect where{panel.x + margin, panel.y + margin, surface->w, surface->h};
        SDL_RenderCopy(renderer, texture, nullptr, &where);
        SDL_DestroyTexture(texture);
    }
    SDL_FreeSurface(surface);
    return panel.h;
}

void draw_wireframes(const Window& window, const std::vector<trac0r::AABB>& boxes,
                     const trac0r::Camera& camera, float near_distance) {
    const trac0r::kernel::CameraRecord record =
        trac0r::make_camera_record(camera, window.render_width(), window.render_height());
    SDL_Renderer* renderer = window.renderer();
    const SDL_Color c = overlay_aabb_color;
    SDL_SetRenderDrawColor(renderer, c.r, c.g, c.b, c.a);
    for (const trac0r::AABB& box : boxes) {
        for (const trac0r::Segment2& s :
             trac0r::project_aabb_wireframe(record, box, near_distance)) {
            const SDL_FPoint a = window.render_to_window(s.a.x, s.a.y);
            const SDL_FPoint b = window.render_to_window(s.b.x, s.b.y);
            SDL_RenderDrawLineF(renderer, a.x, a.y, b.x, b.y);
        }
    }
}

std::string overlay_text(const OverlayFigures& f) {
    const double fps = f.frame_seconds > 0.0 ? 1.0 / f.frame_seconds : 0.0;
    // Paused, the last frame's rate would read as if it still rendered.
    std::string text =
        f.paused_by.empty()
            ? format("render   %.2f fps  %.0f ms/frame  %.2f Mpaths/s\n", fps,
                     1e3 * f.frame_seconds, 1e-6 * fps * f.pixels)
            : format("render   paused at %ld spp (%s; R restarts)\n", f.spp, f.paused_by.c_str());
    if (f.preview_factor > 0) {
        text += format("samples  %ld spp (1/%d-resolution preview while moving, with NEE)\n", f.spp,
                       f.preview_factor);
    } else if (std::isfinite(f.relative_mse) && f.relative_mse_spp == f.spp) {
        text += format("samples  %ld spp  rel. MSE \u2248 %.3g\n", f.spp, f.relative_mse);
    } else if (std::isfinite(f.relative_mse)) {
        // Estimated every half second or so (window_worker.h): say when.
        text += format("samples  %ld spp  rel. MSE \u2248 %.3g at %ld spp\n", f.spp, f.relative_mse,
                       f.relative_mse_spp);
    } else {
        text +=
            f.estimate_overflowed
                ? format("samples  %ld spp  rel. MSE overflowed (radiance above ~1e19)\n", f.spp)
                : format("samples  %ld spp  rel. MSE \u2248 ? (from 2 spp)\n", f.spp);
    }
    if (f.preview_factor == 0) {
        text += format("accum    %.1f s  %s integrator  filter %s\n", f.accumulation_seconds,
                       f.integrator.c_str(), f.filter ? "on" : "off");
    } else {
        text += format("accum    restarts when the camera stops  filter %s\n",
                       f.filter ? "on (full-resolution frames)" : "off");
    }
    text += format("backend  %s: %s\n", f.backend.c_str(), f.device.c_str());
    text += format("scene    %zu triangles, %zu shapes, %dx%d\n", f.triangles, f.shapes, f.width,
                   f.height);
    const glm::vec3 p = f.camera.position;
    const glm::vec3 d = glm::normalize(f.camera.direction);
    if (f.camera.projection == trac0r::Projection::orthographic) {
        text += format(
            "camera   pos (%.3f, %.3f, %.3f)  dir (%.3f, %.3f, %.3f)  orthographic, "
            "%.3g m high\n",
            p.x, p.y, p.z, d.x, d.y, d.z, f.camera.view_height);
    } else {
        text += format("camera   pos (%.3f, %.3f, %.3f)  dir (%.3f, %.3f, %.3f)  fov %.1f\n", p.x,
                       p.y, p.z, d.x, d.y, d.z, f.camera.vertical_fov);
    }
    if (f.camera.aperture_radius > 0.0f) {
        text += format("lens     aperture radius %.3g m  focus at %.3g m\n",
                       f.camera.aperture_radius, f.camera.focus_distance);
    }
    text += f.mouse_in_image
                ? format("mouse    pixel (%d, %d)  radiance (%.4g, %.4g, %.4g)\n", f.mouse_x,
                         f.mouse_y, f.mouse_radiance.x, f.mouse_radiance.y, f.mouse_radiance.z)
                : std::string("mouse    not over the image\n");
    text += format("exposure %.3g  view %s   F1 overlay  H keys", f.exposure, f.view.c_str());
    return text;
}

}  // namespace trac0r_viewer
