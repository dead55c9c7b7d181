#include "stop_rule.h"

namespace trac0r_viewer {

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

}  // namespace trac0r_viewer
