// Owners of OpenCL objects: each holds one handle (a buffer, kernel,
// program, command queue or context) and releases it with its clRelease*
// when it goes or is given another; movable, not copyable, like
// std::unique_ptr. It includes the OpenCL headers (for OpenCL 1.2), for
// itself and for opencl_program.h.
#ifndef TRAC0R_OPENCL_OWNER_H
#define TRAC0R_OPENCL_OWNER_H

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

namespace trac0r {

template <typename Handle, cl_int (*Release)(Handle)>
class OpenClOwner {
  public:
    OpenClOwner() = default;
    // Takes over `handle` (which may be null: nothing is owned).
    explicit OpenClOwner(Handle handle) : handle_(handle) {}
    ~OpenClOwner() { reset(); }

    OpenClOwner(OpenClOwner&& other) noexcept : handle_(other.handle_) { other.handle_ = nullptr; }
    OpenClOwner& operator=(OpenClOwner&& other) noexcept {
        if (this != &other) {
            reset(other.handle_);
            other.handle_ = nullptr;
        }
        return *this;
    }
    OpenClOwner(const OpenClOwner&) = delete;
    OpenClOwner& operator=(const OpenClOwner&) = delete;

    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != nullptr; }

    // Releases what is owned, then owns `handle`.
    void reset(Handle handle = nullptr) {
        if (handle_) {
            Release(handle_);
        }
        handle_ = handle;
    }

  private:
    Handle handle_ = nullptr;
};

using OpenClMem = OpenClOwner<cl_mem, clReleaseMemObject>;
using OpenClKernel = OpenClOwner<cl_kernel, clReleaseKernel>;
using OpenClProgram = OpenClOwner<cl_program, clReleaseProgram>;
using OpenClCommandQueue = OpenClOwner<cl_command_queue, clReleaseCommandQueue>;
using OpenClContext = OpenClOwner<cl_context, clReleaseContext>;
using OpenClEvent = OpenClOwner<cl_event, clReleaseEvent>;

}  // namespace trac0r

#endif
