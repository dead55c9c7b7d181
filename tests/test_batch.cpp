// The library's batch render (batch.h): stop rules, progress, cancelling
// from another thread and from the progress callback, and the images it
// returns on request. Each result is compared with the same frames
// rendered one by one through Renderer, bit for bit.
#include <catch2/catch.hpp>

#include "trac0r/accumulator_merge.h"
#include "trac0r/batch.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/filter.h"
#include "trac0r/scene_loader.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace trac0r;

namespace {

Scene small_scene(int width = 48, int height = 36) {
    Scene scene = builtin_scene();
    scene.render.width = width;
    scene.render.height = height;
    return scene;
}

std::unique_ptr<Renderer> renderer_of(const Scene& scene) {
    return std::unique_ptr<Renderer>(new Renderer(scene, std::make_unique<CpuBackend>(1)));
}

// The image of `frames` frames rendered one by one.
Image frames_image(const Scene& scene, long frames) {
    std::unique_ptr<Renderer> r = renderer_of(scene);
    for (long i = 0; i < frames; ++i) {
        r->render_frame();
    }
    return r->image();
}

bool same_pixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) {
        return false;
    }
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (a.pixels[i] != b.pixels[i]) {
            return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("a batch render stops at its spp and is the same frames rendered one by one", "[batch]") {
    const Scene scene = small_scene();
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.spp = 5;
    const BatchResult result = render_batch(*r, options);
    CHECK(result.first);
    CHECK(result.spp == 5);
    CHECK(result.reason == StopReason::spp);
    CHECK(result.cancelled == 0);
    CHECK_FALSE(result.cannot_reach);
    CHECK(same_pixels(result.image, frames_image(scene, 5)));
    REQUIRE(result.variance.size() == result.image.pixels.size());
    REQUIRE(result.accumulator.size() == result.image.pixels.size());
    for (std::size_t i = 0; i < result.variance.size(); ++i) {
        const kernel::AccumPixel& p = result.accumulator[i];
        REQUIRE(result.variance[i] == static_cast<float>(p.moments.y / (p.moments.z - 1.0) /
                                                         static_cast<double>(p.moments.z)));
    }
    CHECK(std::isfinite(result.estimate));
    CHECK(result.filtered.pixels.empty());
    CHECK(result.layers.empty());
}

TEST_CASE("a batch render with no rule renders the default spp", "[batch]") {
    const Scene scene = small_scene(16, 12);
    std::unique_ptr<Renderer> r = renderer_of(scene);
    const BatchResult result = render_batch(*r);
    CHECK(result.spp == default_batch_spp);
    CHECK(result.reason == StopReason::spp);
}

TEST_CASE("a batch render stops at its target error", "[batch]") {
    const Scene scene = small_scene(32, 24);
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.target_error = 0.5;
    options.stop.spp = 4096;  // a bound, should the target never be met
    const BatchResult result = render_batch(*r, options);
    CHECK(result.reason == StopReason::target_error);
    CHECK(result.error_reached);
    CHECK(result.estimate <= 0.5);
    CHECK(result.spp < 4096);
}

TEST_CASE("a batch render reports progress and the progress callback cancels it", "[batch]") {
    const Scene scene = small_scene();
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.spp = 100000;
    options.progress_interval = 0.0;  // after every frame
    std::vector<BatchProgress> seen;
    options.progress = [&seen](const BatchProgress& p) {
        seen.push_back(p);
        return p.spp < 3;
    };
    const BatchResult result = render_batch(*r, options);
    CHECK(result.cancelled == -1);
    CHECK(result.reason == StopReason::none);
    CHECK(result.spp == 3);
    REQUIRE(seen.size() == 3);
    for (std::size_t i = 0; i < seen.size(); ++i) {
        CHECK(seen[i].spp == static_cast<long>(i) + 1);
        CHECK(seen[i].fraction == Approx(static_cast<double>(i + 1) / 100000.0));
        CHECK(seen[i].seconds >= 0.0);
    }
    CHECK(std::isinf(seen[0].estimate));  // no estimate from one sample
    CHECK(std::isfinite(seen[2].estimate));
    // The partial image: the frames rendered, whole.
    CHECK(same_pixels(result.image, frames_image(scene, 3)));
}

TEST_CASE("a batch render is cancelled from another thread; the partial image comes back",
          "[batch]") {
    const Scene scene = small_scene();
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.seconds = 600.0;
    std::atomic<int> cancel(0);
    options.cancel = &cancel;
    const auto start = std::chrono::steady_clock::now();
    std::thread canceller([&cancel] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        cancel = 7;
    });
    const BatchResult result = render_batch(*r, options);
    canceller.join();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(result.cancelled == 7);
    CHECK(result.reason == StopReason::none);
    CHECK(result.spp > 0);
    CHECK(elapsed < 60.0);
    CHECK(same_pixels(result.image, frames_image(scene, result.spp)));
}

