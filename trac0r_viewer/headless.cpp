#include "headless.h"

#include "startup.h"
#include "stop_rule.h"

#include "trac0r/filter.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/noise.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

namespace trac0r_viewer {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// One progress line; on a terminal redrawn in place (at most 10 times a
// second), in a log every 10%. The fraction done is the larger of the spp,
// seconds and target-error fractions; for the error, E / estimate, since the
// relative MSE falls as 1 / spp.
class Progress {
  public:
    explicit Progress(const StopRule& rule) : rule_(rule), tty_(isatty(2) != 0) {}

    // Whether update() would draw now: the caller computes the noise
    // estimate (a readback and a pass over the image) only then.
    bool due(long spp, double elapsed, double estimate) const {
        return tty_ ? elapsed - last_draw_ >= 0.1
                    : fraction(spp, elapsed, estimate) >= next_log_fraction_;
    }

    void update(long spp, double elapsed, double paths_per_second, double estimate) {
        last_draw_ = elapsed;
        const double f = fraction(spp, elapsed, estimate);
        next_log_fraction_ = std::floor(f * 10.0 + 1.0) / 10.0;
        draw(spp, elapsed, paths_per_second, estimate, std::min(1.0, f));
    }

    // The last line: 100 % for a render that ran to its rule, the fraction
    // done for one that was interrupted.
    void finish(long spp, double elapsed, double paths_per_second, double estimate,
                bool complete = true) {
        if (!tty_ && spp == last_drawn_spp_) {
            return;  // the log already has this line
        }
        draw(spp, elapsed, paths_per_second, estimate,
             complete ? 1.0 : std::min(1.0, fraction(spp, elapsed, estimate)));
        if (tty_) {
            std::fputc('\n', stderr);
        }
    }

  private:
    double fraction(long spp, double elapsed, double estimate) const {
        double f = 0.0;
        if (rule_.spp > 0) {
            f = std::max(f, static_cast<double>(spp) / rule_.spp);
        }
        if (rule_.seconds > 0.0) {
            f = std::max(f, elapsed / rule_.seconds);
        }
        if (rule_.target_error > 0.0 && std::isfinite(estimate) && estimate > 0.0) {
            f = std::max(f, rule_.target_error / estimate);
        }
        return f;
    }

    void draw(long spp, double elapsed, double paths_per_second, double estimate, double fraction) {
        last_drawn_spp_ = spp;
        const int width = 30;
        const int filled = static_cast<int>(fraction * width);
        const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
        char noise[48] = "";
        if (std::isfinite(estimate)) {
            std::snprintf(noise, sizeof noise, "  rel. MSE ~ %.3g", estimate);
        }
        std::fprintf(stderr, "%s[%s%s] %3.0f%%  %ld spp  %.1f s  ETA %.1f s  %.2f Mpaths/s%s%s",
                     tty_ ? "\r" : "", std::string(filled, '#').c_str(),
                     std::string(width - filled, '.').c_str(), 100.0 * fraction, spp, elapsed, eta,
                     paths_per_second * 1e-6, noise, tty_ ? "   " : "\n");
        std::fflush(stderr);
    }

    StopRule rule_;
    bool tty_;
    double last_draw_ = -1.0;
    double next_log_fraction_ = 0.0;
    long last_drawn_spp_ = -1;
};

// When --target-error next looks at the estimate: after 10% more samples
// (so a render stops at most 10% of its samples past the target, and the
// checks cost a fraction of a percent), but not before 8 spp, below which the
// per-pixel variances are too rough to stop on.
// Split across N ranks, the first check waits for 8 frames a rank: each
// rank's estimate comes from its own frames.
long next_error_check(long spp, long ranks) {
    return std::max(8L * ranks, spp + std::max(1L, spp / 10));
}

// SIGINT or SIGTERM during a batch render (0: none yet). The frame in
// flight finishes, the image so far is written, and the exit status says
// which signal came (130, 143). The handler is reset by its first signal,
// so a second one ends the program at once.
volatile std::sig_atomic_t interrupt_signal = 0;

extern "C" void on_interrupt(int signal_number) { interrupt_signal = signal_number; }

// Installs on_interrupt for the life of a batch render. A signal that was
// ignored when the program started (nohup, a background job) stays ignored.
class InterruptHandlers {
  public:
    InterruptHandlers() {
        interrupt_signal = 0;
        struct sigaction action;
        std::memset(&action, 0, sizeof action);
        action.sa_handler = on_interrupt;
        action.sa_flags = SA_RESETHAND;
        sigemptyset(&action.sa_mask);
        for (int i = 0; i < 2; ++i) {
            sigaction(kSignals[i], nullptr, &saved_[i]);
            if (saved_[i].sa_handler != SIG_IGN) {
                sigaction(kSignals[i], &action, nullptr);
            }
        }
    }
    ~InterruptHandlers() {
        for (int i = 0; i < 2; ++i) {
            sigaction(kSignals[i], &saved_[i], nullptr);
        }
    }
    InterruptHandlers(const InterruptHandlers&) = delete;
    InterruptHandlers& operator=(const InterruptHandlers&) = delete;

