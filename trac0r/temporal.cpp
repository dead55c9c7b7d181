#include "trac0r/temporal.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace trac0r {

Image TemporalFrame::image() const {
    Image out;
    out.width = width();
    out.height = height();
    out.pixels.resize(pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        out.pixels[i] = glm::vec3(pixels[i].value);
    }
    return out;
}

TemporalFrame temporal_blend(const TemporalFrame& history, const Image& current, float samples,
                             const kernel::CameraRecord& camera, const GuideImages& guides,
                             const TemporalSettings& settings, TemporalStats* stats) {
    TemporalFrame out;
    temporal_blend(history, current, samples, camera, guides, &out, settings, stats);
    return out;
}

void temporal_blend(const TemporalFrame& history, const Image& current, float samples,
                    const kernel::CameraRecord& camera, const GuideImages& guides,
                    TemporalFrame* into, const TemporalSettings& settings, TemporalStats* stats) {
    if (into == nullptr || into == &history) {
        throw std::invalid_argument(
            "temporal_blend: the result must be a frame other than the history");
    }
    const int width = static_cast<int>(camera.size.x);
    const int height = static_cast<int>(camera.size.y);
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (current.width != width || current.height != height || guides.width != width ||
        guides.height != height) {
        throw std::invalid_argument("temporal_blend: the image and the guides must be " +
                                    std::to_string(width) + " x " + std::to_string(height) +
                                    ", the camera's size");
    }
    const std::size_t history_count =
        static_cast<std::size_t>(history.width()) * static_cast<std::size_t>(history.height());
    if (!history.empty() &&
        (history.pixels.size() != history_count || history.guides.size() != history_count ||
         history.depth_slopes.size() != history_count)) {
        throw std::invalid_argument(
            "temporal_blend: the history's pixels, guides, depth slopes and camera disagree");
    }
    // Every pixel of the three images is written below: resized, not
    // cleared, so that storage of the same size is used again as it is.
    // Where that fails for memory, the frame is left empty, not with
    // images of another size than its camera's.
    TemporalFrame& out = *into;
    try {
        out.pixels.resize(count);
        out.guides.resize(count);
        out.depth_slopes.resize(count);
    } catch (...) {
        out = TemporalFrame();
        throw;
    }
    out.camera = camera;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < count; ++i) {
        const float depth = guides.depth[i];
        out.guides[i].normal_depth =
            glm::vec4(guides.normal[i], std::isfinite(depth) ? depth : T0_NO_HIT);
    }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            out.depth_slopes[static_cast<std::size_t>(y) * width + x] =
                kernel::temporal_depth_slope(out.guides.data(), width, height, x, y);
        }
    }
    // Taken once: every pixel's point is then relative to the previous
    // camera without subtracting two large positions of its own.
    const glm::vec3 offset = history.empty()
                                 ? glm::vec3(0.0f)
                                 : glm::vec3(camera.position) - glm::vec3(history.camera.position);
    long reused = 0;
    long background = 0;
#pragma omp parallel for schedule(static) reduction(+ : reused, background)
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            const glm::vec4 h =
                history.empty()
                    ? glm::vec4(0.0f)
                    : kernel::reproject_history(camera, history.camera, offset,
                                                history.pixels.data(), history.guides.data(),
                                                history.depth_slopes.data(), out.guides[i], x, y);
            reused += h.w > 0.0f ? 1 : 0;
            background += out.guides[i].normal_depth.w < T0_NO_HIT ? 0 : 1;
            out.pixels[i] =
                kernel::temporal_blend_pixel(h, current.pixels[i], samples, settings.max_history);
        }
    }
    if (stats) {
        stats->reused = reused;
        stats->background = background;
        stats->dropped = static_cast<long>(count) - reused - background;
    }
}

}  // namespace trac0r
