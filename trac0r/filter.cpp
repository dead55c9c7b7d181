#include "trac0r/filter.h"

#include "trac0r/kernel/filter.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace trac0r {

std::vector<kernel::FilterGuide> filter_guides(const GuideImages& guides) {
    const int width = guides.width;
    const int height = guides.height;
    std::vector<kernel::FilterGuide> out(guides.albedo.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const int x = static_cast<int>(i % static_cast<std::size_t>(width));
        const int y = static_cast<int>(i / static_cast<std::size_t>(width));
        const glm::vec4 e = guides.emission.empty() ? glm::vec4(0.0f) : guides.emission[i];
        // The surface the pixel shows: its centre's, or where the centre
        // is on a lamp whose edge runs through the pixel, the surface
        // beside the lamp, which goes on under the edge: a 4-neighbour's
        // that is no lamp.
        std::size_t s = i;
        if (guides.emitter[i] != 0 && e.w < 1.0f) {
            const int nx[4] = {x - 1, x + 1, x, x};
            const int ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4 && s == i; ++k) {
                const std::size_t q = static_cast<std::size_t>(ny[k]) * width + nx[k];
                if (nx[k] >= 0 && nx[k] < width && ny[k] >= 0 && ny[k] < height &&
                    guides.emitter[q] == 0 && std::isfinite(guides.depth[q])) {
                    s = q;
                }
            }
        }
        // A pixel (almost) all lamp is kept as it is; where an edge runs
        // through it, the lamps' part is set apart from the surface's.
        const bool kept = guides.emitter[s] != 0 || e.w > 0.95f;
        const float depth = guides.depth[s];
        out[i].albedo = glm::vec4(guides.albedo[s], std::isfinite(depth) ? depth : T0_NO_HIT);
        out[i].normal = glm::vec4(guides.normal[s], kept ? 1.0f : 0.0f);
        out[i].emission = kept ? glm::vec4(0.0f) : e;
    }
    return out;
}

Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int width, int height,
                   const std::vector<kernel::FilterGuide>& guides, int passes) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (accumulator.size() != pixels || guides.size() != pixels) {
        throw std::invalid_argument("filter_image: the accumulator and the guides must have " +
                                    std::to_string(pixels) + " pixels");
    }
    std::vector<kernel::FilterPixel> a(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        a[i] = kernel::filter_input(accumulator[i], guides[i]);
    }
    std::vector<kernel::FilterTap> taps(pixels);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            taps[static_cast<std::size_t>(y) * width + x] =
                kernel::filter_tap(guides.data(), width, height, x, y);
        }
    }
    std::vector<kernel::FilterPixel> b(pixels);
    std::vector<kernel::FilterNoise> noise(pixels);
    for (int pass = 0; pass < passes; ++pass) {
        for (std::size_t i = 0; i < pixels; ++i) {
            noise[i] = kernel::filter_noise(a[i]);
        }
#pragma omp parallel for schedule(static)
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                b[static_cast<std::size_t>(y) * width + x] = kernel::atrous_pixel(
                    a.data(), taps.data(), noise.data(), width, height, x, y, pass);
            }
        }
        std::swap(a, b);
    }
    Image out;
    out.width = width;
    out.height = height;
    out.pixels.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        out.pixels[i] = kernel::filter_output(a[i], guides[i]);
    }
    return out;
}

}  // namespace trac0r
