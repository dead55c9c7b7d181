#include "trac0r/opencl_backend.h"

#include "trac0r/filter.h"
#include "trac0r/kernel/tile_grid.h"
#include "trac0r/opencl_owner.h"
#include "trac0r/opencl_program.h"
#include "trac0r/packed_scene.h"

#include <algorithm>
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

// "12 MiB" for sizes of a MiB or more, else "N bytes".
std::string byte_size(std::uint64_t bytes) {
    if (bytes < (1u << 20)) {
        return std::to_string(bytes) + " bytes";
    }
    char text[64];
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1u << 20));
    return text;
}

// The device's largest buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE); 0 where it
// does not say (then nothing is checked before the driver is asked).
std::uint64_t largest_buffer(cl_device_id device) {
    cl_ulong largest = 0;
    if (clGetDeviceInfo(device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof largest, &largest,
                        nullptr) != CL_SUCCESS) {
        return 0;
    }
    return largest;
}

template <typename T>
OpenClMem upload(cl_context context, const std::vector<T>& data) {
    // OpenCL buffers may not be empty: keep one zeroed element at least.
    std::vector<T> padded = data;
    if (padded.empty()) {
        padded.resize(1);
    }
    cl_int status = CL_SUCCESS;
    OpenClMem m(clCreateBuffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                               sizeof(T) * padded.size(), padded.data(), &status));
    check(status, "clCreateBuffer");
    return m;
}

// The arguments of render_frame, named in the order of its signature in
// trac0r/kernel/render.cl: a change there must change this list.
enum RenderFrameArg : cl_uint {
    arg_triangles,      // __global const TriangleRecord*
    arg_shapes,         // __global const ShapeRecord*
    arg_materials,      // __global const MaterialRecord*
    arg_nodes,          // __global const BvhNode*
    arg_shape_count,    // uint
    arg_camera,         // CameraRecord
    arg_accum,          // __global AccumPixel*
    arg_seed,           // ulong
    arg_frame,          // uint
    arg_max_depth,      // int
    arg_lights,         // __global const LightRecord*
    arg_light_count,    // uint
    arg_packets,        // __global const TrianglePacket*
    arg_normals,        // __global const VertexNormals*
    arg_uvs,            // __global const TriangleUVs*
    arg_textures,       // __global const TextureRecord*
    arg_texels,         // __global const uint*
    arg_environment,    // __global const float4*
    arg_distant_count,  // uint
    arg_light_nodes,    // __global const LightTreeNode*
    arg_tangents,       // __global const VertexTangents*
};

// Sets render_frame's argument `index` to `value`: a cl_mem for a buffer,
// else a value of the type the signature names (cl_uint for uint, ...).
template <typename T>
void set_arg(cl_kernel kernel, RenderFrameArg index, const T& value) {
    check(clSetKernelArg(kernel, index, sizeof value, &value),
          ("clSetKernelArg(" + std::to_string(index) + ")").c_str());
}

// The scene's arrays on the device, uploaded once per scene change.
struct SceneBuffers {
    OpenClMem triangles;
    OpenClMem shapes;
    OpenClMem materials;
    OpenClMem nodes;
    OpenClMem packets;
    OpenClMem lights;
    OpenClMem normals;
    OpenClMem uvs;
    OpenClMem tangents;
    OpenClMem textures;
    OpenClMem texels;
    OpenClMem environment;
    OpenClMem light_nodes;
};

