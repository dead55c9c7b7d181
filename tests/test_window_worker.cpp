// The window's render thread (trac0r_viewer/window_worker.h), without a
// window: what it does with requests that come in during a frame.
#include <catch2/catch.hpp>

#include "trac0r_viewer/window_worker.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/fly_camera.h"
#include "trac0r/scene_loader.h"

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

using trac0r_viewer::RenderWorker;
using trac0r_viewer::WorkerFrame;

namespace {

// Where the test and the backend meet: whether a full (cancellable) frame
// has started, and whether its cancel check said stop.
struct Gate {
    std::mutex mutex;
    std::condition_variable changed;
    int full_frames_started = 0;
    int full_frames_cancelled = 0;
};

// The CPU backend, but a full frame (one with a cancel check) does not end
// on its own: it waits for its cancel check to say stop, for at most a
// minute (then it renders, as one that cannot be cancelled would).
class WaitingBackend : public trac0r::CpuBackend {
  public:
    explicit WaitingBackend(Gate* gate) : CpuBackend(1), gate_(gate) {}
    bool render_frame_cancellable(const trac0r::kernel::CameraRecord& camera, std::uint64_t seed,
                                  std::uint32_t frame, int max_depth,
                                  const CancelCheck& cancel) override {
        if (!cancel) {
            // A preview (or render_frame, which calls this without a check).
            return CpuBackend::render_frame_cancellable(camera, seed, frame, max_depth, cancel);
        }
        {
            std::lock_guard<std::mutex> lock(gate_->mutex);
            ++gate_->full_frames_started;
        }
        gate_->changed.notify_all();
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < until) {
            if (cancel && cancel()) {
                {
                    std::lock_guard<std::mutex> lock(gate_->mutex);
                    ++gate_->full_frames_cancelled;
                }
                gate_->changed.notify_all();
                return false;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        return CpuBackend::render_frame_cancellable(camera, seed, frame, max_depth, cancel);
    }

  private:
    Gate* gate_;
};

// The built-in scene at a size that has a 1/4-resolution preview while
// moving (80 x 60).
trac0r::Scene scene_with_preview() {
    trac0r::Scene scene = trac0r::builtin_scene();
    scene.render.width = 320;
    scene.render.height = 240;
    return scene;
}

RenderWorker::BackendFactory waiting_backends(Gate* gate) {
    return [gate](const std::string&) -> std::unique_ptr<trac0r::Backend> {
        return std::make_unique<WaitingBackend>(gate);
    };
}

}  // namespace

TEST_CASE("a camera change stops the full frame in flight and shows the new view next",
          "[window_worker]") {
    const trac0r::Scene scene = scene_with_preview();
    Gate gate;
    const RenderWorker::BackendFactory make_backend = waiting_backends(&gate);
    std::mutex frame_mutex;
    std::condition_variable frame_ready;
    RenderWorker worker(std::make_unique<trac0r::Renderer>(scene, make_backend("cpu")),
                        make_backend, trac0r_viewer::WorkerSettings(),
                        [&] { frame_ready.notify_all(); });

    // The first full frame is in flight, and would wait a minute.
    {
        std::unique_lock<std::mutex> lock(gate.mutex);
        REQUIRE(gate.changed.wait_for(lock, std::chrono::seconds(60),
                                      [&] { return gate.full_frames_started >= 1; }));
    }
    const trac0r::Camera moved = trac0r::move_camera(scene.camera, glm::vec3(0.0f, 0.0f, 0.1f));
    const std::uint64_t generation = worker.set_camera(moved);

    // The frame in flight stops, and the next one shown is of the new view:
    // a preview, rendered after the stop.
    WorkerFrame frame;
    bool shown = false;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(50);
    while (!shown && std::chrono::steady_clock::now() < until) {
        std::unique_lock<std::mutex> lock(frame_mutex);
        frame_ready.wait_for(lock, std::chrono::milliseconds(50));
        shown = worker.take_frame(&frame);
    }
    REQUIRE(worker.failure().empty());
    REQUIRE(shown);
    CHECK(frame.generation == generation);
    CHECK(frame.preview);
    CHECK(frame.image.width == 80);
    CHECK(worker.cancelled_frames() == 1);
    std::lock_guard<std::mutex> lock(gate.mutex);
    CHECK(gate.full_frames_cancelled == 1);
}

TEST_CASE(
    "while the camera moves on its own, only previews are rendered, and a stop renders "
    "in full",
    "[window_worker]") {
    const trac0r::Scene scene = scene_with_preview();
    Gate gate;
    const RenderWorker::BackendFactory make_backend = waiting_backends(&gate);
    RenderWorker worker(std::make_unique<trac0r::Renderer>(scene, make_backend("cpu")),
                        make_backend, trac0r_viewer::WorkerSettings(), [] {});
    {
        std::unique_lock<std::mutex> lock(gate.mutex);
        REQUIRE(gate.changed.wait_for(lock, std::chrono::seconds(60),
                                      [&] { return gate.full_frames_started >= 1; }));
    }
    // A movement key goes down: the view changes every tick. Between two
    // ticks a full frame would be stopped by the next change; none starts.
    worker.set_moving(true);
    const std::uint64_t generation =
        worker.set_camera(trac0r::move_camera(scene.camera, glm::vec3(0.0f, 0.0f, 0.1f)));
    WorkerFrame frame;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(50);
    bool shown = false;
    while (!shown && std::chrono::steady_clock::now() < until) {
        shown = worker.take_frame(&frame);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    REQUIRE(shown);
    CHECK(frame.generation == generation);
    CHECK(frame.preview);
    // A tick is 10 ms; a quarter of a second of no change is far past one.
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    {
        std::lock_guard<std::mutex> lock(gate.mutex);
        CHECK(gate.full_frames_started == 1);  // the first, stopped by the move
        CHECK(gate.full_frames_cancelled == 1);
    }
    CHECK_FALSE(worker.take_frame(&frame));  // nothing new: no preview of the same view

    // The key comes up: the full accumulation of where the view stopped.
    worker.set_moving(false);
    std::unique_lock<std::mutex> lock(gate.mutex);
    CHECK(gate.changed.wait_for(lock, std::chrono::seconds(60),
                                [&] { return gate.full_frames_started >= 2; }));
    REQUIRE(worker.failure().empty());
}
