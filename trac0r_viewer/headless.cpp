#include "headless.h"

#include "startup.h"

#include "trac0r/batch.h"
#include "trac0r/image_io.h"
#include "trac0r/kernel/filter.h"
#include "trac0r/noise.h"
#include "trac0r/packed_scene.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
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

// One progress line; on a terminal redrawn in place (render_batch reports
// at most 10 times a second), in a log every 10%.
class Progress {
  public:
    Progress() : tty_(isatty(2) != 0) {}

    void update(const trac0r::BatchProgress& p) {
        if (!tty_ && p.fraction < next_log_fraction_) {
            return;
        }
        next_log_fraction_ = std::floor(p.fraction * 10.0 + 1.0) / 10.0;
        draw(p.spp, p.seconds, p.paths_per_second, p.estimate, p.fraction);
    }

    // The last line: 100 % for a render that ran to its rule, the fraction
    // done for one that was interrupted.
    void finish(const trac0r::BatchResult& r, const trac0r::StopRule& rule) {
        if (!tty_ && r.spp == last_drawn_spp_) {
            return;  // the log already has this line
        }
        const double fraction =
            r.cancelled != 0 ? rule.fraction(r.spp, r.seconds, r.estimate) : 1.0;
        draw(r.spp, r.seconds, r.paths_per_second, r.estimate, fraction);
        if (tty_) {
            std::fputc('\n', stderr);
        }
    }

  private:
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

    bool tty_;
    double next_log_fraction_ = 0.0;
    long last_drawn_spp_ = -1;
};

// SIGINT or SIGTERM during a batch render (0: none yet). The frame in
// flight finishes, the image so far is written, and the exit status says
// which signal came (130, 143). The handler is reset by its first signal,
// so a second one ends the program at once.
std::atomic<int> interrupt_signal(0);  // lock-free: set from the handler

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

// --spp, --seconds and --target-error (none: render_batch's default spp).
trac0r::StopRule batch_stop_rule(const Options& options) {
    trac0r::StopRule rule;
    rule.spp = options.spp;
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

trac0r::BatchOptions image_options(const Options& options) {
    trac0r::BatchOptions o;
    o.filtered = options.filter;
    o.layers = options.exr_layers;
    return o;
}

void save_outputs(const trac0r::Image& image, const Options& options, trac0r::ViewTransform view,
                  const trac0r::BatchResult* result) {
    static const std::vector<trac0r::ExrChannel> no_layers;
    const std::vector<trac0r::ExrChannel>& layers = result != nullptr ? result->layers : no_layers;
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
    if (options.filter && result != nullptr && !result->filtered.pixels.empty()) {
        std::fprintf(stderr, "filtered in %.3f s (%d passes)\n", result->filter_seconds,
                     T0_FILTER_PASSES);
        for (const std::string& path : options.outputs) {
            write(path, result->filtered);
            write(raw_output_path(path), image);
        }
        return;
    }
    for (const std::string& path : options.outputs) {
        write(path, image);
    }
}

int run_batch(trac0r::Renderer& renderer, const Options& options, trac0r::Cluster& cluster) {
    trac0r::BatchOptions batch = image_options(options);
    batch.stop = batch_stop_rule(options);
    batch.cluster = &cluster;
    batch.cancel = &interrupt_signal;
    Progress progress;
    batch.progress = [&progress](const trac0r::BatchProgress& p) {
        progress.update(p);
        return true;
    };
    const InterruptHandlers interrupts;
    const trac0r::BatchResult r = trac0r::render_batch(renderer, batch);
    const int signal_number = r.cancelled > 0 ? r.cancelled : 0;
    const int code = r.cannot_reach ? 1 : (signal_number != 0 ? 128 + signal_number : 0);
    if (!r.first) {
        return code;
    }
    if (r.reason == trac0r::StopReason::full) {
        std::fprintf(stderr,
                     "%s: stopped at %u spp, the most a pixel's sample count "
                     "(a float) holds exactly\n",
                     program_name(), trac0r::Renderer::max_frames);
    }
    progress.finish(r, trac0r::batch_stop_rule(batch.stop));
    const long ranks = cluster.size();
    if (options.verbose && ranks > 1) {
        std::string frames;
        for (std::int64_t f : r.frames_per_process) {
            frames += " " + std::to_string(f);
        }
        std::fprintf(stderr, "frames per rank (0 to %ld):%s\n", ranks - 1, frames.c_str());
        std::fprintf(stderr, "merged %ld ranks' accumulators (%.1f MB each) in %.3f s\n", ranks,
                     1e-6 * static_cast<double>(r.accumulator.size() * sizeof(r.accumulator[0])),
                     r.merge_seconds);
    }
    const trac0r::ViewTransform view = renderer.scene().render.view;
    if (r.cannot_reach) {
        std::fprintf(stderr,
                     "%s: --target-error cannot be reached: the noise "
                     "estimate has overflowed (a pixel's squared deviations exceed "
                     "float's range: radiance samples above about 1e19); give --spp "
                     "or --seconds instead (the image so far is written)\n",
                     program_name());
        save_outputs(r.image, options, view, &r);
        return code;
    }
    if (signal_number != 0) {
        std::fprintf(stderr,
                     "%s: interrupted by %s after %ld spp (%.2f s): writing the "
                     "image so far\n",
                     program_name(), signal_number == SIGINT ? "SIGINT" : "SIGTERM", r.spp,
                     r.seconds);
        save_outputs(r.image, options, view, &r);
        return code;
    }
    std::fprintf(stderr,
                 "rendered %ld spp of %dx%d in %.2f s (%.2f Mpaths/s); %.0f non-finite "
                 "samples dropped\n",
                 r.spp, renderer.width(), renderer.height(), r.seconds, r.paths_per_second * 1e-6,
                 r.samples_dropped);
    if (options.target_error > 0.0) {
        if (r.error_reached) {
            std::fprintf(stderr,
                         "target error reached: estimated relative MSE %.4g <= %.4g "
                         "after %ld spp, %.2f s\n",
                         r.estimate, options.target_error, r.spp, r.seconds);
        } else {
            std::fprintf(
                stderr,
                "target error NOT reached: estimated relative MSE %.4g > %.4g "
                "when the %s limit stopped the render (%ld spp, %.2f s)%s\n",
                r.estimate, options.target_error,
                r.reason == trac0r::StopReason::full ? "16777216-spp" : spp_done_reason(options),
                r.spp, r.seconds,
                trac0r::noise_estimate_overflowed(r.accumulator)
                    ? "; the noise estimate has overflowed float (radiance samples "
                      "above about 1e19) and cannot fall"
                    : "");
        }
    }
    save_outputs(r.image, options, view, &r);
    // A signal that came while the outputs were written (they are whole:
    // output_file.h) still says so in the exit status.
    const int late = interrupt_signal.load();
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
        const trac0r::BatchResult images = trac0r::batch_images(renderer, image_options(options));
        save_outputs(images.image, options, renderer.scene().render.view, &images);
    }
    return 0;
}

}  // namespace trac0r_viewer
