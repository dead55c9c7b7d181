#include "trac0r/renderer.h"

#include "trac0r/kernel/accumulate.h"
#include "trac0r/kernel/bdpt_vertex.h"
#include "trac0r/kernel/types.h"
#include "trac0r/packed_scene.h"

#include <stdexcept>
#include <string>

namespace trac0r {

struct Renderer::KernelState {
    PackedScene packed;
    kernel::CameraRecord camera{};
    std::vector<kernel::AccumPixel> readback;
};

namespace {

// Accel::automatic with the backend's own threshold, unless the caller
// chose one.
PackOptions for_backend(PackOptions options, const Backend& backend) {
    if (options.auto_bvh_min_triangles == 0) {
        options.auto_bvh_min_triangles = backend.auto_bvh_min_triangles();
    }
    return options;
}

}  // namespace

Renderer::Renderer(const Scene& scene, std::unique_ptr<Backend> backend, std::uint64_t seed,
                   const PackOptions& pack_options)
    : scene_(scene), kernel_(new KernelState), backend_(std::move(backend)), seed_(seed) {
    if (pack_options.integrator == Integrator::bdpt && scene.render.max_depth > T0_BDPT_MAX_DEPTH) {
        throw std::invalid_argument("the bdpt integrator takes paths of at most " +
                                    std::to_string(T0_BDPT_MAX_DEPTH) + " vertices (max_depth " +
                                    std::to_string(scene.render.max_depth) + "): use --max-depth " +
                                    std::to_string(T0_BDPT_MAX_DEPTH) +
                                    " or less, or --integrator nee");
    }
    kernel_->packed = pack_scene(scene, for_backend(pack_options, *backend_));
    kernel_->camera = make_camera_record(scene.camera, scene.render.width, scene.render.height);
    backend_->set_scene(kernel_->packed);
    restart();
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

const kernel::CameraRecord& Renderer::camera_record() const { return kernel_->camera; }
const PackedScene& Renderer::packed() const { return kernel_->packed; }

void Renderer::set_camera(const Camera& camera) {
    kernel_->camera = make_camera_record(camera, width(), height());
    scene_.camera = camera;
    restart();
}

void Renderer::set_size(int width, int height) {
    scene_.render.width = width;
    scene_.render.height = height;
    kernel_->camera = make_camera_record(scene_.camera, width, height);
    restart();
}

void Renderer::set_frame_sequence(std::uint32_t first, std::uint32_t stride) {
    first_frame_ = first;
    frame_stride_ = stride > 0 ? stride : 1;
    restart();
}

void Renderer::restart() {
    backend_->reset(width(), height());
    frame_ = 0;
    readback_valid_ = false;
}

void Renderer::render_frame() {
    backend_->render_frame(kernel_->camera, seed_, first_frame_ + frame_stride_ * frame_,
                           scene_.render.max_depth);
    ++frame_;
    readback_valid_ = false;
}

bool Renderer::render_frame(const Backend::CancelCheck& cancel) {
    if (!backend_->render_frame_cancellable(kernel_->camera, seed_,
                                            first_frame_ + frame_stride_ * frame_,
                                            scene_.render.max_depth, cancel)) {
        restart();  // part of a frame must not stay in the mean
        return false;
    }
    ++frame_;
    readback_valid_ = false;
    return true;
}

const std::vector<kernel::AccumPixel>& Renderer::accumulator() {
    if (!readback_valid_) {
        backend_->read_accumulator(kernel_->readback);
        readback_valid_ = true;
    }
    return kernel_->readback;
}

Image accumulated_image(const std::vector<kernel::AccumPixel>& accum, int width, int height) {
    Image img;
    img.width = width;
    img.height = height;
    img.pixels.resize(accum.size());
    for (std::size_t i = 0; i < accum.size(); ++i) {
        img.pixels[i] = kernel::accumulated_mean(accum[i]);
    }
    return img;
}

Image Renderer::image() { return accumulated_image(accumulator(), width(), height()); }

RenderStats Renderer::stats() {
    RenderStats s;
    s.frames = frame_;
    for (const kernel::AccumPixel& p : accumulator()) {
        s.samples_dropped += p.moments.w;
    }
    return s;
}

}  // namespace trac0r
