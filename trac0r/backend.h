// A rendering backend: runs the kernel over every pixel and accumulates.
#ifndef TRAC0R_BACKEND_H
#define TRAC0R_BACKEND_H

#include "trac0r/image_io.h"
#include "trac0r/kernel_fwd.h"
#include "trac0r/render_options.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace trac0r {

class Backend {
  public:
    virtual ~Backend() = default;
    std::string name() const { return name_; }      // "cpu", "opencl"
    std::string device() const { return device_; }  // what it runs on, for people
    // From how many triangles Accel::automatic builds a BVH on this backend
    // (packed_scene.h).
    virtual std::size_t auto_bvh_min_triangles() const { return trac0r::auto_bvh_min_triangles; }
    // Called once per scene change.
    virtual void set_scene(const PackedScene& scene) = 0;
    // Clears the accumulator (new size, camera or settings).
    virtual void reset(int width, int height) = 0;
    // One sample per pixel, accumulated.
    virtual void render_frame(const kernel::CameraRecord& camera, std::uint64_t seed,
                              std::uint32_t frame, int max_depth) = 0;
    // render_frame that asks `cancel` between pieces of the frame (tiles on
    // the CPU, chunks on OpenCL), from any of its threads, and stops early
    // once it says true. Returns false when it stopped: the accumulator then
    // holds part of the frame, and must be reset before it is used again
    // (Renderer::render_frame does). An empty `cancel`: render_frame. The
    // default asks once, before the whole frame.
    using CancelCheck = std::function<bool()>;
    virtual bool render_frame_cancellable(const kernel::CameraRecord& camera, std::uint64_t seed,
                                          std::uint32_t frame, int max_depth,
                                          const CancelCheck& cancel) {
        if (cancel && cancel()) {
            return false;
        }
        render_frame(camera, seed, frame, max_depth);
        return true;
    }
    virtual void read_accumulator(std::vector<kernel::AccumPixel>& out) = 0;
    // The edge-preserving filter (filter.h) of an accumulation of width x
    // height pixels, where this backend runs it: the same kernel code on its
    // device. The default runs it on the CPU (filter.cpp).
    virtual Image filter_accumulation(const std::vector<kernel::AccumPixel>& accumulator, int width,
                                      int height, const std::vector<kernel::FilterGuide>& guides,
                                      int passes);

  protected:
    Backend(std::string name, std::string device)
        : name_(std::move(name)), device_(std::move(device)) {}

  private:
    std::string name_;
    std::string device_;
};

}  // namespace trac0r

#endif
