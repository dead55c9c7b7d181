// A batch render: frames until a stop rule (samples per pixel, seconds, an
// estimated error), with progress reports and a way to cancel, returning
// the image, its variance, and on request the filtered image and the EXR
// layers. trac0r_viewer --headless, trac0r_mpi and the Python module call
// it; they parse, print and write.
#ifndef TRAC0R_BATCH_H
#define TRAC0R_BATCH_H

#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/render_cluster.h"
#include "trac0r/renderer.h"
#include "trac0r/stop_rule.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

namespace trac0r {

// The samples per pixel of a batch render whose stop rule sets nothing.
const long default_batch_spp = 64;

// Where a batch render is, for a progress bar.
struct BatchProgress {
    long spp = 0;          // frames rendered by all processes together
    double seconds = 0.0;  // since the render started
    double paths_per_second = 0.0;
    double estimate = 0.0;  // estimated relative MSE (noise.h); +inf before 2 spp;
                            // remade after 50 times its cost, or at each
                            // target-error check
    double fraction = 0.0;  // of the stop rule done, in [0, 1]: the largest of
                            // spp / rule.spp, seconds / rule.seconds and
                            // rule.target_error / estimate
};

struct BatchOptions {
    // When to stop; with nothing set, default_batch_spp. A render also
    // stops at Renderer::max_frames.
    StopRule stop;
    // Called after a frame at most every progress_interval seconds, on the
    // first process only (the result has the final figures). Returning
    // false cancels, as `cancel` does, with the code -1; an exception it
    // throws cancels too, and render_batch throws it once every process
    // has stopped.
    std::function<bool(const BatchProgress&)> progress;
    double progress_interval = 0.1;
    // Read after every frame; non-zero cancels: the frame in flight is
    // finished (at least one frame is always rendered) and the image so
    // far comes back, with this code in BatchResult::cancelled. Another
    // thread, or a signal handler, sets it.
    const std::atomic<int>* cancel = nullptr;
    // The processes the render is split across (nullptr: this one).
    Cluster* cluster = nullptr;
    // Also make BatchResult::filtered (the edge-preserving filter,
    // filter.h, on the backend that rendered) and BatchResult::layers.
    bool filtered = false;
    ExrLayerChoice layers;
};

struct BatchResult {
    // Out of line: the accumulator's type is the kernel's (kernel_fwd.h).
    BatchResult();
    ~BatchResult();
    BatchResult(const BatchResult&);
    BatchResult(BatchResult&&) noexcept;
    BatchResult& operator=(const BatchResult&);
    BatchResult& operator=(BatchResult&&) noexcept;

    // The first process holds the result; the other ranks of a cluster
    // hold only the counts.
    bool first = true;
    Image image;                                  // the mean
    std::vector<float> variance;                  // of each pixel's mean luminance (mean_variance)
    std::vector<kernel::AccumPixel> accumulator;  // every process's, merged
    Image filtered;                               // where BatchOptions::filtered
    std::vector<ExrChannel> layers;               // where BatchOptions::layers asks
    long spp = 0;
    double seconds = 0.0;
    double paths_per_second = 0.0;
    double estimate = 0.0;         // estimated relative MSE at the end (+inf below 2 spp)
    double samples_dropped = 0.0;  // non-finite samples, never accumulated
    // Why it stopped: the rule's reason; none when cancelled or when the
    // target error cannot be reached.
    StopReason reason = StopReason::none;
    int cancelled = 0;  // non-zero: the first cancel code any process saw
    // The target error was the only rule and cannot be reached: the noise
    // estimate overflowed float (radiance samples above about 1e19).
    bool cannot_reach = false;
    bool error_reached = false;
    double filter_seconds = 0.0;
    double merge_seconds = 0.0;
    std::vector<std::int64_t> frames_per_process;
};

// Renders with `renderer` until `options.stop`. Split across a cluster's
// processes, rank r of N renders the frames r, r + N, ...; all stop after
// the same round and the first merges the accumulators. The image is a
// pure function of the scene, settings, seed and the frames rendered (in
// one process; split across processes, to float rounding: docs/mpi.md).
BatchResult render_batch(Renderer& renderer, const BatchOptions& options = BatchOptions());

// The rule render_batch follows for `given`: a part not above zero (NaN
// too) is not set; with none set, default_batch_spp.
StopRule batch_stop_rule(const StopRule& given);

// What render_batch returns, of the frames `renderer` holds now (spp: its
// frames; no timings): for a render driven frame by frame. `options`
// says whether to filter and which layers to make; its rule is not used.
BatchResult batch_images(Renderer& renderer, const BatchOptions& options);

}  // namespace trac0r

#endif