TEST_CASE("a batch render cancelled before it starts still renders one frame", "[batch]") {
    const Scene scene = small_scene(16, 12);
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.spp = 50;
    std::atomic<int> cancel(2);
    options.cancel = &cancel;
    const BatchResult result = render_batch(*r, options);
    CHECK(result.cancelled == 2);
    CHECK(result.spp == 1);
    CHECK(same_pixels(result.image, frames_image(scene, 1)));
}

TEST_CASE("a batch render makes the filtered image and the EXR layers on request", "[batch]") {
    const Scene scene = small_scene(32, 24);
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.spp = 4;
    options.filtered = true;
    options.layers.albedo = true;
    options.layers.variance = true;
    const BatchResult result = render_batch(*r, options);
    const GuideImages guides = render_guides(r->packed(), r->camera_record());
    const Image expected =
        filter_image(result.accumulator, 32, 24, filter_guides(guides), T0_FILTER_PASSES);
    CHECK(same_pixels(result.filtered, expected));
    CHECK_FALSE(same_pixels(result.filtered, result.image));
    std::vector<std::string> names;
    for (const ExrChannel& c : result.layers) {
        names.push_back(c.name);
    }
    CHECK(names == std::vector<std::string>{"albedo.R", "albedo.G", "albedo.B", "variance.Y"});
    // batch_images: the same images of a render driven frame by frame.
    std::unique_ptr<Renderer> by_frames = renderer_of(scene);
    for (int i = 0; i < 4; ++i) {
        by_frames->render_frame();
    }
    const BatchResult images = batch_images(*by_frames, options);
    CHECK(images.spp == 4);
    CHECK(same_pixels(images.image, result.image));
    CHECK(same_pixels(images.filtered, result.filtered));
}

TEST_CASE("an exception from the progress callback stops the render and is thrown", "[batch]") {
    const Scene scene = small_scene(16, 12);
    std::unique_ptr<Renderer> r = renderer_of(scene);
    BatchOptions options;
    options.stop.seconds = 600.0;
    options.progress_interval = 0.0;
    options.progress = [](const BatchProgress& p) -> bool {
        if (p.spp >= 2) {
            throw std::runtime_error("from the callback");
        }
        return true;
    };
    CHECK_THROWS_WITH(render_batch(*r, options), "from the callback");
}

TEST_CASE("a stop rule of NaN or negative parts is not set: the default spp", "[batch]") {
    StopRule given;
    given.spp = -3;
    given.seconds = std::nan("");
    given.target_error = -1.0;
    const StopRule rule = batch_stop_rule(given);
    CHECK(rule.spp == default_batch_spp);
    CHECK(rule.seconds == 0.0);
    CHECK(rule.target_error == 0.0);
}

