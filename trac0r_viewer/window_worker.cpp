#include "window_worker.h"

#include "trac0r/kernel/guides.h"
#include "trac0r/noise.h"
#include "trac0r/packed_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>

namespace trac0r_viewer {

namespace {

using Clock = RenderWorker::Clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int preview_factor(int width, int height) {
    return std::max(1, std::min(4, std::min(width / 80, height / 60)));
}

RenderWorker::RenderWorker(std::unique_ptr<trac0r::Renderer> renderer, BackendFactory make_backend,
                           const WorkerSettings& settings, std::function<void()> frame_ready)
    : full_(std::move(renderer)),
      preview_factor_(preview_factor(full_->width(), full_->height())),
      make_backend_(std::move(make_backend)),
      settings_(settings),
      camera_(full_->scene().camera),
      full_started_(Clock::now()),
      view_history_(
          [this](const trac0r::kernel::CameraRecord& camera) -> const trac0r::GuideImages& {
              return guides_of(camera);
          }),
      frame_ready_(std::move(frame_ready)),
      thread_(&RenderWorker::run, this) {}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        cancel_full_.store(true);  // nobody will see the frame in flight
    }
    wake_.notify_all();
    thread_.join();
}

template <typename Change>
std::uint64_t RenderWorker::request(Change change, bool cancels) {
    std::uint64_t generation;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        change(pending_);
        generation = pending_.generation = ++last_generation_;
        if (cancels) {
            cancel_full_.store(true);
        }
    }
    wake_.notify_all();
    return generation;
}

std::uint64_t RenderWorker::set_camera(const trac0r::Camera& camera) {
    return request(
        [&](Requests& r) {
            r.camera_changed = true;
            r.camera = camera;
        },
        true);
}

std::uint64_t RenderWorker::set_moving(bool moving) {
    return request([&](Requests& r) { r.moving = moving ? 1 : 0; }, false);
}

std::uint64_t RenderWorker::restart() {
    return request([](Requests& r) { r.restart = true; }, true);
}

std::uint64_t RenderWorker::resize(int width, int height) {
    return request(
        [&](Requests& r) {
            r.width = width;
            r.height = height;
        },
        true);
}

std::uint64_t RenderWorker::set_filter(bool on) {
    return request([&](Requests& r) { r.filter = on ? 1 : 0; }, false);
}

std::uint64_t RenderWorker::focus_at(int x, int y) {
    return request(
        [&](Requests& r) {
            r.focus_x = x;
            r.focus_y = y;
        },
        true);
}

std::uint64_t RenderWorker::switch_backend(const std::string& name) {
    // Not cancelling: the switch may fail, and the accumulation go on.
    return request([&](Requests& r) { r.backend = name; }, false);
}

bool RenderWorker::take_frame(WorkerFrame* frame) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!frame_fresh_) {
        return false;
    }
    *frame = std::move(frame_);
    frame_fresh_ = false;
    return true;
}

std::vector<std::string> RenderWorker::take_messages() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> messages;
    messages.swap(messages_);
    return messages;
}

std::string RenderWorker::failure() {
    std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
}

std::uint64_t RenderWorker::cancelled_frames() {
    std::lock_guard<std::mutex> lock(mutex_);
    return cancelled_frames_;
}

void RenderWorker::tell(const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    messages_.push_back(message);
}

// --spp, --seconds, --target-error (and the 2^24 samples a pixel's count
// holds): the image is done; nothing to do until a request.
bool RenderWorker::paused() const { return !full_stale_ && !pause_reason_.empty(); }

bool RenderWorker::idle() const { return paused() || (moving_ && preview_factor_ > 1); }

std::string RenderWorker::pause_reason_now() const {
    const trac0r::StopRule& stop = settings_.stop;
    // The target by the last estimate (refreshed about twice a second, so the
    // window pauses within about half a second of reaching it), from 8 spp
    // on, as a batch render checks it.
    const bool error_reached = estimate_.spp() >= 8 && stop.error_reached(estimate_.value());
    switch (
        stop.reason(full_->frames(), seconds_since(full_started_), error_reached, full_->full())) {
    case trac0r::StopReason::spp:
        return "--spp " + std::to_string(stop.spp);
    case trac0r::StopReason::seconds: {
        char text[64];
        std::snprintf(text, sizeof text, "--seconds %g", stop.seconds);
        return text;
    }
    case trac0r::StopReason::full:
        return "the most a pixel's sample count holds";
    case trac0r::StopReason::target_error: {
        char text[64];
        std::snprintf(text, sizeof text, "--target-error %g", stop.target_error);
        return text;
    }
    case trac0r::StopReason::none:
        break;
    }
    return "";
}

