#include "trac0r/batch.h"

#include "trac0r/filter.h"
#include "trac0r/kernel/types.h"
#include "trac0r/noise.h"
#include "trac0r/packed_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

namespace trac0r {

BatchResult::BatchResult() = default;
BatchResult::~BatchResult() = default;
BatchResult::BatchResult(const BatchResult&) = default;
BatchResult::BatchResult(BatchResult&&) noexcept = default;
BatchResult& BatchResult::operator=(const BatchResult&) = default;
BatchResult& BatchResult::operator=(BatchResult&&) noexcept = default;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// When the target error next looks at the estimate: after 10% more samples
// (so a render stops at most 10% of its samples past the target, and the
// checks cost a fraction of a percent), but not before 8 spp, below which the
// per-pixel variances are too rough to stop on. Split across N ranks, the
// first check waits for 8 frames a rank: each rank's estimate comes from its
// own frames.
long next_error_check(long spp, long ranks) {
    return std::max(8L * ranks, spp + std::max(1L, spp / 10));
}

// result.accumulator's image, variance, dropped samples, and what
// `options` asks for: the filtered image and the EXR layers.
void make_images(Renderer& renderer, const BatchOptions& options, BatchResult& result) {
    const int w = renderer.width();
    const int h = renderer.height();
    result.image = accumulated_image(result.accumulator, w, h);
    result.variance = mean_variance(result.accumulator);
    result.samples_dropped = 0.0;
    for (const kernel::AccumPixel& p : result.accumulator) {
        result.samples_dropped += p.moments.w;
    }
    const ExrLayerChoice& layers = options.layers;
    if (!options.filtered && !layers.any()) {
        return;
    }
    GuideImages guides;
    if (options.filtered || layers.albedo || layers.normal || layers.depth) {
        // The lamp-edge split only for the filter: the layers hold none of it.
        guides = options.filtered
                     ? render_guides(renderer.packed(), renderer.camera_record())
                     : render_surface_guides(renderer.packed(), renderer.camera_record());
    }
    if (layers.any()) {
        result.layers = exr_layers(layers, guides, result.accumulator);
    }
    if (options.filtered) {
        const Clock::time_point filter_start = Clock::now();
        result.filtered = renderer.backend().filter_accumulation(
            result.accumulator, w, h, filter_guides(guides), T0_FILTER_PASSES);
        result.filter_seconds = seconds_since(filter_start);
    }
}

}  // namespace

StopRule batch_stop_rule(const StopRule& given) {
    StopRule rule;
    rule.spp = given.spp > 0 ? given.spp : 0;
    // Not above zero (NaN included): not set.
    rule.seconds = given.seconds > 0.0 ? given.seconds : 0.0;
    rule.target_error = given.target_error > 0.0 ? given.target_error : 0.0;
    if (rule.spp == 0 && rule.seconds == 0.0 && rule.target_error == 0.0) {
        rule.spp = default_batch_spp;
    }
    return rule;
}

