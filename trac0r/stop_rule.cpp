#include "trac0r/stop_rule.h"

#include <algorithm>
#include <cmath>

namespace trac0r {

StopReason StopRule::reason(long done_spp, double elapsed, bool error_reached, bool full) const {
    if (done_spp > 0) {
        if (spp > 0 && done_spp >= spp) {
            return StopReason::spp;
        }
        if (seconds > 0.0 && elapsed >= seconds) {
            return StopReason::seconds;
        }
        if (error_reached) {
            return StopReason::target_error;
        }
    }
    return full ? StopReason::full : StopReason::none;
}

double StopRule::fraction(long done_spp, double elapsed, double estimate) const {
    double f = 0.0;
    if (spp > 0) {
        f = std::max(f, static_cast<double>(done_spp) / static_cast<double>(spp));
    }
    if (seconds > 0.0) {
        f = std::max(f, elapsed / seconds);
    }
    if (target_error > 0.0 && std::isfinite(estimate) && estimate > 0.0) {
        f = std::max(f, target_error / estimate);
    }
    return std::min(1.0, f);
}

}  // namespace trac0r
