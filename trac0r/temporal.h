// Temporal reuse while the camera moves (kernel/temporal.h): the frame on
// display carried into the next view through each pixel's first hit, kept
// where the previous frame saw the same surface and dropped where it did
// not, and blended with the new view's samples. A display aid: the
// accumulation is never touched.
#ifndef TRAC0R_TEMPORAL_H
#define TRAC0R_TEMPORAL_H

#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/kernel/temporal.h"
#include "trac0r/kernel/types.h"

#include <vector>

namespace trac0r {

// A displayed frame and what its reprojection into another view needs:
// its camera (as the Renderer holds it, in the scene's coordinates) and
// per pixel its colour, the samples behind it, its first hit's depth and
// normal (from render_guides), and how much that depth changes to a
// neighbour (kernel::temporal_depth_slope, made once here rather than for
// each of the four taps that read a pixel).
struct TemporalFrame {
    kernel::CameraRecord camera{};
    std::vector<kernel::TemporalPixel> pixels;  // row-major, row 0 at the top
    std::vector<kernel::TemporalGuide> guides;
    std::vector<float> depth_slopes;
    int width() const { return static_cast<int>(camera.size.x); }
    int height() const { return static_cast<int>(camera.size.y); }
    bool empty() const { return pixels.empty(); }
    Image image() const;  // the colours
};

struct TemporalSettings {
    // The most samples the history counts for against the new ones: more
    // keeps less noise while moving, fewer lets stale light (a moved
    // highlight) fade sooner. 16 at a preview's 1 sample a frame: the
    // history's share falls to a half in about 11 frames once it is stale.
    float max_history = 16.0f;
};

// What reprojection did: pixels that took history; pixels on a surface
// that started again (disoccluded, outside the previous view, or no history
// at all); pixels that see nothing (the background: never carried over).
struct TemporalStats {
    long reused = 0;
    long dropped = 0;
    long background = 0;
};

// `current` (the mean of `samples` samples a pixel, seen by `camera` with
// `guides`, all of the same size) blended with `history` reprojected into
// its view (any size, any camera; empty: none). The result is what to show
// and the next frame's history. Throws std::invalid_argument when the
// sizes disagree.
TemporalFrame temporal_blend(const TemporalFrame& history, const Image& current, float samples,
                             const kernel::CameraRecord& camera, const GuideImages& guides,
                             const TemporalSettings& settings = TemporalSettings(),
                             TemporalStats* stats = nullptr);

// The same into *into (not the history), whose images are resized and
// overwritten: a caller that blends every frame keeps two frames and
// swaps them, and makes no new pages each time (at 800 x 600, the size
// of the window's first 64 full frames after a move, a new frame's 17 MB
// of pages made the blend 1.4 to 1.7 times as slow).
void temporal_blend(const TemporalFrame& history, const Image& current, float samples,
                    const kernel::CameraRecord& camera, const GuideImages& guides,
                    TemporalFrame* into, const TemporalSettings& settings = TemporalSettings(),
                    TemporalStats* stats = nullptr);

}  // namespace trac0r

#endif
