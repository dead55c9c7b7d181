#include "screenshot_name.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>

namespace trac0r_viewer {

namespace {

// "trac0r-20250101-120000-123": local time to the millisecond, so that
// screenshots sort by time and two in one second do not collide.
std::string timestamped_name() {
    const auto now = std::chrono::system_clock::now();
    const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
    const long millis = static_cast<long>(
        std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() %
        1000);
    std::tm local;
    localtime_r(&seconds, &local);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
    char name[64];
    std::snprintf(name, sizeof name, "trac0r-%s-%03ld", stamp, millis);
    return name;
}

std::string in_working_directory(const std::string& name) {
    char buffer[4096];
    return getcwd(buffer, sizeof buffer) ? std::string(buffer) + "/" + name : name;
}

}  // namespace

std::string unused_screenshot_base() {
    const std::string stamp = in_working_directory(timestamped_name());
    std::string base = stamp;
    for (int n = 2; std::ifstream(base + ".png") || std::ifstream(base + ".pfm"); ++n) {
        base = stamp + "-" + std::to_string(n);
    }
    return base;
}

}  // namespace trac0r_viewer
