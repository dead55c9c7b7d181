// The OpenCL device registry and program cache: the devices the OpenCL
// backends, tests and benchmarks open (shared while any holds one) and the
// programs built on them (opencl_program.h).
#include "trac0r/opencl_program.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <utility>

namespace trac0r {

extern const char* const embedded_opencl_source;

const char* opencl_kernel_source() { return embedded_opencl_source; }

namespace {

// The name of an OpenCL error code, for the ones a user can meet and act
// on; "" for the rest.
const char* error_name(cl_int status) {
    switch (status) {
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
        return "CL_MEM_OBJECT_ALLOCATION_FAILURE: the device is out of memory";
    case CL_OUT_OF_RESOURCES:
        return "CL_OUT_OF_RESOURCES: the device is out of memory or other resources";
    case CL_OUT_OF_HOST_MEMORY:
        return "CL_OUT_OF_HOST_MEMORY: out of memory";
    case CL_INVALID_BUFFER_SIZE:
        return "CL_INVALID_BUFFER_SIZE: larger than the device's largest buffer";
    default:
        return "";
    }
}

void check(cl_int status, const char* what) {
    if (status != CL_SUCCESS) {
        const std::string name = error_name(status);
        throw OpenClError(std::string("OpenCL: ") + what + " failed (error " +
                          std::to_string(status) + (name.empty() ? "" : ", " + name) + ")");
    }
}

std::string device_string(cl_device_id device, cl_device_info what) {
    std::size_t size = 0;
    clGetDeviceInfo(device, what, 0, nullptr, &size);
    std::string s(size, '\0');
    clGetDeviceInfo(device, what, size, &s[0], nullptr);
    return std::string(s.c_str());  // drop the terminating zero
}

std::string platform_string(cl_platform_id platform, cl_platform_info what) {
    std::size_t size = 0;
    clGetPlatformInfo(platform, what, 0, nullptr, &size);
    std::string s(size, '\0');
    clGetPlatformInfo(platform, what, size, &s[0], nullptr);
    return std::string(s.c_str());
}

struct DeviceHandle {
    cl_platform_id platform;
    cl_device_id device;
};

std::vector<DeviceHandle> enumerate_devices() {
    cl_uint platform_count = 0;
    if (clGetPlatformIDs(0, nullptr, &platform_count) != CL_SUCCESS || platform_count == 0) {
        return {};  // no ICD, or no platform registered
    }
    std::vector<cl_platform_id> platforms(platform_count);
    check(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs");
    std::vector<DeviceHandle> out;
    for (cl_platform_id p : platforms) {
        cl_uint count = 0;
        if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS) {
            continue;  // CL_DEVICE_NOT_FOUND: a platform with no device
        }
        std::vector<cl_device_id> devices(count);
        check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, count, devices.data(), nullptr),
              "clGetDeviceIDs");
        for (cl_device_id d : devices) {
            out.push_back({p, d});
        }
    }
    return out;
}

std::string type_name(cl_device_id device) {
    cl_device_type type = 0;
    clGetDeviceInfo(device, CL_DEVICE_TYPE, sizeof type, &type, nullptr);
    if (type & CL_DEVICE_TYPE_GPU) {
        return "GPU";
    }
    if (type & CL_DEVICE_TYPE_CPU) {
        return "CPU";
    }
    if (type & CL_DEVICE_TYPE_ACCELERATOR) {
        return "accelerator";
    }
    return "other";
}

}  // namespace

