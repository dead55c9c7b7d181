#include "slow_step.h"
#include "options.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace trac0r_viewer {

SlowStep::SlowStep(std::string what, bool at_once)
    : what_(std::move(what)), at_once_(at_once), watcher_([this] { watch(); }) {}

SlowStep::~SlowStep() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        done_ = true;
    }
    wake_.notify_one();
    watcher_.join();
}

void SlowStep::watch() {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    const bool tty = isatty(2) != 0;
    std::unique_lock<std::mutex> lock(mutex_);
    bool shown = false;
    auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    if (!at_once_ && wake_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; })) {
        return;  // quick: nothing to say
    }
    for (;;) {
        if (!shown || tty) {
            std::fprintf(stderr, "%s%s: %s ... %.0f s%s", tty ? "\r" : "", program_name(),
                         what_.c_str(), seconds(), tty ? "" : "\n");
            std::fflush(stderr);
            shown = true;
        }
        if (wake_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; })) {
            break;
        }
    }
    std::fprintf(stderr, "%s%s: %s: done in %.2f s\n", tty ? "\r" : "", program_name(),
                 what_.c_str(), seconds());
}

}  // namespace trac0r_viewer
