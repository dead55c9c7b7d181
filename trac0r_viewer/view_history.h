// What the window shows while the view moves and just after it stops
// (temporal reuse, trac0r/temporal.h): the frame on display as history for
// the next preview, what the moves left carried into the first full
// frames of the new accumulation, and the last full frame as shown. The
// render thread's (RenderWorker's) state for it, and its rules.
#ifndef TRAC0R_VIEWER_VIEW_HISTORY_H
#define TRAC0R_VIEWER_VIEW_HISTORY_H

#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/temporal.h"

#include <cstdint>
#include <functional>

namespace trac0r_viewer {

// The full frames after a stop blend in what the moves left until the
// accumulation has this many samples a pixel (then the history's share
// would be at most a fifth).
constexpr std::uint32_t carried_history_frames = 64;

class ViewHistory {
  public:
    // The guides of a view of the full renderer's scene (made once a view).
    using GuidesOf = std::function<const trac0r::GuideImages&(const trac0r::kernel::CameraRecord&)>;

    explicit ViewHistory(GuidesOf guides_of) : guides_of_(std::move(guides_of)) {}

    // A restart or a backend switch: the next frames start from nothing.
    void drop() { drop_ = true; }

    // A preview of `spp` samples from `camera` (its own guides) blended
    // into the history: what to show.
    trac0r::Image preview(const trac0r::Image& image, float spp,
                          const trac0r::kernel::CameraRecord& camera,
                          const trac0r::GuideImages& guides);

    // A new accumulation starts: what is shown now is carried into its
    // first frames, and stays the history until one of them is shown.
    void start_accumulation();

    // A full frame: `image` (the accumulation of `spp` samples from
    // `camera`) with what the moves left blended in, while that lasts.
    // What to show.
    trac0r::Image full_frame(const trac0r::Image& image, std::uint32_t spp,
                             const trac0r::kernel::CameraRecord& camera);

    // The accumulation paused: whether what the moves left was still being
    // blended in; then it is dropped and `accumulation` is what is shown.
    bool pause(const trac0r::Image& accumulation);

    // The last full frame as shown; empty before the first.
    const trac0r::Image& last_full_frame() const { return shown_full_; }

  private:
    // history_ from the last full frame shown, where that is what was
    // shown last.
    void settle();

    GuidesOf guides_of_;
    // The frame on display with its guides (empty: none, or the last full
    // frame shown, made from shown_full_ when needed).
    trac0r::TemporalFrame history_;
    // The frame before history_, whose storage the next preview's blend
    // writes into (then the two swap), so that previews make no new
    // pages; let go where it is not of the previews' size (a full frame's,
    // after a stop), not kept through the move.
    trac0r::TemporalFrame spare_;
    bool history_is_shown_full_ = false;
    bool drop_ = false;
    // What the moves left, blended into the full frames after a stop.
    trac0r::TemporalFrame carried_;
    // The last full frame as shown, with its samples and camera.
    trac0r::Image shown_full_;
    std::uint32_t shown_full_spp_ = 0;
    trac0r::kernel::CameraRecord shown_full_camera_{};
};

}  // namespace trac0r_viewer

#endif
