// When a render is done: --spp N, --seconds S, --target-error E, and the
// 2^24 samples a pixel's count holds (trac0r::Renderer::max_frames). The
// headless render stops by this rule and the window pauses by it.
#ifndef TRAC0R_VIEWER_STOP_RULE_H
#define TRAC0R_VIEWER_STOP_RULE_H

namespace trac0r_viewer {

enum class StopReason { none, spp, seconds, target_error, full };

struct StopRule {
    long spp = 0;               // samples per pixel (0: no limit)
    double seconds = 0.0;       // since the render (re)started (0: no limit)
    double target_error = 0.0;  // estimated relative MSE (0: no target)

    // Whether a noise estimate (trac0r::estimate_relative_mse) reaches the
    // target error.
    bool error_reached(double estimate) const {
        return target_error > 0.0 && estimate <= target_error;
    }

    // Why a render of `done_spp` samples per pixel, `elapsed` seconds after
    // its start, is done, in this order: --spp, --seconds, the target error
    // (`error_reached`, of the last estimate), a full sample count (`full`,
    // Renderer::full). None while it goes on, and none of the first three
    // before one sample: an image of none would be black.
    StopReason reason(long done_spp, double elapsed, bool error_reached, bool full) const;
};

}  // namespace trac0r_viewer

#endif
