// The OpenCL device registry and program cache (opencl_devices.cpp), for
// the backend and for code that runs kernels of its own beside
// render_frame (the ray-casting benchmark, the bit-for-bit helpers test):
// the OpenCL context and queue that
// the OpenClBackends on a device share, and programs of the embedded kernel
// source with more source appended, built once per (device, appended
// source, options) and cached as the backend's own are. Unlike
// opencl_backend.h this header needs the OpenCL headers (by opencl_owner.h,
// whose owners suit the buffers and kernels such code makes).
#ifndef TRAC0R_OPENCL_PROGRAM_H
#define TRAC0R_OPENCL_PROGRAM_H

#include "trac0r/opencl_backend.h"
#include "trac0r/opencl_owner.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace trac0r {

// A device's context and queue, and the programs built on it, by appended
// source (empty for the renderer's own) and build options (which hold the
// feature mask): PoCL takes seconds to build one, so every backend, test
// and benchmark that runs while one holds it shares them. Released (queue,
// programs, context) when the last holder goes.
struct OpenClDeviceCache {
    cl_device_id device = nullptr;
    OpenClContext context;
    OpenClCommandQueue queue;
    std::string description;
    std::map<std::pair<std::string, std::string>, OpenClProgram> programs;
};

struct OpenClQueue {
    cl_device_id device;
    cl_context context;
    cl_command_queue queue;
    std::string description;                   // "device (platform)"
    std::shared_ptr<OpenClDeviceCache> cache;  // holds the above open
};

// Device `device_index` (see list_opencl_devices), shared with the backends
// and handles that hold it open, else opened. Throws OpenClError when there
// is no such device.
OpenClQueue shared_opencl_queue(int device_index);

// Throws OpenClError "OpenCL: WHAT failed (error N, NAME)" unless status
// is CL_SUCCESS.
void check_opencl(cl_int status, const char* what);

// The build options of the renderer's program for feature mask `features`:
// the OpenCL C version, the mask, T0_GPU=1 where `gpu` (a device that is not
// a CPU: the kernels' GPU choices, kernel/tuning.h), and
// $TRAC0R_OPENCL_OPTIONS.
std::string opencl_build_options(std::uint32_t features, bool gpu = false);

// opencl_kernel_source() followed by appended_source, built with options on
// cl's device, or the program already built from the same. cl's cache owns
// it (do not release it): it lives while cl, or a copy, does. Throws
// OpenClError with the build log if it does not build.
cl_program embedded_opencl_program(const OpenClQueue& cl, const std::string& appended_source,
                                   const std::string& options);

// The program of opencl_kernel_source() followed by appended_source,
// built with options on `device`, or the one built before from the same
// (then *build_seconds is 0, else the seconds the build took). The cache
// owns it. Throws OpenClError with the build log if it does not build.
cl_program cached_opencl_program(OpenClDeviceCache& device, const std::string& appended_source,
                                 const std::string& options, double* build_seconds);

// Whether the OpenCL device is a CPU (its programs built without T0_GPU).
bool opencl_device_is_cpu(cl_device_id device);

}  // namespace trac0r

#endif
