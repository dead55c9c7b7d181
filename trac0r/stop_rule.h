// When a render is done: N samples per pixel, S seconds, an estimated
// error E (the programs' --spp, --seconds, --target-error), and the 2^24
// samples a pixel's count holds (Renderer::max_frames). A batch render
// (batch.h) stops by this rule and trac0r_viewer's window pauses by it.
#ifndef TRAC0R_STOP_RULE_H
#define TRAC0R_STOP_RULE_H

namespace trac0r {

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
    // its start, is done, in this order: spp, seconds, the target error
    // (`error_reached`, of the last estimate), a full sample count (`full`,
    // Renderer::full). None while it goes on, and none of the first three
    // before one sample: an image of none would be black.
    StopReason reason(long done_spp, double elapsed, bool error_reached, bool full) const;

    // How much of the rule is done, in [0, 1], for a progress bar: the
    // largest of done_spp / spp, elapsed / seconds and target_error /
    // estimate (the relative MSE falls as 1 / spp).
    double fraction(long done_spp, double elapsed, double estimate) const;
};

}  // namespace trac0r

#endif
