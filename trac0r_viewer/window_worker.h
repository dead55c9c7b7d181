// The window's render thread. A frame takes up to seconds, so rendering
// runs here and the window's thread only handles input and drawing.
//
// The Renderer is not thread-safe: this thread owns it outright. The window
// sends requests (camera, restart, backend), which the thread applies
// between frames, and takes copies of finished frames under a mutex.
//
// While the camera moves (a new camera arrived during the last frame), the
// thread renders single frames at a reduced resolution, so navigation stays
// fluid; once it stops, accumulation restarts at full resolution. A request
// that throws the accumulation away (a camera, a restart) stops the full
// frame in flight between two tiles, so the next frame starts at once; a
// preview in flight is finished and shown (it is the newest view there is).
//
// Each frame shown is blended with the one before it, reprojected into its
// view (trac0r/temporal.h): while moving, the image keeps what the last
// view saw and starts again only where something came into sight; after a
// stop, what the moves left fades out over the first full frames. The
// accumulation itself is never touched.
#ifndef TRAC0R_VIEWER_WINDOW_WORKER_H
#define TRAC0R_VIEWER_WINDOW_WORKER_H

#include "refreshed.h"
#include "view_history.h"

#include "trac0r/camera.h"
#include "trac0r/filter.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/renderer.h"
#include "trac0r/stop_rule.h"
#include "trac0r/temporal.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace trac0r_viewer {

// How often the worker refreshes WorkerFrame::relative_mse: at most every
// noise_estimate_interval seconds, and, where one estimate takes long (it
// reads every pixel's 5 x 5 neighbourhood: about 0.1 s at 1920 x 1080 on
// one core), no more often than noise_estimate_cost_factor times its cost,
// so it never takes more than a tenth of the render thread's time.
constexpr double noise_estimate_interval = 0.5;
constexpr double noise_estimate_cost_factor = 10.0;
// The display filter likewise: it costs several frames, so the filtered
// image is made again at most every filter_interval seconds, and no more
// often than filter_cost_factor times its cost (the last one is shown in
// between), and always for the frame a pause stops at.
constexpr double filter_interval = 0.5;
constexpr double filter_cost_factor = 4.0;

// A finished frame: the running mean and what the overlay says about it.
struct WorkerFrame {
    trac0r::Image image;         // linear radiance, as shown: temporal reuse blended in
    trac0r::Image accumulation;  // the running mean itself; empty for previews
    // With the display filter on: the accumulation through trac0r::filter_image (the
    // accumulation itself is never filtered), refreshed as said at
    // filter_interval; empty when off and for previews.
    trac0r::Image filtered;
    std::uint32_t spp = 0;
    bool preview = false;               // reduced resolution, while the camera moves
    double frame_seconds = 0.0;         // rendering and reading back this frame
    double accumulation_seconds = 0.0;  // since the accumulation (re)started; 0 for previews
    // trac0r::estimate_relative_mse of the running mean at
    // relative_mse_spp samples per pixel, refreshed as said above; +inf
    // below 2 spp and for previews.
    double relative_mse = 0.0;
    std::uint32_t relative_mse_spp = 0;
    std::uint64_t generation = 0;  // of the last request it reflects
    // Why the worker stopped after this frame ("--spp 20"), until a
    // request; empty while it goes on.
    std::string paused_by;
    // trac0r::noise_estimate_overflowed: the estimate is infinite for good.
    bool estimate_overflowed = false;
    std::string backend;
    std::string device;
    float focus_distance = 0.0f;  // of the camera the frame was rendered with
};

struct WorkerSettings {
    std::uint64_t seed = 1;
    trac0r::PackOptions pack;  // for renderers made on a backend switch
    // When the accumulation pauses (its seconds count from a restart; the
    // target error by the estimate the overlay shows).
    trac0r::StopRule stop;
};

class RenderWorker {
  public:
    // A backend by name ("cpu", "opencl"); throws, saying why, when it
    // cannot be had.
    using BackendFactory = std::function<std::unique_ptr<trac0r::Backend>(const std::string&)>;

    // Starts the thread. `frame_ready` is called from it after each frame
    // is published (and when it fails), to wake the window.
    RenderWorker(std::unique_ptr<trac0r::Renderer> renderer, BackendFactory make_backend,
                 const WorkerSettings& settings, std::function<void()> frame_ready);
    ~RenderWorker();  // stops the full frame in flight (a preview finishes), then the thread
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    // Requests, applied before the next frame. Each returns its generation:
    // frames that reflect it carry that number or a later one.
    std::uint64_t set_camera(const trac0r::Camera& camera);
    // Whether the camera is moving on its own (a movement key held): it
    // changes again within a tick, so between changes the thread renders
    // nothing rather than start a full frame that the next change stops
    // (where there is a low-resolution preview to show meanwhile).
    std::uint64_t set_moving(bool moving);
    std::uint64_t restart();
    // Renders width x height pixels from now on (the window's new size).
    std::uint64_t resize(int width, int height);
    std::uint64_t switch_backend(const std::string& name);
    // The display filter on or off (the accumulation goes on untouched).
    std::uint64_t set_filter(bool on);
    // Focuses the camera's thin lens on the surface that render pixel
    // (x, y) of the full-resolution view sees (its depth along the view
    // direction); says so, or that nothing is there. Frames that reflect
    // it carry the new focus_distance.
    std::uint64_t focus_at(int x, int y);