SceneBuffers upload_scene(cl_context context, const PackedScene& scene, std::uint64_t largest,
                          const std::string& device) {
    // Each checked before any is made: a scene too large for the device
    // is one message naming its first buffer over the limit.
    const auto check = [&](const char* name, std::size_t bytes) {
        if (largest > 0) {
            check_opencl_buffer_size(name, std::max<std::size_t>(bytes, 1), largest, device);
        }
    };
    check("the scene's triangles", sizeof(scene.triangles[0]) * scene.triangles.size());
    check("the scene's shapes", sizeof(scene.shapes[0]) * scene.shapes.size());
    check("the scene's materials", sizeof(scene.materials[0]) * scene.materials.size());
    check("the scene's BVH nodes", sizeof(scene.nodes[0]) * scene.nodes.size());
    check("the scene's triangle packets", sizeof(scene.packets[0]) * scene.packets.size());
    check("the scene's lights", sizeof(scene.lights[0]) * scene.lights.size());
    check("the scene's vertex normals", sizeof(scene.normals[0]) * scene.normals.size());
    check("the scene's texture coordinates", sizeof(scene.uvs[0]) * scene.uvs.size());
    check("the scene's tangents", sizeof(scene.tangents[0]) * scene.tangents.size());
    check("the scene's texture records", sizeof(scene.textures[0]) * scene.textures.size());
    check("the scene's texels", sizeof(scene.texels[0]) * scene.texels.size());
    check("the environment map", sizeof(glm::vec4) * scene.environment.size());
    check("the light tree", sizeof(scene.light_nodes[0]) * scene.light_nodes.size());
    SceneBuffers buffers;
    buffers.triangles = upload(context, scene.triangles);
    buffers.shapes = upload(context, scene.shapes);
    buffers.materials = upload(context, scene.materials);
    buffers.nodes = upload(context, scene.nodes);
    buffers.packets = upload(context, scene.packets);
    buffers.lights = upload(context, scene.lights);
    buffers.normals = upload(context, scene.normals);
    buffers.uvs = upload(context, scene.uvs);
    buffers.tangents = upload(context, scene.tangents);
    buffers.textures = upload(context, scene.textures);
    buffers.texels = upload(context, scene.texels);
    buffers.environment = upload(context, scene.environment);
    buffers.light_nodes = upload(context, scene.light_nodes);
    return buffers;
}

}  // namespace

void check_opencl_buffer_size(const std::string& buffer, std::uint64_t bytes,
                              std::uint64_t largest, const std::string& device) {
    if (bytes > largest) {
        throw OpenClError("OpenCL: " + buffer + " need " + byte_size(bytes) +
                          " in one buffer, more than the " + byte_size(largest) + " that device " +
                          device + " allows in one (CL_DEVICE_MAX_MEM_ALLOC_SIZE): use --backend cpu, or a smaller scene");
    }
}

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
    std::lock_guard<std::mutex> lock(shared_mutex);
    double seconds = 0.0;
    return get_program(*cl.cache, appended_source, options, &seconds);
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

// The BVH program's work-group: one tile of T0_TILE x T0_TILE pixels.
const std::size_t kTileItems = T0_TILE * T0_TILE;

struct OpenClBackend::State {
    std::shared_ptr<SharedDevice> device;  // kept open while the backend lives
    int device_index = 0;                  // list_opencl_devices' index of it
    float scale = 1.0f;                    // the packed scene's (scaled_camera)
    OpenClKernel kernel;
    SceneBuffers scene;
    OpenClMem accum;
    std::size_t pixels = 0;
    bool bvh = false;  // the BVH's program: a tile a work-group
    cl_uint shape_count = 0;
    cl_uint light_count = 0;
    cl_uint distant_count = 0;
    double build_seconds = 0.0;
    std::string options;
};

namespace {

std::unique_ptr<OpenClBackend::State> opened_state(int device_index) {
    std::unique_ptr<OpenClBackend::State> state(new OpenClBackend::State);
    std::lock_guard<std::mutex> lock(shared_mutex);
    state->device = shared_device(device_index);
    state->device_index = device_index;
    return state;
}

}  // namespace

OpenClBackend::OpenClBackend(int device_index) : OpenClBackend(opened_state(device_index)) {}

OpenClBackend::OpenClBackend(std::unique_ptr<State> state)
    : Backend("opencl", state->device->description), state_(std::move(state)) {}

OpenClBackend::~OpenClBackend() = default;

double OpenClBackend::last_build_seconds() const { return state_->build_seconds; }

std::string OpenClBackend::build_options() const { return state_->options; }

