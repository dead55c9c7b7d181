// A value made from the accumulation that costs time to make (the noise
// estimate, the filtered image), refreshed by one rule: at most every
// `interval` seconds and no more often than `cost_factor` times what it
// last cost, at once when the accumulation has paused, and only for
// samples it was not made from.
#ifndef TRAC0R_VIEWER_REFRESHED_H
#define TRAC0R_VIEWER_REFRESHED_H

#include <algorithm>
#include <chrono>
#include <cstdint>

template <typename T>
class Refreshed {
  public:
    using Clock = std::chrono::steady_clock;

    Refreshed(double interval, double cost_factor)
        : interval_(interval), cost_factor_(cost_factor) {}

    // The value for an accumulation of `spp` samples: make() when due, else
    // the last one made.
    template <typename Make>
    const T& get(std::uint32_t spp, bool paused, Make make) {
        const double wait = std::max(interval_, cost_factor_ * cost_);
        const bool due = spp_ == 0 || seconds_since(made_) >= wait || paused;
        if (due && spp_ != spp) {
            const Clock::time_point start = Clock::now();
            value_ = make();
            spp_ = spp;
            made_ = Clock::now();
            cost_ = seconds_since(start);
        }
        return value_;
    }

    // The samples the value was made from; 0: none since the last restart.
    std::uint32_t spp() const { return spp_; }
    const T& value() const { return value_; }
    // A new accumulation: the next get() makes the value at once.
    void restart() { spp_ = 0; }

  private:
    static double seconds_since(Clock::time_point t) {
        return std::chrono::duration<double>(Clock::now() - t).count();
    }

    double interval_;
    double cost_factor_;
    T value_{};
    std::uint32_t spp_ = 0;
    Clock::time_point made_;
    double cost_ = 0.0;  // seconds
};

#endif
