// A line on stderr while a long step runs (loading a scene, packing it and
// building its BVH), so that a minute's load of a huge mesh is not silent:
// after a second (at once with --verbose), "trac0r_viewer: WHAT ... N s",
// redrawn every second on a terminal, and the time it took at the end.
#ifndef TRAC0R_VIEWER_SLOW_STEP_H
#define TRAC0R_VIEWER_SLOW_STEP_H

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace trac0r_viewer {

class SlowStep {
  public:
    SlowStep(std::string what, bool at_once);
    ~SlowStep();  // ends the line, if one was written
    SlowStep(const SlowStep&) = delete;
    SlowStep& operator=(const SlowStep&) = delete;

  private:
    void watch();

    std::string what_;
    bool at_once_;
    bool done_ = false;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::thread watcher_;
};

}  // namespace trac0r_viewer

#endif