  private:
    static constexpr int kSignals[2] = {SIGINT, SIGTERM};
    struct sigaction saved_[2];
};

constexpr int InterruptHandlers::kSignals[2];

// --spp, --seconds and --target-error; 64 spp when none of them is given.
StopRule batch_stop_rule(const Options& options) {
    StopRule rule;
    rule.spp = options.spp > 0 ? options.spp
                               : (options.seconds > 0.0 || options.target_error > 0.0 ? 0 : 64);
    rule.seconds = options.seconds;
    rule.target_error = options.target_error;
    return rule;
}

const char* spp_done_reason(const Options& options) {
    return options.spp > 0 && options.seconds > 0.0 ? "--spp or --seconds"
                                                    : (options.spp > 0 ? "--spp" : "--seconds");
}

double percentile_sorted(const std::vector<double>& sorted, double q) {
    const std::size_t i = static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1));
    return sorted[i];
}

std::string json_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out;
}

}  // namespace

void save_outputs(const trac0r::Image& image, const Options& options, trac0r::ViewTransform view,
                  const trac0r::Renderer* renderer,
                  const std::vector<trac0r::kernel::AccumPixel>* accumulator) {
    const bool with_guides = renderer != nullptr && accumulator != nullptr;
    // The guides, made once for the --exr-layers and the --filter.
    trac0r::GuideImages guides;
    if (with_guides && (options.filter || options.exr_layers.albedo || options.exr_layers.normal ||
                        options.exr_layers.depth)) {
        guides = trac0r::render_guides(renderer->packed(), renderer->camera_record());
    }
    std::vector<trac0r::ExrChannel> layers;
    if (options.exr_layers.any() && with_guides) {
        layers = trac0r::exr_layers(options.exr_layers, guides, *accumulator);
    }
    const trac0r::ExrPrecision precision =
        options.exr_half ? trac0r::ExrPrecision::Half : trac0r::ExrPrecision::Float;
    const auto write = [&](const std::string& path, const trac0r::Image& picture) {
        if (trac0r::is_exr_path(path)) {
            trac0r::write_exr(path, picture, layers, precision);
        } else {
            trac0r::write_image(path, picture, options.exposure, view);
        }
        std::fprintf(stderr, "wrote %s\n", path.c_str());
    };
    if (options.filter && with_guides) {
        // The same kernel code on the backend that rendered.
        const std::vector<trac0r::kernel::FilterGuide> g = trac0r::filter_guides(guides);
        const int w = renderer->width();
        const int h = renderer->height();
        trac0r::Image filtered;
        const Clock::time_point start = Clock::now();
#ifdef TRAC0R_HAVE_OPENCL
        if (renderer->backend().name() == "opencl") {
            filtered = trac0r::opencl_filter_image(std::max(options.device, 0), *accumulator, w, h,
                                                   g, T0_FILTER_PASSES);
        } else
#endif
        {
            filtered = trac0r::filter_image(*accumulator, w, h, g, T0_FILTER_PASSES);
        }
        std::fprintf(stderr, "filtered in %.3f s (%d passes)\n",
                     std::chrono::duration<double>(Clock::now() - start).count(),
                     T0_FILTER_PASSES);
        for (const std::string& path : options.outputs) {
            write(path, filtered);
            write(raw_output_path(path), image);
        }
        return;
    }
    for (const std::string& path : options.outputs) {
        write(path, image);
    }
}