void OpenClBackend::set_scene(const PackedScene& scene) {
    state_->scale = scene.scale;
    const std::string options =
        opencl_build_options(scene.features, type_name(state_->device->device) != "CPU");
    cl_program program = nullptr;
    {
        std::lock_guard<std::mutex> lock(shared_mutex);
        program = get_program(*state_->device, "", options, &state_->build_seconds);
    }
    state_->kernel.reset();
    cl_int status = CL_SUCCESS;
    state_->kernel.reset(clCreateKernel(program, "render_frame", &status));
    check(status, "clCreateKernel(render_frame)");
    state_->options = options;
    // The BVH's program renders a tile of 8 x 8 pixels a work-group of 64
    // (render.cl), the flat list's a pixel a work-item in groups of the
    // driver's choice. Groups of 64 also suit PoCL: it picks groups of
    // thousands of work-items on a CPU and lays their private arrays out
    // side by side, and the BVH's traversal stack (1,184 bytes a
    // work-item) then streams megabytes through the cache; with 64, BVH
    // frames on cornell.json took 4.5 % less time. The flat list, which
    // has no such array, took 3 % more (bench_backends, alternated;
    // docs/performance.md, "Kernel tuning").
    state_->bvh = (scene.features & T0_FEATURE_BVH) != 0u;
    if (state_->bvh) {
        std::size_t most = 0;
        check(clGetKernelWorkGroupInfo(state_->kernel.get(), state_->device->device,
                                       CL_KERNEL_WORK_GROUP_SIZE, sizeof most, &most, nullptr),
              "clGetKernelWorkGroupInfo(CL_KERNEL_WORK_GROUP_SIZE)");
        std::size_t sizes[3] = {0, 0, 0};
        check(clGetDeviceInfo(state_->device->device, CL_DEVICE_MAX_WORK_ITEM_SIZES, sizeof sizes,
                              sizes, nullptr),
              "clGetDeviceInfo(CL_DEVICE_MAX_WORK_ITEM_SIZES)");
        most = std::min(most, sizes[0]);
        if (most < kTileItems) {
            throw OpenClError("OpenCL device " + state_->device->description +
                              " runs the BVH program in work-groups of at most " +
                              std::to_string(most) + " work-items; it needs " +
                              std::to_string(kTileItems) + " (one 8 x 8 tile): use --accel flat");
        }
    }
    // Uploaded once per scene change; a frame sends only its small arguments.
    // The old scene's buffers go first: the device never holds two scenes.
    state_->scene = SceneBuffers();
    state_->scene = upload_scene(state_->device->context.get(), scene,
                                 largest_buffer(state_->device->device),
                                 state_->device->description);
    state_->shape_count = static_cast<cl_uint>(scene.shapes.size());
    state_->light_count = static_cast<cl_uint>(scene.lights.size());
    state_->distant_count = static_cast<cl_uint>(scene.distant_count);
}

void OpenClBackend::reset(int width, int height) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    cl_int status = CL_SUCCESS;
    if (pixels != state_->pixels || !state_->accum) {
        // Said before asking: the driver's answer is a bare error code.
        const std::size_t bytes = sizeof(kernel::AccumPixel) * pixels;
        cl_ulong largest = 0;
        if (clGetDeviceInfo(state_->device->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof largest,
                            &largest, nullptr) == CL_SUCCESS &&
            bytes > largest) {
            throw OpenClError("OpenCL: the accumulator of " + std::to_string(width) + " x " +
                              std::to_string(height) + " pixels needs " +
                              std::to_string(bytes >> 20) + " MiB, more than the device's " +
                              "largest buffer (" + std::to_string(largest >> 20) +
                              " MiB): try a smaller --width and --height, or --backend cpu");
        }
        state_->accum.reset();  // the old one first, as the scene's buffers
        state_->accum.reset(clCreateBuffer(state_->device->context.get(), CL_MEM_READ_WRITE,
                                           sizeof(kernel::AccumPixel) * pixels, nullptr, &status));
        check(status, "clCreateBuffer(accumulator)");
        state_->pixels = pixels;
    }
    const cl_float zero = 0.0f;
    check(clEnqueueFillBuffer(state_->device->queue.get(), state_->accum.get(), &zero, sizeof zero,
                              0, sizeof(kernel::AccumPixel) * pixels, 0, nullptr, nullptr),
          "clEnqueueFillBuffer(accumulator)");
}

void OpenClBackend::render_frame(const kernel::CameraRecord& camera, std::uint64_t seed,
                                 std::uint32_t frame, int max_depth) {
    render_frame_cancellable(camera, seed, frame, max_depth, CancelCheck());
}