namespace {

// Two ranks on two threads of this process: what MpiCluster does over MPI.
class ThreadPair {
  public:
    class Rank : public Cluster {
      public:
        Rank(ThreadPair& pair, int rank) : pair_(pair), rank_(rank) {}
        int rank() const override { return rank_; }
        int size() const override { return 2; }
        std::vector<RoundReport> exchange(const RoundReport& mine) override {
            pair_.reports[static_cast<std::size_t>(rank_)] = mine;
            pair_.wait();
            std::vector<RoundReport> all = pair_.reports;
            pair_.wait();  // both have read before the next round writes
            return all;
        }
        void merge_to_first(std::vector<kernel::AccumPixel>& accumulator) override {
            pair_.parts[static_cast<std::size_t>(rank_)] = &accumulator;
            pair_.wait();
            if (rank_ == 0) {
                std::vector<kernel::AccumPixel> merged(accumulator.size());
                merge_accumulators({pair_.parts[0]->data(), pair_.parts[1]->data()},
                                   accumulator.size(), merged.data());
                pair_.wait();
                accumulator = merged;
            } else {
                pair_.wait();
            }
        }

      private:
        ThreadPair& pair_;
        int rank_;
    };

    std::vector<RoundReport> reports = std::vector<RoundReport>(2);
    std::vector<std::vector<kernel::AccumPixel>*> parts = {nullptr, nullptr};

    void wait() {
        std::unique_lock<std::mutex> lock(mutex_);
        const long generation = generation_;
        if (++arrived_ == 2) {
            arrived_ = 0;
            ++generation_;
            condition_.notify_all();
        } else {
            condition_.wait(lock, [&] { return generation_ != generation; });
        }
    }

  private:
    std::mutex mutex_;
    std::condition_variable condition_;
    int arrived_ = 0;
    long generation_ = 0;
};

}  // namespace

TEST_CASE("a batch render split across two ranks: every frame once, one decision, one cancel",
          "[batch]") {
    const Scene scene = small_scene(24, 18);
    SECTION("an odd spp: rank 0 renders 0, 2, 4, 6, rank 1 renders 1, 3, 5") {
        ThreadPair pair;
        ThreadPair::Rank first(pair, 0);
        ThreadPair::Rank second(pair, 1);
        BatchResult results[2];
        std::thread other([&] {
            std::unique_ptr<Renderer> r = renderer_of(scene);
            BatchOptions o;
            o.stop.spp = 7;
            o.cluster = &second;
            results[1] = render_batch(*r, o);
        });
        std::unique_ptr<Renderer> r = renderer_of(scene);
        BatchOptions o;
        o.stop.spp = 7;
        o.cluster = &first;
        results[0] = render_batch(*r, o);
        other.join();
        CHECK(results[0].first);
        CHECK_FALSE(results[1].first);
        CHECK(results[0].spp == 7);
        CHECK(results[1].spp == 7);
        CHECK(results[0].frames_per_process == std::vector<std::int64_t>{4, 3});
        CHECK(results[1].image.pixels.empty());
        // The merge of the two equals one process's 7 frames to float
        // rounding (accumulator_merge.h).
        const Image one = frames_image(scene, 7);
        for (std::size_t i = 0; i < one.pixels.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                REQUIRE(results[0].image.pixels[i][c] ==
                        Approx(one.pixels[i][c]).epsilon(1e-5).margin(1e-6));
            }
        }
    }
    SECTION("rank 1 cancelled: both stop after the same round") {
        ThreadPair pair;
        ThreadPair::Rank first(pair, 0);
        ThreadPair::Rank second(pair, 1);
        BatchResult results[2];
        std::atomic<int> cancel(4);
        std::thread other([&] {
            std::unique_ptr<Renderer> r = renderer_of(scene);
            BatchOptions o;
            o.stop.spp = 1000;
            o.cluster = &second;
            o.cancel = &cancel;
            results[1] = render_batch(*r, o);
        });
        std::unique_ptr<Renderer> r = renderer_of(scene);
        BatchOptions o;
        o.stop.spp = 1000;
        o.cluster = &first;
        results[0] = render_batch(*r, o);
        other.join();
        CHECK(results[0].cancelled == 4);
        CHECK(results[1].cancelled == 4);
        CHECK(results[0].spp == 2);  // one round of two frames
        CHECK(results[0].frames_per_process == std::vector<std::int64_t>{1, 1});
    }
}
