#include "headless.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <vector>

namespace trac0r_viewer {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// One progress line; on a terminal redrawn in place, in a log every 10%.
class Progress {
  public:
    explicit Progress(long total_spp, double total_seconds)
        : total_spp_(total_spp), total_seconds_(total_seconds), tty_(isatty(2) != 0) {}

    void update(long spp, double elapsed, double paths_per_second) {
        const double fraction = total_spp_ > 0 ? static_cast<double>(spp) / total_spp_
                                               : elapsed / total_seconds_;
        const double now = elapsed;
        if (tty_ ? now - last_draw_ < 0.1 : fraction < next_log_fraction_) {
            return;
        }
        last_draw_ = now;
        next_log_fraction_ = fraction + 0.1;
        draw(spp, elapsed, paths_per_second, std::min(1.0, fraction));
    }

    void finish(long spp, double elapsed, double paths_per_second) {
        if (!tty_ && spp == last_drawn_spp_) {
            return;  // the log already has this line
        }
        draw(spp, elapsed, paths_per_second, 1.0);
        if (tty_) {
            std::fputc('\n', stderr);
        }
    }

  private:
    void draw(long spp, double elapsed, double paths_per_second, double fraction) {
        last_drawn_spp_ = spp;
        const int width = 30;
        const int filled = static_cast<int>(fraction * width);
        const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
        std::fprintf(stderr, "%s[%s%s] %3.0f%%  %ld spp  %.1f s  ETA %.1f s  %.2f Mpaths/s%s",
                     tty_ ? "\r" : "", std::string(filled, '#').c_str(),
                     std::string(width - filled, '.').c_str(), 100.0 * fraction, spp, elapsed,
                     eta, paths_per_second * 1e-6, tty_ ? "   " : "\n");
        std::fflush(stderr);
    }

    long total_spp_;
    double total_seconds_;
    bool tty_;
    double last_draw_ = -1.0;
    double next_log_fraction_ = 0.0;
    long last_drawn_spp_ = -1;
};

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

void save_outputs(trac0r::Renderer& renderer, const Options& options) {
    if (options.outputs.empty()) {
        return;
    }
    const trac0r::Image image = renderer.image();
    for (const std::string& path : options.outputs) {
        trac0r::write_image(path, image, options.exposure);
        std::fprintf(stderr, "wrote %s\n", path.c_str());
    }
}

}  // namespace

int run_batch(trac0r::Renderer& renderer, const Options& options) {
    const long target_spp = options.spp > 0 ? options.spp : (options.seconds > 0.0 ? 0 : 64);
    const double pixels = static_cast<double>(renderer.width()) * renderer.height();
    Progress progress(target_spp, options.seconds);
    const Clock::time_point start = Clock::now();
    long spp = 0;
    for (;;) {
        const double elapsed = seconds_since(start);
        const bool spp_done = target_spp > 0 && spp >= target_spp;
        const bool time_done = options.seconds > 0.0 && elapsed >= options.seconds;
        if (spp_done || time_done) {
            break;
        }
        renderer.render_frame();
        ++spp;
        const double now = seconds_since(start);
        progress.update(spp, now, spp * pixels / now);
    }
    const double elapsed = seconds_since(start);
    const double paths_per_second = elapsed > 0.0 ? spp * pixels / elapsed : 0.0;
    progress.finish(spp, elapsed, paths_per_second);
    const trac0r::RenderStats stats = renderer.stats();
    std::fprintf(stderr, "rendered %ld spp of %dx%d in %.2f s (%.2f Mpaths/s); %.0f non-finite "
                         "samples dropped\n",
                 spp, renderer.width(), renderer.height(), elapsed, paths_per_second * 1e-6,
                 stats.samples_dropped);
    save_outputs(renderer, options);
    return 0;
}

int run_benchmark(trac0r::Renderer& renderer, const Options& options) {
    std::vector<double> frame_seconds;
    frame_seconds.reserve(static_cast<std::size_t>(options.benchmark_frames));
    for (long i = 0; i < options.benchmark_frames; ++i) {
        const Clock::time_point start = Clock::now();
        renderer.render_frame();
        frame_seconds.push_back(seconds_since(start));
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
         << ", \"min_fps\": " << 1.0 / sorted.back() << ", \"ms_per_frame\": "
         << 1e3 * mean_seconds << ", \"paths_per_second\": " << pixels / mean_seconds
         << ", \"width\": " << renderer.width() << ", \"height\": " << renderer.height()
         << ", \"triangles\": " << renderer.packed().triangles.size() << ", \"backend\": \""
         << json_escape(renderer.backend().name()) << "\", \"device\": \""
         << json_escape(renderer.backend().device()) << "\"}";
    std::cout << json.str() << std::endl;
    save_outputs(renderer, options);
    return 0;
}

}  // namespace trac0r_viewer