bool OpenClBackend::render_frame_cancellable(const kernel::CameraRecord& camera, std::uint64_t seed,
                                             std::uint32_t frame, int max_depth,
                                             const CancelCheck& cancel) {
    cl_kernel k = state_->kernel.get();
    const cl_ulong seed_arg = seed;
    const cl_uint frame_arg = frame;
    const cl_int depth_arg = max_depth;
    const kernel::CameraRecord scaled = scaled_camera(camera, state_->scale);
    // Every argument, in the order of render_frame's signature.
    set_arg(k, arg_triangles, state_->scene.triangles.get());
    set_arg(k, arg_shapes, state_->scene.shapes.get());
    set_arg(k, arg_materials, state_->scene.materials.get());
    set_arg(k, arg_nodes, state_->scene.nodes.get());
    set_arg(k, arg_shape_count, state_->shape_count);
    set_arg(k, arg_camera, scaled);
    set_arg(k, arg_accum, state_->accum.get());
    set_arg(k, arg_seed, seed_arg);
    set_arg(k, arg_frame, frame_arg);
    set_arg(k, arg_max_depth, depth_arg);
    set_arg(k, arg_lights, state_->scene.lights.get());
    set_arg(k, arg_light_count, state_->light_count);
    set_arg(k, arg_packets, state_->scene.packets.get());
    set_arg(k, arg_normals, state_->scene.normals.get());
    set_arg(k, arg_uvs, state_->scene.uvs.get());
    set_arg(k, arg_textures, state_->scene.textures.get());
    set_arg(k, arg_texels, state_->scene.texels.get());
    set_arg(k, arg_environment, state_->scene.environment.get());
    set_arg(k, arg_distant_count, state_->distant_count);
    set_arg(k, arg_light_nodes, state_->scene.light_nodes.get());
    set_arg(k, arg_tangents, state_->scene.tangents.get());
    std::size_t global = 0;
    const std::size_t* local = nullptr;  // the driver's choice
    if (state_->bvh) {
        const std::size_t tiles = kernel::tile_count(camera.size.x, camera.size.y);
        global = tiles * kTileItems;
        local = &kTileItems;
    } else {
        // A multiple of 64, which a driver choosing the groups can split evenly.
        global = (state_->pixels + 63) / 64 * 64;
    }
    cl_command_queue queue = state_->device->queue.get();
    // Parts of whole tiles (64 work-items each, both ways), launched with a
    // global offset; without a `cancel`, the frame in one launch.
    const std::size_t groups = global / 64;
    const std::size_t chunks = cancel ? std::min<std::size_t>(opencl_cancel_chunks, groups) : 1;
    const auto launch = [&](std::size_t c, OpenClEvent* done) {
        const std::size_t first = groups * c / chunks * 64;
        const std::size_t size = groups * (c + 1) / chunks * 64 - first;
        cl_event event = nullptr;
        check(clEnqueueNDRangeKernel(queue, k, 1, &first, &size, local, 0, nullptr,
                                     done ? &event : nullptr),
              "clEnqueueNDRangeKernel(render_frame)");
        if (done) {
            done->reset(event);
        }
    };
    if (cancel && cancel()) {
        return false;
    }
    bool finished = true;
    if (chunks <= 1) {
        launch(0, nullptr);
    } else {
        // One part queued ahead of the one waited for, so the device never
        // waits for the host between them.
        OpenClEvent waited;
        launch(0, &waited);
        for (std::size_t c = 0; c < chunks; ++c) {
            OpenClEvent next;
            if (c + 1 < chunks) {
                launch(c + 1, &next);
            }
            cl_event e = waited.get();
            check(clWaitForEvents(1, &e), "clWaitForEvents(render_frame)");
            if (c + 1 < chunks && cancel()) {
                finished = false;
                break;
            }
            waited = std::move(next);
        }
    }
    // A frame is done when render_frame returns, so timings are honest and
    // the queue never runs far ahead of the viewer.
    check(clFinish(queue), "clFinish");
    return finished;
}

void OpenClBackend::read_accumulator(std::vector<kernel::AccumPixel>& out) {
    out.resize(state_->pixels);
    check(clEnqueueReadBuffer(state_->device->queue.get(), state_->accum.get(), CL_TRUE, 0,
                              sizeof(kernel::AccumPixel) * state_->pixels, out.data(), 0, nullptr,
                              nullptr),
          "clEnqueueReadBuffer(accumulator)");
}

Image OpenClBackend::filter_accumulation(const std::vector<kernel::AccumPixel>& accumulator,
                                         int width, int height,
                                         const std::vector<kernel::FilterGuide>& guides,
                                         int passes) {
    return opencl_filter_image(state_->device_index, accumulator, width, height, guides, passes);
}

}  // namespace trac0r
