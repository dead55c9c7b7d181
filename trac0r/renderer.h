// Renders a scene progressively on a backend: the one entry point the
// viewer, the tests and the benchmarks use.
#ifndef TRAC0R_RENDERER_H
#define TRAC0R_RENDERER_H

#include "trac0r/backend.h"
#include "trac0r/image_io.h"
#include "trac0r/kernel_fwd.h"
#include "trac0r/render_options.h"
#include "trac0r/scene.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace trac0r {

struct RenderStats {
    std::uint32_t frames = 0;
    double samples_dropped = 0;  // non-finite samples, never accumulated
};

// The running mean of an accumulator of width x height pixels.
Image accumulated_image(const std::vector<kernel::AccumPixel>& accumulator, int width, int height);

// The seed of a render unless one is given: the library's and every
// program's (--seed).
const std::uint64_t default_seed = 1;

class Renderer {
  public:
    Renderer(const Scene& scene, std::unique_ptr<Backend> backend,
             std::uint64_t seed = default_seed, const PackOptions& pack_options = PackOptions());
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;

    const Scene& scene() const { return scene_; }
    // The kernel's camera of the current view (in the scene's coordinates:
    // the backends scale it by packed().scale).
    // (Inside trac0r: packed_scene.h and kernel/types.h define them.)
    const kernel::CameraRecord& camera_record() const;
    const PackedScene& packed() const;
    Backend& backend() { return *backend_; }
    const Backend& backend() const { return *backend_; }
    int width() const { return scene_.render.width; }
    int height() const { return scene_.render.height; }
    std::uint32_t frames() const { return frame_; }
    // The most frames (samples a pixel) an accumulation holds: a pixel's
    // sample count is a float (kernel::AccumPixel::moments.z), exact to
    // 2^24, past which it stops growing and the mean would drift. Callers
    // stop there (the viewer's batch mode and window, and --spp's range).
    static const std::uint32_t max_frames = 1u << 24;
    bool full() const { return frame_ >= max_frames; }

    // The frames this renderer renders, by their index in the render's
    // sequence (a pixel's random numbers are a function of the seed, the
    // pixel and that index): first, first + stride, first + 2 stride, ...
    // (0, 1 unless set: every frame). Rank r of N ranks renders r, N, and
    // their accumulators merged (accumulator_merge.h) are the render of
    // every frame. Restarts accumulation.
    void set_frame_sequence(std::uint32_t first, std::uint32_t stride);

    void set_camera(const Camera& camera);  // restarts accumulation
    // Renders width x height pixels from now on (the vertical field of view
    // kept: a wider image shows more at the sides); restarts accumulation.
    // The scene is not packed again.
    void set_size(int width, int height);
    void restart();
    void render_frame();
    // render_frame, stopped early once `cancel` says true (asked between
    // tiles, from the rendering threads: Backend::render_frame_cancellable).
    // A stopped frame never counts: the accumulation restarts (frames() is
    // 0), so the mean is always of whole frames. Cancel only a frame whose
    // accumulation is about to be thrown away anyway (a new camera, a
    // restart). Returns whether the frame was finished.
    bool render_frame(const Backend::CancelCheck& cancel);

    // The running mean, and what the accumulator knows about it.
    Image image();
    RenderStats stats();
    const std::vector<kernel::AccumPixel>& accumulator();

  private:
    // The packed scene, the kernel's camera and the read-back accumulator:
    // the kernel's types, kept out of this header (kernel_fwd.h).
    struct KernelState;

    Scene scene_;
    std::unique_ptr<KernelState> kernel_;
    std::unique_ptr<Backend> backend_;
    std::uint64_t seed_;
    std::uint32_t frame_ = 0;  // frames rendered since the restart
    std::uint32_t first_frame_ = 0;
    std::uint32_t frame_stride_ = 1;
    bool readback_valid_ = false;
};

}  // namespace trac0r

#endif