namespace {

using SharedDevice = OpenClDeviceCache;

// Guards the registry and every cache's programs.
std::mutex shared_mutex;

// The device open now as `index`, or a newly opened one. The registry holds
// no device open: only the backends and keep_opencl_device's callers do.
// Called with shared_mutex held.
std::shared_ptr<SharedDevice> shared_device(int index) {
    static std::map<int, std::weak_ptr<SharedDevice>> devices;
    if (std::shared_ptr<SharedDevice> open = devices[index].lock()) {
        return open;
    }
    const std::vector<DeviceHandle> all = enumerate_devices();
    if (all.empty()) {
        throw OpenClError(
            "no OpenCL platform or device found (install an OpenCL driver, "
            "e.g. Debian's pocl-opencl-icd)");
    }
    if (index < 0 || static_cast<std::size_t>(index) >= all.size()) {
        throw OpenClError("--device " + std::to_string(index) + ": no such OpenCL device; " +
                          std::to_string(all.size()) + " found (see --list-devices)");
    }
    auto d = std::make_shared<SharedDevice>();
    d->device = all[static_cast<std::size_t>(index)].device;
    cl_int status = CL_SUCCESS;
    d->context.reset(clCreateContext(nullptr, 1, &d->device, nullptr, nullptr, &status));
    check(status, "clCreateContext");
    d->queue.reset(clCreateCommandQueue(d->context.get(), d->device, 0, &status));
    check(status, "clCreateCommandQueue");
    d->description =
        device_string(d->device, CL_DEVICE_NAME) + " (" +
        platform_string(all[static_cast<std::size_t>(index)].platform, CL_PLATFORM_NAME) + ")";
    devices[index] = d;
    return d;
}

std::string build_log(cl_program program, cl_device_id device) {
    std::size_t size = 0;
    clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
    std::string log(size, '\0');
    clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, &log[0], nullptr);
    return std::string(log.c_str());
}

cl_program get_program(SharedDevice& d, const std::string& appended_source,
                       const std::string& options, double* build_seconds) {
    *build_seconds = 0.0;
    const auto key = std::make_pair(appended_source, options);
    auto found = d.programs.find(key);
    if (found != d.programs.end()) {
        return found->second.get();
    }
    const auto start = std::chrono::steady_clock::now();
    const std::string text = std::string(opencl_kernel_source()) + appended_source;
    const char* source = text.c_str();
    cl_int status = CL_SUCCESS;
    OpenClProgram program(clCreateProgramWithSource(d.context.get(), 1, &source, nullptr, &status));
    check(status, "clCreateProgramWithSource");
    status = clBuildProgram(program.get(), 1, &d.device, options.c_str(), nullptr, nullptr);
    if (status != CL_SUCCESS) {
        const std::string log = build_log(program.get(), d.device);
        throw OpenClError("OpenCL program build failed on " + d.description + " with options '" +
                          options + "' (error " + std::to_string(status) + "); build log:\n" + log);
    }
    *build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cl_program built = program.get();
    d.programs[key] = std::move(program);
    return built;
}

}  // namespace

std::shared_ptr<OpenClDeviceCache> keep_opencl_device(int device_index) {
    std::lock_guard<std::mutex> lock(shared_mutex);
    return shared_device(device_index);
}

void check_opencl(cl_int status, const char* what) { check(status, what); }

OpenClQueue shared_opencl_queue(int device_index) {
    const std::shared_ptr<OpenClDeviceCache> d = keep_opencl_device(device_index);
    return {d->device, d->context.get(), d->queue.get(), d->description, d};
}

std::string opencl_build_options(std::uint32_t features, bool gpu) {
    char mask[32];
    std::snprintf(mask, sizeof mask, "0x%xu", features);
    std::string options = std::string("-cl-std=CL1.2 -DT0_FEATURES=") + mask;
    if (gpu) {
        options += " -DT0_GPU=1";
    }
    if (const char* extra = std::getenv("TRAC0R_OPENCL_OPTIONS")) {
        options += std::string(" ") + extra;
    }
    return options;
}

cl_program embedded_opencl_program(const OpenClQueue& cl, const std::string& appended_source,
                                   const std::string& options) {
    double seconds = 0.0;
    return cached_opencl_program(*cl.cache, appended_source, options, &seconds);
}

std::vector<OpenClDeviceInfo> list_opencl_devices() {
    std::vector<OpenClDeviceInfo> out;
    int index = 0;
    for (const DeviceHandle& h : enumerate_devices()) {
        out.push_back({index++, platform_string(h.platform, CL_PLATFORM_NAME),
                       device_string(h.device, CL_DEVICE_NAME), type_name(h.device)});
    }
    return out;
}

bool opencl_device_is_cpu(cl_device_id device) { return type_name(device) == "CPU"; }

cl_program cached_opencl_program(OpenClDeviceCache& device, const std::string& appended_source,
                                 const std::string& options, double* build_seconds) {
    std::lock_guard<std::mutex> lock(shared_mutex);
    return get_program(device, appended_source, options, build_seconds);
}

}  // namespace trac0r
