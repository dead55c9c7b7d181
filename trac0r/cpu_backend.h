// The C++/OpenMP backend: the kernel headers compiled as C++.
#ifndef TRAC0R_CPU_BACKEND_H
#define TRAC0R_CPU_BACKEND_H

#include "trac0r/backend.h"

namespace trac0r {

class CpuBackend : public Backend {
  public:
    // threads <= 0: OpenMP's default.
    explicit CpuBackend(int threads = 0);
    std::string name() const override { return "cpu"; }
    std::string device() const override;
    void set_scene(const PackedScene& scene) override;
    void reset(int width, int height) override;
    void render_frame(const kernel::CameraRecord& camera, std::uint64_t seed, std::uint32_t frame,
                      int max_depth) override;
    void read_accumulator(std::vector<kernel::AccumPixel>& out) override;

  private:
    int threads_;
    PackedScene scene_;
    std::vector<kernel::AccumPixel> accum_;
};

}  // namespace trac0r

#endif
