// The C++/OpenMP backend: the kernel headers compiled as C++.
#ifndef TRAC0R_CPU_BACKEND_H
#define TRAC0R_CPU_BACKEND_H

#include "trac0r/backend.h"

#include <memory>

namespace trac0r {

// While in scope, the calling thread's floating point treats denormal
// inputs and results as zero (x86: MXCSR's DAZ and FTZ bits; elsewhere it
// does nothing), as GPUs and most renderers do; the previous mode comes
// back at the end of the scope. The CPU backend renders so: GCC computes
// some float3 operations on four lanes, and the fourth holds whatever was
// in memory next to the vector, often half of a pointer, a denormal; each
// operation on one took a microcode assist, which made a BVH frame of
// cornell.json up to a fifth slower, depending on what had run before on
// the thread's stack (docs/performance.md, "Kernel tuning"). The kernel
// does not rely on denormals: it steps off 0 to the smallest normal float
// and takes a denormal triangle area for 0.
class DenormalsAreZero {
  public:
    DenormalsAreZero();
    ~DenormalsAreZero();
    DenormalsAreZero(const DenormalsAreZero&) = delete;
    DenormalsAreZero& operator=(const DenormalsAreZero&) = delete;

  private:
    unsigned int saved_;
};

class CpuBackend : public Backend {
  public:
    // threads <= 0: OpenMP's default.
    explicit CpuBackend(int threads = 0);
    ~CpuBackend() override;
    void set_scene(const PackedScene& scene) override;
    void reset(int width, int height) override;
    void render_frame(const kernel::CameraRecord& camera, std::uint64_t seed, std::uint32_t frame,
                      int max_depth) override;
    bool render_frame_cancellable(const kernel::CameraRecord& camera, std::uint64_t seed,
                                  std::uint32_t frame, int max_depth,
                                  const CancelCheck& cancel) override;
    void read_accumulator(std::vector<kernel::AccumPixel>& out) override;

  private:
    // The packed scene and the accumulator (the kernel's types, kept out of
    // this header: kernel_fwd.h).
    struct State;

    int threads_;
    std::unique_ptr<State> state_;
};

}  // namespace trac0r

#endif
