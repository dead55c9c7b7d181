// The edge-preserving filter on an OpenCL device: filter_begin, the
// passes and filter_end of the embedded program (kernel/render.cl).
#include "trac0r/filter.h"
#include "trac0r/opencl_owner.h"
#include "trac0r/opencl_program.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace trac0r {

namespace {

template <typename T>
void set_args(cl_kernel k, cl_uint index, const T& value) {
    check_opencl(clSetKernelArg(k, index, sizeof value, &value), "clSetKernelArg(filter)");
}

template <typename T, typename... Rest>
void set_args(cl_kernel k, cl_uint index, const T& value, const Rest&... rest) {
    set_args(k, index, value);
    set_args(k, index + 1, rest...);
}

OpenClMem buffer(cl_context context, cl_mem_flags flags, std::size_t bytes, const void* data) {
    cl_int status = CL_SUCCESS;
    OpenClMem m(clCreateBuffer(context, flags | (data ? CL_MEM_COPY_HOST_PTR : 0), bytes,
                               const_cast<void*>(data), &status));
    check_opencl(status, "clCreateBuffer(filter)");
    return m;
}

OpenClKernel kernel_of(cl_program program, const char* name) {
    cl_int status = CL_SUCCESS;
    OpenClKernel k(clCreateKernel(program, name, &status));
    check_opencl(status, (std::string("clCreateKernel(") + name + ")").c_str());
    return k;
}

void run(const OpenClQueue& cl, cl_kernel k, std::size_t items) {
    const std::size_t global = (items + 63) / 64 * 64;
    check_opencl(
        clEnqueueNDRangeKernel(cl.queue, k, 1, nullptr, &global, nullptr, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel(filter)");
}

}  // namespace

Image opencl_filter_image(int device_index, const std::vector<kernel::AccumPixel>& accumulator,
                          int width, int height, const std::vector<kernel::FilterGuide>& guides,
                          int passes) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (pixels == 0 || accumulator.size() != pixels || guides.size() != pixels) {
        throw std::invalid_argument(
            "opencl_filter_image: the accumulator and the guides must "
            "have " +
            std::to_string(pixels) + " pixels, at least one");
    }
    const OpenClQueue cl = shared_opencl_queue(device_index);
    // The filter reads no scene: any feature mask's program has it.
    cl_program program = embedded_opencl_program(cl, "", opencl_build_options(0u));
    OpenClKernel begin = kernel_of(program, "filter_begin");
    OpenClKernel taps_kernel = kernel_of(program, "filter_taps");
    OpenClKernel noise_kernel = kernel_of(program, "filter_noise_pass");
    OpenClKernel pass_kernel = kernel_of(program, "filter_pass");
    OpenClKernel end = kernel_of(program, "filter_end");
    OpenClMem accum = buffer(cl.context, CL_MEM_READ_ONLY, sizeof(kernel::AccumPixel) * pixels,
                             accumulator.data());
    OpenClMem guide =
        buffer(cl.context, CL_MEM_READ_ONLY, sizeof(kernel::FilterGuide) * pixels, guides.data());
    OpenClMem a =
        buffer(cl.context, CL_MEM_READ_WRITE, sizeof(kernel::FilterPixel) * pixels, nullptr);
    OpenClMem b =
        buffer(cl.context, CL_MEM_READ_WRITE, sizeof(kernel::FilterPixel) * pixels, nullptr);
    OpenClMem taps =
        buffer(cl.context, CL_MEM_READ_WRITE, sizeof(kernel::FilterTap) * pixels, nullptr);
    OpenClMem noise =
        buffer(cl.context, CL_MEM_READ_WRITE, sizeof(kernel::FilterNoise) * pixels, nullptr);
    OpenClMem colour = buffer(cl.context, CL_MEM_WRITE_ONLY, sizeof(cl_float4) * pixels, nullptr);
    const cl_uint count = static_cast<cl_uint>(pixels);
    set_args(begin.get(), 0, accum.get(), guide.get(), a.get(), count);
    run(cl, begin.get(), pixels);
    set_args(taps_kernel.get(), 0, guide.get(), taps.get(), cl_int(width), cl_int(height));
    run(cl, taps_kernel.get(), pixels);
    for (cl_int pass = 0; pass < passes; ++pass) {
        set_args(noise_kernel.get(), 0, a.get(), noise.get(), count);
        run(cl, noise_kernel.get(), pixels);
        set_args(pass_kernel.get(), 0, a.get(), taps.get(), noise.get(), b.get(), cl_int(width),
                 cl_int(height), pass);
        run(cl, pass_kernel.get(), pixels);
        std::swap(a, b);
    }
    set_args(end.get(), 0, a.get(), guide.get(), colour.get(), count);
    run(cl, end.get(), pixels);
    std::vector<cl_float4> out(pixels);
    check_opencl(clEnqueueReadBuffer(cl.queue, colour.get(), CL_TRUE, 0, sizeof(cl_float4) * pixels,
                                     out.data(), 0, nullptr, nullptr),
                 "clEnqueueReadBuffer(filter)");
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        image.pixels[i] = glm::vec3(out[i].s[0], out[i].s[1], out[i].s[2]);
    }
    return image;
}

}  // namespace trac0r
