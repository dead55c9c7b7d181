#include "trac0r/opencl_backend.h"

#include "trac0r/filter.h"
#include "trac0r/kernel/tile_grid.h"
#include "trac0r/opencl_owner.h"
#include "trac0r/opencl_program.h"
#include "trac0r/packed_scene.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace trac0r {

namespace {

void check(cl_int status, const char* what) { check_opencl(status, what); }

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
    if (clGetDeviceInfo(device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof largest, &largest, nullptr) !=
        CL_SUCCESS) {
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
    arg_sphere,         // float4
    // bdpt_frame's, after render_frame's:
    arg_frame_radiance,  // __global float4*
    arg_splats,          // __global long*
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

void check_opencl_buffer_size(const std::string& buffer, std::uint64_t bytes, std::uint64_t largest,
                              const std::string& device) {
    if (bytes > largest) {
        throw OpenClError(
            "OpenCL: " + buffer + " need " + byte_size(bytes) + " in one buffer, more than the " +
            byte_size(largest) + " that device " + device +
            " allows in one (CL_DEVICE_MAX_MEM_ALLOC_SIZE): use --backend cpu, or a smaller scene");
    }
}

// The BVH program's work-group: one tile of T0_TILE x T0_TILE pixels.
const std::size_t kTileItems = T0_TILE * T0_TILE;

struct OpenClBackend::State {
    std::shared_ptr<OpenClDeviceCache> device;  // kept open while the backend lives
    int device_index = 0;                       // list_opencl_devices' index of it
    float scale = 1.0f;                         // the packed scene's (scaled_camera)
    OpenClKernel kernel;
    SceneBuffers scene;
    OpenClMem accum;
    // Bidirectional path tracing (T0_FEATURE_BDPT): its frame kernel (in
    // `kernel`), the merge, each pixel's own light and the splat sums.
    bool bdpt = false;
    OpenClKernel merge;
    OpenClMem frame_radiance;
    OpenClMem splats;
    glm::vec4 sphere = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
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
    state->device = keep_opencl_device(device_index);
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
        opencl_build_options(scene.features, !opencl_device_is_cpu(state_->device->device));
    cl_program program =
        cached_opencl_program(*state_->device, "", options, &state_->build_seconds);
    state_->kernel.reset();
    state_->merge.reset();
    cl_int status = CL_SUCCESS;
    state_->bdpt = (scene.features & T0_FEATURE_BDPT) != 0u;
    const char* name = state_->bdpt ? "bdpt_frame" : "render_frame";
    state_->kernel.reset(clCreateKernel(program, name, &status));
    check(status, (std::string("clCreateKernel(") + name + ")").c_str());
    if (state_->bdpt) {
        state_->merge.reset(clCreateKernel(program, "bdpt_merge_frame", &status));
        check(status, "clCreateKernel(bdpt_merge_frame)");
    }
    state_->sphere = scene.sphere;
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
    state_->bvh = (scene.features & T0_FEATURE_BVH) != 0u && !state_->bdpt;
    // Both run groups of 64 work-items: the BVH's program a tile, BDPT's
    // 64 pixels (render_frame_cancellable).
    if (state_->bvh || state_->bdpt) {
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
            throw OpenClError("OpenCL device " + state_->device->description + " runs the " +
                              (state_->bdpt ? "BDPT" : "BVH") +
                              " program in work-groups of at most " + std::to_string(most) +
                              " work-items; it needs " + std::to_string(kTileItems) +
                              (state_->bdpt ? ": use --integrator nee or --backend cpu"
                                            : " (one 8 x 8 tile): use --accel flat"));
        }
    }
    // Uploaded once per scene change; a frame sends only its small arguments.
    // The old scene's buffers go first: the device never holds two scenes.
    state_->scene = SceneBuffers();
    state_->scene =
        upload_scene(state_->device->context.get(), scene, largest_buffer(state_->device->device),
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
        state_->frame_radiance.reset();
        state_->splats.reset();
    }
    if (state_->bdpt) {
        clear_splats();
    }
    const cl_float zero = 0.0f;
    check(clEnqueueFillBuffer(state_->device->queue.get(), state_->accum.get(), &zero, sizeof zero,
                              0, sizeof(kernel::AccumPixel) * pixels, 0, nullptr, nullptr),
          "clEnqueueFillBuffer(accumulator)");
}

// Bidirectional path tracing's frame buffers, made where missing (a scene
// set since the last reset), and the splat sums zeroed.
void OpenClBackend::clear_splats() {
    const std::size_t pixels = state_->pixels;
    cl_int status = CL_SUCCESS;
    if (!state_->splats) {
        state_->frame_radiance.reset(clCreateBuffer(state_->device->context.get(),
                                                    CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels,
                                                    nullptr, &status));
        check(status, "clCreateBuffer(frame radiance)");
        state_->splats.reset(clCreateBuffer(state_->device->context.get(), CL_MEM_READ_WRITE,
                                            4 * sizeof(cl_long) * pixels, nullptr, &status));
        check(status, "clCreateBuffer(splats)");
    }
    const cl_long none = 0;
    check(clEnqueueFillBuffer(state_->device->queue.get(), state_->splats.get(), &none, sizeof none,
                              0, 4 * sizeof(cl_long) * pixels, 0, nullptr, nullptr),
          "clEnqueueFillBuffer(splats)");
}

void OpenClBackend::render_frame(const kernel::CameraRecord& camera, std::uint64_t seed,
                                 std::uint32_t frame, int max_depth) {
    render_frame_cancellable(camera, seed, frame, max_depth, CancelCheck());
}

bool OpenClBackend::render_frame_cancellable(const kernel::CameraRecord& camera, std::uint64_t seed,
                                             std::uint32_t frame, int max_depth,
                                             const CancelCheck& cancel) {
    if (state_->bdpt && !state_->splats) {
        clear_splats();
    }
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
    const cl_float4 sphere = {
        {state_->sphere.x, state_->sphere.y, state_->sphere.z, state_->sphere.w}};
    set_arg(k, arg_sphere, sphere);
    if (state_->bdpt) {
        set_arg(k, arg_frame_radiance, state_->frame_radiance.get());
        set_arg(k, arg_splats, state_->splats.get());
    }
    std::size_t global = 0;
    const std::size_t* local = nullptr;  // the driver's choice
    if (state_->bvh) {
        const std::size_t tiles = kernel::tile_count(camera.size.x, camera.size.y);
        global = tiles * kTileItems;
        local = &kTileItems;
    } else {
        // A multiple of 64, which a driver choosing the groups can split evenly.
        global = (state_->pixels + 63) / 64 * 64;
        if (state_->bdpt) {
            // Groups of 64 too: each work-item holds its two subpaths (16
            // KB), and PoCL keeps a group's private arrays side by side on
            // its thread's stack, which groups of thousands overflowed.
            local = &kTileItems;
        }
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
    if (finished && state_->bdpt) {
        // Every pixel's sample and splats are in: accumulate them.
        cl_kernel merge = state_->merge.get();
        const cl_uint pixels = static_cast<cl_uint>(state_->pixels);
        const cl_mem buffers[3] = {state_->accum.get(), state_->frame_radiance.get(),
                                   state_->splats.get()};
        for (cl_uint i = 0; i < 3; ++i) {
            check(clSetKernelArg(merge, i, sizeof(cl_mem), &buffers[i]), "clSetKernelArg");
        }
        check(clSetKernelArg(merge, 3, sizeof pixels, &pixels), "clSetKernelArg");
        const std::size_t merge_global = (state_->pixels + 63) / 64 * 64;
        check(clEnqueueNDRangeKernel(queue, merge, 1, nullptr, &merge_global, nullptr, 0, nullptr,
                                     nullptr),
              "clEnqueueNDRangeKernel(bdpt_merge_frame)");
    }
    if (!finished && state_->bdpt) {
        clear_splats();  // the stopped frame's splats: none of them may reach the next
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
