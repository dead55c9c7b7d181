// Image error against a reference, and the renderer's own estimate of it
// from the per-pixel sample variance (no reference needed).
//
// Relative MSE, as commonly used for Monte Carlo renders (e.g. Rousselle et
// al. 2011): the mean over pixels of (L - L_ref)^2 / (L_ref^2 + 0.01), on
// luminance L. The 0.01 keeps near-black pixels from dominating.
#ifndef TRAC0R_NOISE_H
#define TRAC0R_NOISE_H

#include "trac0r/image_io.h"
#include "trac0r/kernel_fwd.h"

#include <vector>

namespace trac0r {

const double relative_mse_epsilon = 0.01;

struct ImageError {
    double rmse;          // over all RGB values
    double relative_mse;  // luminance, as above
    double psnr;          // dB, peak 1 (display white at exposure 1)
};

// Throws std::invalid_argument when the sizes differ.
ImageError image_error(const Image& image, const Image& reference);

// The expected relative MSE of the current mean: per pixel, the variance of
// the mean (sample variance of the luminance / samples) over (m^2 + 0.01),
// where m is the mean luminance of the pixel's 5 x 5 neighbourhood. The
// pixel's own mean would not do: where rare bright samples carry the mean
// (light found by chance), it is large exactly when the variance estimate
// is, and their ratio says "converged" after a handful of samples. The same
// quantity as image_error's relative_mse, expected over renders. Pixels with
// fewer than two samples make it unknown (infinite).
double estimate_relative_mse(const std::vector<kernel::AccumPixel>& accumulator, int width,
                             int height);

// Whether a pixel's sum of squared luminance deviations (a float,
// AccumPixel::moments.y) has overflowed: samples beyond about 1e19, whose
// squares a float cannot hold. The estimate is then infinite for good,
// however long the render runs.
bool noise_estimate_overflowed(const std::vector<kernel::AccumPixel>& accumulator);

}  // namespace trac0r

#endif
