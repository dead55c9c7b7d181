// A rendering backend: runs the kernel over every pixel and accumulates.
#ifndef TRAC0R_BACKEND_H
#define TRAC0R_BACKEND_H

#include "trac0r/kernel/types.h"
#include "trac0r/packed_scene.h"

#include <cstddef>
#include <cstdint>
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
    virtual void read_accumulator(std::vector<kernel::AccumPixel>& out) = 0;

  protected:
    Backend(std::string name, std::string device)
        : name_(std::move(name)), device_(std::move(device)) {}

  private:
    std::string name_;
    std::string device_;
};

}  // namespace trac0r

#endif
