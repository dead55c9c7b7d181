// The OpenCL backend: the same kernel headers, compiled as OpenCL C for the
// scene's feature mask, on PoCL (CPU) or any GPU driver.
#ifndef TRAC0R_OPENCL_BACKEND_H
#define TRAC0R_OPENCL_BACKEND_H

#include "trac0r/backend.h"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r {

// No platform or device, a bad device index, a failed build (the message
// then holds the compiler's build log), or a failed OpenCL call.
class OpenClError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct OpenClDeviceInfo {
    int index;  // what --device takes
    std::string platform;
    std::string name;
    std::string type;  // "CPU", "GPU", ...
};

// Every device of every platform, numbered in order. Empty when there is
// no OpenCL platform (no ICD installed).
std::vector<OpenClDeviceInfo> list_opencl_devices();

// Throws OpenClError, before the driver is asked, when a buffer of `bytes`
// is more than `largest`, the device's largest (CL_DEVICE_MAX_MEM_ALLOC_SIZE):
// the message names the buffer ("the scene's texels"), its size, the
// device and its limit.
void check_opencl_buffer_size(const std::string& buffer, std::uint64_t bytes,
                              std::uint64_t largest, const std::string& device);

// The OpenCL C source embedded at build time (kernel headers + render.cl).
const char* opencl_kernel_source();

// A device's context, command queue and built programs. Every backend on
// the device holds it while it lives, and it is released with the last
// holder: a program (seconds to build on PoCL) is built once while any
// holder lives, and nothing stays behind once all are gone.
struct OpenClDeviceCache;

// Holds device `device_index` open, so that backends made and destroyed one
// after another while the handle lives share its programs: a library user
// who makes renderers in a loop keeps one. Throws OpenClError when there is
// no such device.
std::shared_ptr<OpenClDeviceCache> keep_opencl_device(int device_index);

// How many launches a cancellable OpenCL frame is split into.
constexpr int opencl_cancel_chunks = 8;

class OpenClBackend : public Backend {
  public:
    // Opens device `device_index` (see list_opencl_devices), or shares it
    // with the backends and keep_opencl_device handles that hold it open:
    // programs are built once per (device, feature mask) while it is open.
    // Extra build options come from $TRAC0R_OPENCL_OPTIONS.
    explicit OpenClBackend(int device_index = 0);
    ~OpenClBackend() override;

    void set_scene(const PackedScene& scene) override;
    void reset(int width, int height) override;
    void render_frame(const kernel::CameraRecord& camera, std::uint64_t seed, std::uint32_t frame,
                      int max_depth) override;
    // In up to opencl_cancel_chunks launches of a part of the image each,
    // the next queued before the last is waited for; `cancel` is asked
    // between them.
    bool render_frame_cancellable(const kernel::CameraRecord& camera, std::uint64_t seed,
                                  std::uint32_t frame, int max_depth,
                                  const CancelCheck& cancel) override;
    void read_accumulator(std::vector<kernel::AccumPixel>& out) override;
    // On this backend's device (opencl_filter_image).
    Image filter_accumulation(const std::vector<kernel::AccumPixel>& accumulator, int width,
                              int height, const std::vector<kernel::FilterGuide>& guides,
                              int passes) override;

    // Seconds the last set_scene spent building its program (0 if cached).
    double last_build_seconds() const;
    // The options the current program was built with.
    std::string build_options() const;

    struct State;

  private:
    explicit OpenClBackend(std::unique_ptr<State> state);
    void clear_splats();

    std::unique_ptr<State> state_;
};

}  // namespace trac0r

#endif