int run_batch(trac0r::Renderer& renderer, const Options& options, Cluster& cluster) {
    const StopRule rule = batch_stop_rule(options);
    const bool by_error = rule.target_error > 0.0;
    const int rank = cluster.rank();
    const long ranks = cluster.size();
    const bool first = rank == 0;  // draws the progress, merges, writes
    // Rank r of N renders the frames r, r + N, ...: round k is the frames
    // k N to k N + N - 1, one a rank (fewer when --spp ends inside it).
    renderer.set_frame_sequence(static_cast<std::uint32_t>(rank),
                                static_cast<std::uint32_t>(ranks));
    const double pixels = static_cast<double>(renderer.width()) * renderer.height();
    long spp = 0;  // frames rendered by all ranks together
    // The noise estimate of the whole render from a rank's own: each falls
    // as 1 / its frames, so the mean of (estimate x frames) over the ranks,
    // over all frames, estimates the whole render's. With one process it is
    // that process's estimate.
    double last_estimate = std::numeric_limits<double>::infinity();
    long estimate_spp = 0;  // of the last --target-error check
    const auto own_estimate = [&] {
        return trac0r::estimate_relative_mse(renderer.accumulator(), renderer.width(),
                                             renderer.height());
    };
    Progress progress(rule);
    const InterruptHandlers interrupts;
    const Clock::time_point start = Clock::now();
    long error_check = next_error_check(0, ranks);
    bool error_reached = false;
    bool overflowed = false;
    int signal_number = 0;  // the first signal any rank received
    double now = 0.0;       // rank 0's clock: every rank decides by it
    std::vector<RoundReport> reports;
    StopReason stopped = StopReason::none;
    for (;;) {
        if (signal_number != 0 && spp > 0) {
            break;
        }
        const bool full = spp >= static_cast<long>(trac0r::Renderer::max_frames);
        stopped = rule.reason(spp, now, error_reached, full);
        if (stopped == StopReason::full && first) {
            std::fprintf(stderr,
                         "%s: stopped at %u spp, the most a pixel's sample count "
                         "(a float) holds exactly\n",
                         program_name(), trac0r::Renderer::max_frames);
        }
        if (stopped != StopReason::none) {
            break;
        }
        long round = std::min(ranks, static_cast<long>(trac0r::Renderer::max_frames) - spp);
        if (rule.spp > 0) {
            round = std::min(round, rule.spp - spp);
        }
        if (rank < round) {
            renderer.render_frame();
        }
        spp += round;
        RoundReport mine;
        mine.signal = interrupt_signal;
        mine.frames = renderer.frames();
        mine.elapsed = seconds_since(start);
        const bool check = by_error && spp >= error_check;
        if (check) {
            mine.estimate = own_estimate();
            mine.overflowed = trac0r::noise_estimate_overflowed(renderer.accumulator());
        }
        reports = cluster.exchange(mine);
        now = reports[0].elapsed;
        for (const RoundReport& r : reports) {
            if (signal_number == 0) {
                signal_number = r.signal;
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
            error_reached = rule.error_reached(last_estimate);
            error_check = next_error_check(spp, ranks);
            // Would never stop unless --spp or --seconds bounds it: say so,
            // keep what was rendered.
            if (!error_reached && rule.spp == 0 && rule.seconds <= 0.0 && overflowed) {
                break;
            }
        }
        if (first && progress.due(spp, now, last_estimate)) {
            if (!by_error && renderer.frames() >= 2) {
                // For the display: rank 0's own, scaled to all frames.
                last_estimate = own_estimate() * static_cast<double>(renderer.frames()) /
                                static_cast<double>(spp);
            }
            progress.update(spp, now, spp * pixels / now, last_estimate);
        }
    }
    const bool cannot_reach = by_error && !error_reached && overflowed && rule.spp == 0 &&
                              rule.seconds <= 0.0 && stopped == StopReason::none &&
                              signal_number == 0;
    // One process's accumulator as it is; the ranks' merged into a copy.
    const std::vector<trac0r::kernel::AccumPixel>* merged = &renderer.accumulator();
    std::vector<trac0r::kernel::AccumPixel> merged_copy;
    const Clock::time_point merge_start = Clock::now();
    if (ranks > 1) {
        merged_copy = *merged;
        cluster.merge_to_first(merged_copy);
        merged = &merged_copy;
    }
    const std::vector<trac0r::kernel::AccumPixel>& accumulator = *merged;
    const double merge_seconds = seconds_since(merge_start);
    const int code = cannot_reach ? 1 : (signal_number != 0 ? 128 + signal_number : 0);
    if (!first) {
        return code;
    }
    const trac0r::Image image =
        trac0r::accumulated_image(accumulator, renderer.width(), renderer.height());
    const double elapsed = seconds_since(start);
    const double paths_per_second = elapsed > 0.0 ? spp * pixels / elapsed : 0.0;
    // The final estimate: the last check's, if it was at this spp (what the
    // target was judged by), else the merged accumulator's.
    if (spp >= 2 && estimate_spp != spp) {
        last_estimate =
            trac0r::estimate_relative_mse(accumulator, renderer.width(), renderer.height());
    }
    progress.finish(spp, elapsed, paths_per_second, last_estimate, signal_number == 0);
    if (options.verbose && ranks > 1) {
        std::string frames;
        for (const RoundReport& r : reports) {
            frames += " " + std::to_string(r.frames);
        }
        std::fprintf(stderr, "frames per rank (0 to %ld):%s\n", ranks - 1, frames.c_str());
        std::fprintf(stderr, "merged %ld ranks' accumulators (%.1f MB each) in %.3f s\n", ranks,
                     1e-6 * static_cast<double>(accumulator.size() * sizeof(accumulator[0])),
                     merge_seconds);
    }
    if (cannot_reach) {
        std::fprintf(stderr,
                     "%s: --target-error cannot be reached: the noise "
                     "estimate has overflowed (a pixel's squared deviations exceed "
                     "float's range: radiance samples above about 1e19); give --spp "
                     "or --seconds instead (the image so far is written)\n",
                     program_name());
        save_outputs(image, options, renderer.scene().render.view, &renderer, &accumulator);
        return code;
    }
    if (signal_number != 0) {
        std::fprintf(stderr,
                     "%s: interrupted by %s after %ld spp (%.2f s): writing the "
                     "image so far\n",
                     program_name(), signal_number == SIGINT ? "SIGINT" : "SIGTERM", spp, elapsed);
        save_outputs(image, options, renderer.scene().render.view, &renderer, &accumulator);
        return code;
    }
    double dropped = 0.0;
    for (const trac0r::kernel::AccumPixel& p : accumulator) {
        dropped += p.moments.w;
    }
    std::fprintf(stderr,
                 "rendered %ld spp of %dx%d in %.2f s (%.2f Mpaths/s); %.0f non-finite "
                 "samples dropped\n",
                 spp, renderer.width(), renderer.height(), elapsed, paths_per_second * 1e-6,
                 dropped);
    if (by_error) {
        if (error_reached) {
            std::fprintf(stderr,
                         "target error reached: estimated relative MSE %.4g <= %.4g "
                         "after %ld spp, %.2f s\n",
                         last_estimate, options.target_error, spp, elapsed);
        } else {
            std::fprintf(stderr,
                         "target error NOT reached: estimated relative MSE %.4g > %.4g "
                         "when the %s limit stopped the render (%ld spp, %.2f s)%s\n",
                         last_estimate, options.target_error,
                         stopped == StopReason::full ? "16777216-spp" : spp_done_reason(options),
                         spp, elapsed,
                         trac0r::noise_estimate_overflowed(accumulator)
                             ? "; the noise estimate has overflowed float (radiance samples "
                               "above about 1e19) and cannot fall"
                             : "");
        }
    }
    save_outputs(image, options, renderer.scene().render.view, &renderer, &accumulator);
    // A signal that came while the outputs were written (they are whole:
    // output_file.h) still says so in the exit status.
    const int late = interrupt_signal;
    if (code == 0 && late != 0) {
        std::fprintf(stderr, "%s: interrupted by %s while the image was written (it is whole)\n",
                     program_name(), late == SIGINT ? "SIGINT" : "SIGTERM");
        return 128 + late;
    }
    return code;
}

int run_benchmark(trac0r::Renderer& renderer, const Options& options,
                  const std::function<bool()>& after_frame) {
    std::vector<double> frame_seconds;
    frame_seconds.reserve(static_cast<std::size_t>(options.benchmark_frames));
    for (long i = 0; i < options.benchmark_frames; ++i) {
        const Clock::time_point start = Clock::now();
        renderer.render_frame();
        const bool go_on = !after_frame || after_frame();
        frame_seconds.push_back(seconds_since(start));
        if (!go_on) {
            std::fprintf(stderr, "trac0r_viewer: benchmark interrupted after %zu of %ld frames\n",
                         frame_seconds.size(), options.benchmark_frames);
            return 1;
        }
    }
    double total = 0.0;
    for (double s : frame_seconds) {
        total += s;
    }
    std::vector<double> sorted = frame_seconds;
    std::sort(sorted.begin(), sorted.end());
    const double pixels = static_cast<double>(renderer.width()) * renderer.height();
    const double mean_seconds = total / static_cast<double>(frame_seconds.size());
    std::ostringstream json;
    json.precision(6);
    json << "{\"frames\": " << frame_seconds.size() << ", \"mean_fps\": " << 1.0 / mean_seconds
         << ", \"median_fps\": " << 1.0 / percentile_sorted(sorted, 0.5)
         << ", \"min_fps\": " << 1.0 / sorted.back() << ", \"ms_per_frame\": " << 1e3 * mean_seconds
         << ", \"paths_per_second\": " << pixels / mean_seconds
         << ", \"width\": " << renderer.width() << ", \"height\": " << renderer.height()
         << ", \"triangles\": " << renderer.packed().triangles.size() << ", \"backend\": \""
         << json_escape(renderer.backend().name()) << "\", \"device\": \""
         << json_escape(renderer.backend().device()) << "\"}";
    std::cout << json.str() << std::endl;
    if (!options.outputs.empty()) {
        save_outputs(renderer.image(), options, renderer.scene().render.view, &renderer,
                     &renderer.accumulator());
    }
    return 0;
}

}  // namespace trac0r_viewer