    // The newest frame, when there is one not taken yet.
    bool take_frame(WorkerFrame* frame);
    // Things to tell the user (a backend switch and why it failed).
    std::vector<std::string> take_messages();
    // Why the thread stopped, or empty while it runs.
    std::string failure();
    // Full frames stopped part way by a request (for the tests).
    std::uint64_t cancelled_frames();

    using Clock = std::chrono::steady_clock;

  private:
    struct Requests {
        bool camera_changed = false;
        trac0r::Camera camera;
        bool restart = false;
        int width = 0;  // > 0: a new size
        int height = 0;
        std::string backend;
        int filter = -1;   // -1: unchanged; 0: off; 1: on
        int focus_x = -1;  // >= 0: focus_at this pixel
        int focus_y = -1;
        int moving = -1;  // -1: unchanged; 0: still; 1: moving
        std::uint64_t generation = 0;
    };

    // Changes pending_ under the lock, gives it a new generation and wakes
    // the thread: what every request does.
    // Where `cancels`, the full frame in flight stops (its accumulation is
    // about to be thrown away).
    template <typename Change>
    std::uint64_t request(Change change, bool cancels);
    void run();
    bool paused() const;
    // Nothing to render until a request: paused, or between a moving
    // camera's changes.
    bool idle() const;
    // Why the accumulation is done now (publish decides it once a frame, so
    // that the frame on screen and the pause agree); empty: not done.
    std::string pause_reason_now() const;
    void apply(const Requests& requests);
    void change_backend(const std::string& name);
    void focus_on(int x, int y);
    void render_preview();
    void render_full();
    // The guides of `camera`'s view of full_'s scene, made once per view.
    const trac0r::GuideImages& guides_of(const trac0r::kernel::CameraRecord& camera);
    // Publishes `shown` (and, for a full frame, the running mean);
    // frame_seconds counts from `start`.
    void publish(trac0r::Renderer& renderer, bool preview, Clock::time_point start,
                 const trac0r::Image& shown);
    // The noise estimate of full_'s mean, or the last one while it is recent.
    double noise_estimate();
    // full_'s mean through the display filter, or the last one while recent.
    trac0r::Image filtered_image();
    void tell(const std::string& message);

    // Owned by the thread (no lock): only run() and what it calls use them.
    std::unique_ptr<trac0r::Renderer> full_;
    std::unique_ptr<trac0r::Renderer> preview_;  // made on the first move
    int preview_factor_;                         // 1: no preview
    BackendFactory make_backend_;
    WorkerSettings settings_;
    trac0r::Camera camera_;
    bool full_stale_ = false;  // full_ has not seen camera_ or a restart yet
    bool moving_ = false;      // set_moving
    Clock::time_point full_started_;
    std::uint64_t applied_generation_ = 0;
    Refreshed<double> estimate_{noise_estimate_interval, noise_estimate_cost_factor};
    std::string pause_reason_;           // of the last full frame (pause_reason_now)
    double accumulation_seconds_ = 0.0;  // how long it ran, until a pause
    bool filter_ = false;
    bool filter_has_guides_ = false;  // filter_workspace_ holds full_'s view's guides
    Refreshed<trac0r::Image> filtered_{filter_interval, filter_cost_factor};
    trac0r::FilterWorkspace filter_workspace_;  // its buffers and guides, kept between refreshes
    // The guides of one view (render_surface_guides; add_lamp_edges when
    // the filter wants them), for the filter and temporal
    // reuse: made again only for another view, size or backend.
    trac0r::GuideImages guide_images_;
    trac0r::kernel::CameraRecord guide_camera_{};
    // The preview's guides, made every moving frame into the same storage.
    trac0r::GuideImages preview_guides_;
    ViewHistory view_history_;          // temporal reuse while moving and after a stop
    std::uint32_t preview_frames_ = 0;  // previews rendered: each its own samples

    // Shared with the window's thread, under mutex_.
    std::mutex mutex_;
    std::condition_variable wake_;
    Requests pending_;
    std::uint64_t last_generation_ = 0;
    bool stop_ = false;
    bool frame_fresh_ = false;
    std::uint64_t cancelled_frames_ = 0;
    WorkerFrame frame_;
    std::vector<std::string> messages_;
    std::string failure_;
    // Set by a request that throws the accumulation away, cleared when the
    // thread takes the requests: asked between the full frame's tiles.
    std::atomic<bool> cancel_full_{false};

    std::function<void()> frame_ready_;
    std::thread thread_;  // last: starts after everything above exists
};

// The divisor of the preview's resolution: about a sixteenth of the pixels,
// but no smaller than 80 x 60; 1 (no preview) for images too small for it.
int preview_factor(int width, int height);

}  // namespace trac0r_viewer

#endif