void RenderWorker::run() {
    try {
        for (;;) {
            Requests requests;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] {
                    return stop_ || pending_.generation != applied_generation_ || !idle();
                });
                if (stop_) {
                    return;
                }
                requests = pending_;
                pending_ = Requests();
                pending_.generation = requests.generation;
                cancel_full_.store(false);  // the requests so far are in hand
            }
            apply(requests);
            if (paused()) {
                // A request that changed nothing (a backend switch to the
                // backend in use, or one that failed): the same image under
                // the new generation, not one more sample past --spp.
                const trac0r::Image& last = view_history_.last_full_frame();
                publish(*full_, false, Clock::now(), last.pixels.empty() ? full_->image() : last);
            } else if (requests.camera_changed && preview_factor_ > 1) {
                render_preview();
            } else if (!idle()) {
                render_full();
            }
        }
    } catch (const std::exception& e) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            failure_ = e.what();
        }
        frame_ready_();
    }
}

// The guides' first-hit depth (along the view direction) of the pixel's
// centre ray: the distance at which the thin lens is sharp there.
void RenderWorker::focus_on(int x, int y) {
    const int width = full_->width();
    const int height = full_->height();
    x = std::max(0, std::min(width - 1, x));
    y = std::max(0, std::min(height - 1, y));
    const trac0r::PackedScene& packed = full_->packed();
    const trac0r::kernel::SceneView view = packed.view();
    const trac0r::kernel::CameraRecord record =
        trac0r::scaled_camera(trac0r::make_camera_record(camera_, width, height), packed.scale);
    const trac0r::kernel::GuidePixel g = trac0r::kernel::pixel_guides(
        &view, record, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
    if (!(g.albedo.w > 0.0f && g.albedo.w < T0_NO_HIT)) {
        tell("focus: nothing under the mouse to focus on");
        return;
    }
    const float depth = g.albedo.w / packed.scale;
    camera_.focus_distance = depth;
    full_stale_ = true;
    char text[128];
    std::snprintf(text, sizeof text, "focus at %.3g m (aperture radius %.3g m)", depth,
                  camera_.aperture_radius);
    tell(text);
}

void RenderWorker::apply(const Requests& requests) {
    if (requests.camera_changed) {
        camera_ = requests.camera;
        full_stale_ = true;
    }
    if (requests.restart) {
        full_stale_ = true;
        view_history_.drop();
    }
    if (requests.focus_x >= 0) {
        focus_on(requests.focus_x, requests.focus_y);
    }
    if (requests.width > 0 &&
        (requests.width != full_->width() || requests.height != full_->height())) {
        full_->set_size(requests.width, requests.height);
        preview_.reset();  // made again at the new size on the next move
        preview_factor_ = preview_factor(requests.width, requests.height);
        full_stale_ = true;
    }
    if (!requests.backend.empty()) {
        change_backend(requests.backend);
    }
    if (requests.filter >= 0) {
        filter_ = requests.filter == 1;
    }
    if (requests.moving >= 0) {
        moving_ = requests.moving == 1;
    }
    applied_generation_ = requests.generation;
}

// A new Renderer on the new backend: the Renderer has no way to swap its
// backend, and packing the scene again costs far less than a frame.
void RenderWorker::change_backend(const std::string& name) {
    const std::string current = full_->backend().name();
    if (name == current) {
        return;
    }
    try {
        trac0r::Scene scene = full_->scene();
        scene.camera = camera_;
        full_ = std::make_unique<trac0r::Renderer>(scene, make_backend_(name), settings_.seed,
                                                   settings_.pack);
        preview_.reset();  // made again on the new backend when needed
        full_stale_ = true;
        view_history_.drop();
        guide_images_ = trac0r::GuideImages();
        tell("backend: " + name + " (" + full_->backend().device() + ")");
    } catch (const std::exception& e) {
        tell("cannot switch to " + name + ": " + e.what() + "; staying on " + current);
    }
}

void RenderWorker::render_preview() {
    if (!preview_) {
        trac0r::Scene scene = full_->scene();
        scene.camera = camera_;
        scene.render.width /= preview_factor_;
        scene.render.height /= preview_factor_;
        // Next-event estimation whatever the integrator: one naive sample
        // a pixel finds the lamp by chance, and the moving view was black
        // but for scattered dots; with a light sample at every diffuse hit
        // it shows the lit room. Both converge to the same image, and the
        // preview never accumulates.
        trac0r::PackOptions pack = settings_.pack;
        pack.integrator = trac0r::Integrator::nee;
        try {
            preview_ = std::make_unique<trac0r::Renderer>(
                scene, make_backend_(full_->backend().name()), settings_.seed, pack);
        } catch (const std::exception& e) {
            // Navigation still works, at full resolution.
            tell(std::string("no low-resolution preview while moving: ") + e.what());
            preview_factor_ = 1;
            render_full();
            return;
        }
    }
    const Clock::time_point start = Clock::now();
    preview_->set_camera(camera_);  // one frame per camera: no accumulation
    // Each preview its own samples: with the same ones every frame, the
    // noise would stand still on the screen while the view slides under it,
    // and temporal reuse would smear it into streaks.
    preview_->set_frame_sequence(preview_frames_++, 1);
    preview_->render_frame();
    trac0r::render_surface_guides(preview_->packed(), preview_->camera_record(), &preview_guides_);
    const trac0r::Image shown =
        view_history_.preview(preview_->image(), static_cast<float>(preview_->frames()),
                              preview_->camera_record(), preview_guides_);
    publish(*preview_, true, start, shown);
}

const trac0r::GuideImages& RenderWorker::guides_of(const trac0r::kernel::CameraRecord& camera) {
    if (guide_images_.width == 0 || std::memcmp(&camera, &guide_camera_, sizeof camera) != 0) {
        trac0r::render_surface_guides(full_->packed(), camera, &guide_images_);
        guide_camera_ = camera;
    }
    return guide_images_;
}

void RenderWorker::render_full() {
    if (full_stale_) {
        // What was shown last (the moves' frames, or the old view's
        // accumulation) is carried into the new accumulation's first
        // frames.
        view_history_.start_accumulation();
        full_->set_camera(camera_);  // restarts accumulation
        full_started_ = Clock::now();
        full_stale_ = false;
        estimate_.restart();
        filter_has_guides_ = false;  // a new view or size: made again when the filter is on
        filtered_.restart();
        pause_reason_.clear();
    }
    const Clock::time_point start = Clock::now();
    if (!full_->render_frame([this] { return cancel_full_.load(std::memory_order_relaxed); })) {
        // A camera or a restart came in: the renderer has restarted, and
        // the request in hand starts a new accumulation.
        full_stale_ = true;
        std::lock_guard<std::mutex> lock(mutex_);
        ++cancelled_frames_;
        return;
    }
    const trac0r::Image shown =
        view_history_.full_frame(full_->image(), full_->frames(), full_->camera_record());
    publish(*full_, false, start, shown);
}

double RenderWorker::noise_estimate() {
    if (full_->frames() < 2) {
        return std::numeric_limits<double>::infinity();
    }
    // Fresh when there is none for this accumulation yet, when it is old,
    // and for the last frame before a --spp or --seconds pause, which stays
    // on screen.
    return estimate_.get(full_->frames(), paused(), [&] {
        return trac0r::estimate_relative_mse(full_->accumulator(), full_->width(), full_->height());
    });
}

trac0r::Image RenderWorker::filtered_image() {
    return filtered_.get(full_->frames(), paused(), [&] {
        if (!filter_has_guides_) {
            guides_of(full_->camera_record());
            trac0r::add_lamp_edges(full_->packed(), full_->camera_record(), &guide_images_);
            filter_workspace_.set_guides(guide_images_);
            filter_has_guides_ = true;  // only once set_guides has not thrown
        }
        return trac0r::filter_image(full_->accumulator(), T0_FILTER_PASSES, filter_workspace_);
    });
}

void RenderWorker::publish(trac0r::Renderer& renderer, bool preview, Clock::time_point start,
                           const trac0r::Image& shown) {
    WorkerFrame frame;
    frame.image = shown;
    if (!preview) {
        frame.accumulation = renderer.image();
    }
    frame.spp = renderer.frames();
    frame.preview = preview;
    frame.focus_distance = camera_.focus_distance;
    frame.frame_seconds = seconds_since(start);
    if (!preview) {
        // The clock stops with the accumulation: a paused window shown
        // again (F, a backend switch that failed) says how long it ran.
        if (pause_reason_.empty()) {
            accumulation_seconds_ = seconds_since(full_started_);
        }
        pause_reason_ = pause_reason_now();  // before noise_estimate, which asks paused()
        frame.paused_by = pause_reason_;
        if (!pause_reason_.empty() && view_history_.pause(frame.accumulation)) {
            // Paused before what the moves left has faded out: the image
            // it stays on is the accumulation itself.
            frame.image = frame.accumulation;
        }
    }
    frame.accumulation_seconds = preview ? 0.0 : accumulation_seconds_;
    frame.relative_mse = preview ? std::numeric_limits<double>::infinity() : noise_estimate();
    frame.relative_mse_spp = preview ? 0 : estimate_.spp();
    if (!preview && filter_ && full_->frames() > 0) {
        frame.filtered = filtered_image();  // after pause_reason_: a pause filters its frame
    }
    frame.estimate_overflowed = !preview && std::isinf(frame.relative_mse) &&
                                full_->frames() >= 2 &&
                                trac0r::noise_estimate_overflowed(full_->accumulator());
    frame.generation = applied_generation_;
    frame.backend = renderer.backend().name();
    frame.device = renderer.backend().device();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!preview && last_generation_ != applied_generation_) {
            return;  // a request came in during the frame: it shows an old view
        }
        // A preview is shown even so: while the camera moves, a new one
        // comes in during every preview, and it is the newest view there is.
        frame_ = std::move(frame);
        frame_fresh_ = true;
    }
    frame_ready_();
}

}  // namespace trac0r_viewer
