// Shared by the benchmark programs: time frames of a packed scene on a
// backend, after one warm-up frame.
//
// Wall-clock time and the process's CPU time (all its threads: OpenMP's and
// PoCL's workers). On a machine shared with other work the wall clock
// measures the load as much as the renderer, while CPU time counts only the
// time our threads ran; so the tables compare CPU time, and turn it into
// "on N free cores" figures: N cores give N CPU-seconds per second (what a
// frame's wall time is when the machine is otherwise idle: both backends use
// every core).
#ifndef TRAC0R_BENCHMARKS_TIMING_H
#define TRAC0R_BENCHMARKS_TIMING_H

#include "trac0r/backend.h"
#include "trac0r/camera.h"
#include "trac0r/packed_scene.h"
#include "trac0r/scene.h"

#include <dirent.h>
#include <omp.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <vector>

namespace trac0r_bench {

inline double clock_seconds(clockid_t clock) {
    timespec t;
    clock_gettime(clock, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Seconds of CPU time this process's threads have used: the sum of each
// live thread's own clock. Not CLOCK_PROCESS_CPUTIME_ID: Linux adds a thread
// that runs on another core to it only as the scheduler books that
// thread's time (at its ticks and switches), so over a few milliseconds it
// may count a busy worker's time twice or not at all (on this repository's
// machine a 2.8-ms frame of two busy threads read anywhere from 3.0 to
// 6.8 ms, and the sum of the two threads' own clocks 5.5 to 5.9 ms). A
// thread's clock, read from any thread of the process, is up to date. A
// thread that ends between two readings takes all its time out of the
// difference: the benchmarks keep one OpenMP team size and PoCL's workers,
// and start timing after a warm-up, so none ends. Where no thread's clock
// can be read (no /proc), the process's clock.
inline double process_cpu_seconds() {
    DIR* dir = opendir("/proc/self/task");
    if (dir == nullptr) {
        return clock_seconds(CLOCK_PROCESS_CPUTIME_ID);
    }
    double sum = 0.0;
    int read = 0;
    while (const dirent* entry = readdir(dir)) {
        const unsigned long tid = std::strtoul(entry->d_name, nullptr, 10);
        if (tid == 0) {
            continue;  // "." and ".."
        }
        // The clock of thread `tid` (what glibc's pthread_getcpuclockid
        // makes: CPUCLOCK_PERTHREAD and CPUCLOCK_SCHED).
        const clockid_t clock = static_cast<clockid_t>((~tid << 3) | 6u);
        timespec t;
        if (clock_gettime(clock, &t) == 0) {
            sum += static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
            ++read;
        }
    }
    closedir(dir);
    return read > 0 ? sum : clock_seconds(CLOCK_PROCESS_CPUTIME_ID);
}

// Seconds of CPU time of the calling thread alone: for work timed on one
// thread, which OpenMP's idle workers must not add to.
inline double thread_cpu_seconds() { return clock_seconds(CLOCK_THREAD_CPUTIME_ID); }

// The cores that the "on N free cores" figures assume.
inline int machine_cores() { return omp_get_num_procs(); }

struct Timing {
    double build_seconds;      // set_scene: upload, and the OpenCL program build
    double frame_seconds;      // wall clock, mean over the timed frames
    double cpu_frame_seconds;  // CPU time of all threads, mean over the timed frames
    // A frame's seconds on machine_cores() free cores: CPU time / cores.
    double free_frame_seconds() const { return cpu_frame_seconds / machine_cores(); }
};

// The camera of the scene at its resolution.
inline trac0r::kernel::CameraRecord scene_camera(const trac0r::Scene& scene) {
    return trac0r::make_camera_record(scene.camera, scene.render.width, scene.render.height);
}

// Gives the backend the packed scene, clears its accumulator and renders
// one warm-up frame (frame 0); returns the seconds set_scene took (the
// upload, and the OpenCL program build).
inline double prepare(trac0r::Backend& backend, const trac0r::PackedScene& packed,
                      const trac0r::Scene& scene) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point build_start = Clock::now();
    backend.set_scene(packed);
    const double build = std::chrono::duration<double>(Clock::now() - build_start).count();
    backend.reset(scene.render.width, scene.render.height);
    backend.render_frame(scene_camera(scene), 1, 0, scene.render.max_depth);
    return build;
}

inline Timing measure(trac0r::Backend& backend, const trac0r::PackedScene& packed,
                      const trac0r::Scene& scene, int frames) {
    using Clock = std::chrono::steady_clock;
    const double build = prepare(backend, packed, scene);
    const trac0r::kernel::CameraRecord camera = scene_camera(scene);
    const Clock::time_point start = Clock::now();
    const double cpu_start = process_cpu_seconds();
    for (int i = 1; i <= frames; ++i) {
        backend.render_frame(camera, 1, static_cast<std::uint32_t>(i), scene.render.max_depth);
    }
    const double cpu = process_cpu_seconds() - cpu_start;
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return {build, seconds / frames, cpu / frames};
}

// Frames of two set-ups alternated (a, b, a, b, ...), after one warm-up
// frame of each, so that a change in the machine's load falls on both
// alike: each frame's CPU seconds (all threads).
struct Alternated {
    std::vector<double> a;
    std::vector<double> b;
};

inline Alternated measure_alternated(trac0r::Backend& a, const trac0r::PackedScene& packed_a,
                                     trac0r::Backend& b, const trac0r::PackedScene& packed_b,
                                     const trac0r::Scene& scene, int rounds) {
    const trac0r::kernel::CameraRecord camera = scene_camera(scene);
    trac0r::Backend* backends[2] = {&a, &b};
    prepare(a, packed_a, scene);
    prepare(b, packed_b, scene);
    Alternated out;
    for (int i = 1; i <= rounds; ++i) {
        for (int k = 0; k < 2; ++k) {
            const double start = process_cpu_seconds();
            backends[k]->render_frame(camera, 1, static_cast<std::uint32_t>(i),
                                      scene.render.max_depth);
            (k == 0 ? out.a : out.b).push_back(process_cpu_seconds() - start);
        }
    }
    return out;
}

// The scene packed with the given structure.
inline trac0r::PackedScene pack_with(const trac0r::Scene& scene, trac0r::Accel accel) {
    trac0r::PackOptions options;
    options.accel = accel;
    return trac0r::pack_scene(scene, options);
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace trac0r_bench

#endif
