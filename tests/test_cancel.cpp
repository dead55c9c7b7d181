// A frame stopped part way (Backend::render_frame_cancellable,
// Renderer::render_frame(cancel)): it stops between pieces of the frame,
// and never leaves part of itself in the accumulation.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_backend.h"
#endif

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

using namespace trac0r;

namespace {

// Says stop from its n-th question on (1: at once); counts the questions.
struct StopAfter {
    explicit StopAfter(int n) : n(n) {}
    int n;
    std::atomic<int> asked{0};
    Backend::CancelCheck check() {
        return [this] { return ++asked >= n; };
    }
};

Scene small_scene() {
    Scene scene = builtin_scene();
    scene.render.width = 64;
    scene.render.height = 48;
    return scene;
}

// Pixels with at least one sample (accepted or dropped).
long pixels_sampled(const std::vector<kernel::AccumPixel>& accum) {
    long n = 0;
    for (const kernel::AccumPixel& p : accum) {
        n += p.moments.z + p.moments.w > 0.0f;
    }
    return n;
}

bool same_accumulators(const std::vector<kernel::AccumPixel>& a,
                       const std::vector<kernel::AccumPixel>& b) {
    if (a.size() != b.size()) {
        return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
        const kernel::AccumPixel& p = a[i];
        const kernel::AccumPixel& q = b[i];
        if (p.sum.x != q.sum.x || p.sum.y != q.sum.y || p.sum.z != q.sum.z ||
            p.moments.z != q.moments.z || p.moments.w != q.moments.w) {
            return false;
        }
    }
    return true;
}

// A backend from `make` holding `packed`, with an empty accumulation of
// the scene's size.
std::unique_ptr<Backend> ready_backend(const std::function<std::unique_ptr<Backend>()>& make,
                                       const PackedScene& packed, const Scene& scene) {
    std::unique_ptr<Backend> backend = make();
    backend->set_scene(packed);
    backend->reset(scene.render.width, scene.render.height);
    return backend;
}

// Frame 0 (seed 1, paths of 5) rendered whole on a fresh backend: the
// accumulator a cancelled or split render is held to.
std::vector<kernel::AccumPixel> whole_frame(const std::function<std::unique_ptr<Backend>()>& make,
                                            const PackedScene& packed, const Scene& scene,
                                            const kernel::CameraRecord& camera) {
    std::unique_ptr<Backend> plain = ready_backend(make, packed, scene);
    plain->render_frame(camera, 1, 0, 5);
    std::vector<kernel::AccumPixel> accum;
    plain->read_accumulator(accum);
    return accum;
}

// The backend's behaviour under a cancel check, whichever backend it is.
void check_backend_cancels(const std::function<std::unique_ptr<Backend>()>& make) {
    const Scene scene = small_scene();
    const PackedScene packed = pack_scene(scene);
    const kernel::CameraRecord camera =
        make_camera_record(scene.camera, scene.render.width, scene.render.height);
    const long pixels = static_cast<long>(scene.render.width) * scene.render.height;

    // Never cancelled: the same frame as render_frame's, every pixel.
    const std::vector<kernel::AccumPixel> expected = whole_frame(make, packed, scene, camera);
    REQUIRE(pixels_sampled(expected) == pixels);

    std::unique_ptr<Backend> backend = ready_backend(make, packed, scene);
    StopAfter never(1 << 30);
    CHECK(backend->render_frame_cancellable(camera, 1, 0, 5, never.check()));
    CHECK(never.asked > 1);  // asked between pieces, not once
    std::vector<kernel::AccumPixel> got;
    backend->read_accumulator(got);
    CHECK(same_accumulators(got, expected));

    // Stop at the second question: some of the frame, not all of it.
    backend->reset(scene.render.width, scene.render.height);
    StopAfter second(2);
    CHECK_FALSE(backend->render_frame_cancellable(camera, 1, 0, 5, second.check()));
    backend->read_accumulator(got);
    CHECK(pixels_sampled(got) > 0);
    CHECK(pixels_sampled(got) < pixels);

    // Stop at once: nothing rendered.
    backend->reset(scene.render.width, scene.render.height);
    StopAfter first(1);
    CHECK_FALSE(backend->render_frame_cancellable(camera, 1, 0, 5, first.check()));
    backend->read_accumulator(got);
    CHECK(pixels_sampled(got) == 0);
}

// A BDPT frame stopped part way adds nothing, and leaves none of its light
// subpaths' splats for the next frame, even without a reset between.
void check_bdpt_cancel_drops_splats(const std::function<std::unique_ptr<Backend>()>& make) {
    const Scene scene = small_scene();
    PackOptions options;
    options.integrator = Integrator::bdpt;
    const PackedScene packed = pack_scene(scene, options);
    REQUIRE((packed.features & T0_FEATURE_BDPT) != 0u);
    const kernel::CameraRecord camera =
        make_camera_record(scene.camera, scene.render.width, scene.render.height);

    const std::vector<kernel::AccumPixel> expected = whole_frame(make, packed, scene, camera);

    std::unique_ptr<Backend> backend = ready_backend(make, packed, scene);
    StopAfter second(2);
    CHECK_FALSE(backend->render_frame_cancellable(camera, 1, 0, 5, second.check()));
    std::vector<kernel::AccumPixel> got;
    backend->read_accumulator(got);
    CHECK(pixels_sampled(got) == 0);  // merged only once the whole frame is in
    // The same frame again, whole, with no reset: as if the first never ran.
    backend->render_frame(camera, 1, 0, 5);
    backend->read_accumulator(got);
    CHECK(same_accumulators(got, expected));
}

}  // namespace

TEST_CASE("a CPU frame stops between tiles when cancelled", "[cancel]") {
    check_backend_cancels([] { return std::make_unique<CpuBackend>(2); });
}

TEST_CASE("a stopped CPU BDPT frame leaves no splats for the next", "[cancel][bdpt]") {
    check_bdpt_cancel_drops_splats([] { return std::make_unique<CpuBackend>(2); });
}

#ifdef TRAC0R_HAVE_OPENCL
TEST_CASE(
    "an OpenCL frame stops between its launches when cancelled, and in parts is the same "
    "frame",
    "[cancel]") {
    check_backend_cancels([] { return std::make_unique<OpenClBackend>(0); });
}

TEST_CASE("a stopped OpenCL BDPT frame leaves no splats for the next", "[cancel][bdpt]") {
    check_bdpt_cancel_drops_splats([] { return std::make_unique<OpenClBackend>(0); });
}
#endif

TEST_CASE("a cancelled frame leaves nothing in the accumulation", "[cancel]") {
    const Scene scene = small_scene();
    Renderer renderer(scene, std::make_unique<CpuBackend>(2), 7);
    renderer.render_frame();
    renderer.render_frame();
    StopAfter second(2);
    CHECK_FALSE(renderer.render_frame(second.check()));
    // The accumulation restarted: no frame, and no sample of the stopped one.
    CHECK(renderer.frames() == 0);
    CHECK(pixels_sampled(renderer.accumulator()) == 0);

    // Frames after it are those of a fresh render, bit for bit.
    StopAfter never(1 << 30);
    CHECK(renderer.render_frame(never.check()));
    renderer.render_frame();
    Renderer fresh(scene, std::make_unique<CpuBackend>(2), 7);
    fresh.render_frame();
    fresh.render_frame();
    CHECK(renderer.frames() == 2);
    CHECK(same_accumulators(renderer.accumulator(), fresh.accumulator()));
}
