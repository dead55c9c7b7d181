#include "trac0r/noise.h"

#include "trac0r/kernel/accumulate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace trac0r {

ImageError image_error(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height) {
        throw std::invalid_argument("image is " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + ", reference is " +
                                    std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height));
    }
    double squared = 0.0;
    double relative = 0.0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::dvec3 d = glm::dvec3(image.pixels[i]) - glm::dvec3(reference.pixels[i]);
        squared += glm::dot(d, d);
        const double l = kernel::luminance(image.pixels[i]);
        const double l_ref = kernel::luminance(reference.pixels[i]);
        relative += (l - l_ref) * (l - l_ref) / (l_ref * l_ref + relative_mse_epsilon);
    }
    const double n = static_cast<double>(image.pixels.size());
    ImageError e;
    e.rmse = std::sqrt(squared / (3.0 * n));
    e.relative_mse = relative / n;
    e.psnr = e.rmse > 0.0 ? -20.0 * std::log10(e.rmse) : std::numeric_limits<double>::infinity();
    return e;
}

namespace {

// Box-filtered mean luminance, radius 2, clamped at the image border:
// separable, a running window along rows then columns (O(1) per pixel).
std::vector<double> neighbourhood_means(const std::vector<kernel::AccumPixel>& accumulator,
                                        int width, int height) {
    constexpr int radius = 2;
    const auto window = [](int i, int n) {
        return std::make_pair(std::max(0, i - radius), std::min(n - 1, i + radius));
    };
    std::vector<double> rows(accumulator.size());
    std::vector<double> prefix(static_cast<std::size_t>(std::max(width, height)) + 1);
    for (int y = 0; y < height; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * width;
        for (int x = 0; x < width; ++x) {
            prefix[x + 1] = prefix[x] + accumulator[row + x].moments.x;
        }
        for (int x = 0; x < width; ++x) {
            const auto w = window(x, width);
            rows[row + x] = prefix[w.second + 1] - prefix[w.first];
        }
    }
    std::vector<double> out(accumulator.size());
    for (int x = 0; x < width; ++x) {
        for (int y = 0; y < height; ++y) {
            prefix[y + 1] = prefix[y] + rows[static_cast<std::size_t>(y) * width + x];
        }
        const auto wx = window(x, width);
        for (int y = 0; y < height; ++y) {
            const auto wy = window(y, height);
            const double count = static_cast<double>(wx.second - wx.first + 1) *
                                 static_cast<double>(wy.second - wy.first + 1);
            out[static_cast<std::size_t>(y) * width + x] =
                (prefix[wy.second + 1] - prefix[wy.first]) / count;
        }
    }
    return out;
}

}  // namespace

bool noise_estimate_overflowed(const std::vector<kernel::AccumPixel>& accumulator) {
    for (const kernel::AccumPixel& p : accumulator) {
        if (!std::isfinite(p.moments.y)) {
            return true;
        }
    }
    return false;
}

double estimate_relative_mse(const std::vector<kernel::AccumPixel>& accumulator, int width,
                             int height) {
    if (accumulator.empty() || accumulator.size() != static_cast<std::size_t>(width) * height) {
        throw std::invalid_argument("estimate_relative_mse: accumulator is not width x height");
    }
    const std::vector<double> means = neighbourhood_means(accumulator, width, height);
    double sum = 0.0;
    for (std::size_t i = 0; i < accumulator.size(); ++i) {
        const kernel::AccumPixel& p = accumulator[i];
        const double n = p.moments.z;
        if (n < 2.0) {
            return std::numeric_limits<double>::infinity();
        }
        const double variance_of_mean = p.moments.y / (n - 1.0) / n;
        sum += variance_of_mean / (means[i] * means[i] + relative_mse_epsilon);
    }
    return sum / static_cast<double>(accumulator.size());
}

}  // namespace trac0r