BatchResult render_batch(Renderer& renderer, const BatchOptions& options) {
    SingleProcess one;
    Cluster& cluster = options.cluster != nullptr ? *options.cluster : one;
    const StopRule rule = batch_stop_rule(options.stop);
    const bool by_error = rule.target_error > 0.0;
    const int rank = cluster.rank();
    const long ranks = cluster.size();
    const bool first = rank == 0;  // reports progress, merges, makes the images
    // Rank r of N renders the frames r, r + N, ...: round k is the frames
    // k N to k N + N - 1, one a rank (fewer when the spp ends inside it).
    renderer.set_frame_sequence(static_cast<std::uint32_t>(rank),
                                static_cast<std::uint32_t>(ranks));
    const double pixels = static_cast<double>(renderer.width()) * renderer.height();
    const long max_spp = static_cast<long>(Renderer::max_frames);
    BatchResult result;
    result.first = first;
    long spp = 0;  // frames rendered by all ranks together
    // The noise estimate of the whole render from a rank's own: each falls
    // as 1 / its frames, so the mean of (estimate x frames) over the ranks,
    // over all frames, estimates the whole render's. With one process it is
    // that process's estimate.
    double last_estimate = std::numeric_limits<double>::infinity();
    long estimate_spp = 0;  // of the last target-error check
    const auto own_estimate = [&] {
        return estimate_relative_mse(renderer.accumulator(), renderer.width(), renderer.height());
    };
    const Clock::time_point start = Clock::now();
    long error_check = next_error_check(0, ranks);
    bool overflowed = false;
    int cancelled = 0;  // the first cancel code any rank saw
    int own_cancel = 0;
    double now = 0.0;  // rank 0's clock: every rank decides by it
    double next_progress = 0.0;
    // The display's estimate (without a target error) costs a readback and a
    // pass over the image (76 ms at 800 x 600 on 2 cores, a third of a
    // frame): it is made again only after 50 times its last cost, so that
    // it takes at most 2% of the render.
    double display_estimate_at = 0.0;
    double display_estimate_cost = -1.0;  // none made yet
    std::vector<RoundReport> reports;
    std::exception_ptr progress_error;
    for (;;) {
        if (cancelled != 0 && spp > 0) {
            break;
        }
        result.reason = rule.reason(spp, now, result.error_reached, spp >= max_spp);
        if (result.reason != StopReason::none) {
            break;
        }
        long round = std::min(ranks, max_spp - spp);
        if (rule.spp > 0) {
            round = std::min(round, rule.spp - spp);
        }
        if (rank < round) {
            renderer.render_frame();
        }
        spp += round;
        if (own_cancel == 0 && options.cancel != nullptr) {
            own_cancel = options.cancel->load();
        }
        RoundReport mine;
        mine.cancel = own_cancel;
        mine.frames = renderer.frames();
        mine.elapsed = seconds_since(start);
        const bool check = by_error && spp >= error_check;
        if (check) {
            mine.estimate = own_estimate();
            mine.overflowed = noise_estimate_overflowed(renderer.accumulator());
        }
        reports = cluster.exchange(mine);
        now = reports[0].elapsed;
        for (const RoundReport& r : reports) {
            if (cancelled == 0) {
                cancelled = r.cancel;
            }
        }
        if (check) {
            double weighted = 0.0;
            overflowed = false;
            for (const RoundReport& r : reports) {
                if (r.frames > 0) {  // one with none has no estimate, and no weight
                    weighted += r.estimate * static_cast<double>(r.frames);
                }
                overflowed = overflowed || r.overflowed != 0;
            }
            last_estimate = weighted / static_cast<double>(ranks) / static_cast<double>(spp);
            estimate_spp = spp;
            result.error_reached = rule.error_reached(last_estimate);
            error_check = next_error_check(spp, ranks);
            // Would never stop unless the spp or seconds bound it: say so,
            // keep what was rendered.
            if (!result.error_reached && rule.spp == 0 && rule.seconds <= 0.0 && overflowed) {
                result.cannot_reach = cancelled == 0;
                break;
            }
        }
        if (first && options.progress && now >= next_progress) {
            next_progress = now + options.progress_interval;
            if (!by_error && renderer.frames() >= 2 &&
                (display_estimate_cost < 0.0 ||
                 now - display_estimate_at >= 50.0 * display_estimate_cost)) {
                // For the display: rank 0's own, scaled to all frames.
                const Clock::time_point estimate_start = Clock::now();
                last_estimate = own_estimate() * static_cast<double>(renderer.frames()) /
                                static_cast<double>(spp);
                display_estimate_cost = seconds_since(estimate_start);
                display_estimate_at = now;
            }
            BatchProgress p;
            p.spp = spp;
            p.seconds = now;
            p.paths_per_second = now > 0.0 ? static_cast<double>(spp) * pixels / now : 0.0;
            p.estimate = last_estimate;
            p.fraction = rule.fraction(spp, now, last_estimate);
            bool go_on = false;
            try {
                go_on = options.progress(p);
            } catch (...) {
                // Raised once every rank has stopped (they wait for this
                // one's next report).
                if (!progress_error) {
                    progress_error = std::current_exception();
                }
            }
            if (!go_on && own_cancel == 0) {
                // Told to the other ranks with the next round's reports.
                own_cancel = -1;
                if (ranks == 1) {
                    cancelled = -1;
                }
            }
        }
    }
    if (cancelled != 0) {
        result.reason = StopReason::none;
    }
    result.cancelled = cancelled;
    result.spp = spp;
    for (const RoundReport& r : reports) {
        result.frames_per_process.push_back(r.frames);
    }
    // One process's accumulator as it is; the ranks' merged into rank 0's.
    result.accumulator = renderer.accumulator();
    const Clock::time_point merge_start = Clock::now();
    if (ranks > 1) {
        cluster.merge_to_first(result.accumulator);
    }
    result.merge_seconds = seconds_since(merge_start);
    if (progress_error) {
        std::rethrow_exception(progress_error);
    }
    if (!first) {
        result.accumulator.clear();
        return result;
    }
    result.seconds = seconds_since(start);
    result.paths_per_second =
        result.seconds > 0.0 ? static_cast<double>(spp) * pixels / result.seconds : 0.0;
    // The final estimate: the last check's, if it was at this spp (what the
    // target was judged by), else the merged accumulator's.
    if (spp >= 2 && estimate_spp != spp) {
        last_estimate =
            estimate_relative_mse(result.accumulator, renderer.width(), renderer.height());
    }
    result.estimate = last_estimate;
    make_images(renderer, options, result);
    return result;
}

BatchResult batch_images(Renderer& renderer, const BatchOptions& options) {
    BatchResult result;
    result.accumulator = renderer.accumulator();
    result.spp = renderer.frames();
    result.estimate = result.spp >= 2 ? estimate_relative_mse(result.accumulator, renderer.width(),
                                                              renderer.height())
                                      : std::numeric_limits<double>::infinity();
    make_images(renderer, options, result);
    return result;
}

}  // namespace trac0r
