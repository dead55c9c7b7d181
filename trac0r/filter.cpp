#include "trac0r/filter.h"

#include "trac0r/kernel/filter.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace trac0r {

std::vector<kernel::FilterGuide> filter_guides(const GuideImages& guides) {
    std::vector<kernel::FilterGuide> out(guides.albedo.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const float depth = guides.depth[i];
        out[i].albedo = glm::vec4(guides.albedo[i], std::isfinite(depth) ? depth : T0_NO_HIT);
        out[i].normal = glm::vec4(guides.normal[i], guides.emitter[i] != 0 ? 1.0f : 0.0f);
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
    std::vector<kernel::FilterPixel> b(pixels);
    for (int pass = 0; pass < passes; ++pass) {
#pragma omp parallel for schedule(static)
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                b[static_cast<std::size_t>(y) * width + x] =
                    kernel::atrous_pixel(a.data(), guides.data(), width, height, x, y, pass);
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
