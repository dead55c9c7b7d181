#include "view_history.h"

#include <utility>

namespace trac0r_viewer {

void ViewHistory::settle() {
    if (drop_) {
        history_ = trac0r::TemporalFrame();
        spare_ = trac0r::TemporalFrame();
        history_is_shown_full_ = false;
        drop_ = false;
    } else if (history_is_shown_full_) {
        trac0r::temporal_blend(trac0r::TemporalFrame(), shown_full_,
                               static_cast<float>(shown_full_spp_), shown_full_camera_,
                               guides_of_(shown_full_camera_), &history_);
        history_is_shown_full_ = false;
    }
}

trac0r::Image ViewHistory::preview(const trac0r::Image& image, float spp,
                                   const trac0r::kernel::CameraRecord& camera,
                                   const trac0r::GuideImages& guides) {
    settle();
    trac0r::temporal_blend(history_, image, spp, camera, guides, &spare_);
    std::swap(history_, spare_);
    if (spare_.pixels.size() != history_.pixels.size()) {
        spare_ = trac0r::TemporalFrame();
    }
    return history_.image();
}

void ViewHistory::start_accumulation() {
    settle();
    carried_ = history_;
}

trac0r::Image ViewHistory::full_frame(const trac0r::Image& image, std::uint32_t spp,
                                      const trac0r::kernel::CameraRecord& camera) {
    trac0r::Image shown = image;
    if (!carried_.empty() && spp >= carried_history_frames) {
        carried_ = trac0r::TemporalFrame();
    }
    if (carried_.empty()) {
        // The next move starts from this frame, made into history_ only
        // then: most full frames are followed by another.
        history_is_shown_full_ = true;
    } else {
        trac0r::temporal_blend(carried_, shown, static_cast<float>(spp), camera, guides_of_(camera),
                               &history_);
        history_is_shown_full_ = false;
        shown = history_.image();
    }
    shown_full_ = shown;
    shown_full_spp_ = spp;
    shown_full_camera_ = camera;
    return shown;
}

bool ViewHistory::pause(const trac0r::Image& accumulation) {
    if (carried_.empty()) {
        return false;
    }
    carried_ = trac0r::TemporalFrame();
    history_is_shown_full_ = true;
    shown_full_ = accumulation;
    return true;
}

}  // namespace trac0r_viewer
