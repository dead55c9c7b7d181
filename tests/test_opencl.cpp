// The OpenCL backend on PoCL (CI) or any device: the same kernel headers
// build as OpenCL C for every feature mask the scenes use, and the images
// agree with the CPU backend's. A missing device fails these tests.
#include <catch2/catch.hpp>

#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/accumulate.h"
#include "trac0r/kernel/ray_offset.h"
#include "trac0r/kernel/sampling.h"
#include "trac0r/kernel/tile_grid.h"
#include "trac0r/kernel/trace.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/opencl_program.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "test_support.h"

#include <sys/wait.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using namespace trac0r;

TEST_CASE("an OpenCL device is present", "[opencl]") {
    // No skip: CI installs PoCL, so no device means a broken installation.
    REQUIRE_FALSE(list_opencl_devices().empty());
    OpenClBackend backend(0);
    INFO(backend.device());
    REQUIRE_FALSE(backend.device().empty());
}

TEST_CASE("the kernel builds as OpenCL C for every scene's feature mask, warning-free",
          "[opencl]") {
    const char* scenes[] = {"cornell.json",  "cornell_diffuse.json", "furnace.json",
                            "mesh_demo.json", "mtl_demo.json",       "smooth_demo.json",
                            "materials_demo.json"};
    for (const char* name : scenes) {
        CAPTURE(name);
        const Scene scene = load_test_scene(name, 8, 8);
        const PackedScene packed = pack_scene(scene);
        require_warning_free_build(packed);
    }
}

TEST_CASE("--accel auto on OpenCL builds a BVH from PoCL's crossover", "[opencl]") {
    // README, "Performance": on PoCL the BVH is faster from the smallest
    // scene measured, the Cornell box's walls and lamp (12 triangles).
    Scene scene = builtin_scene();
    scene.shapes.resize(6);  // walls and lamp
    scene.render.width = 8;
    scene.render.height = 6;
    const Renderer gpu(scene, std::make_unique<OpenClBackend>(0), 1, PackOptions());
    REQUIRE(gpu.packed().triangles.size() == auto_bvh_min_triangles);
    REQUIRE(gpu.packed().features & T0_FEATURE_BVH);
    scene.shapes.resize(5);  // the walls without the lamp: 10 triangles
    const Renderer fewer(scene, std::make_unique<OpenClBackend>(0), 1, PackOptions());
    REQUIRE(fewer.packed().features & T0_FEATURE_FLAT);
}

TEST_CASE("a program is built once per feature mask and then reused", "[opencl]") {
    const PackedScene packed = pack_scene(load_test_scene("cornell_diffuse.json", 8, 8));
    OpenClBackend first(0);
    first.set_scene(packed);
    OpenClBackend second(0);
    second.set_scene(packed);
    REQUIRE(second.last_build_seconds() == 0.0);
}

// An OpenCL call's status: CL_SUCCESS, or the test fails naming the call.
static void require_cl(cl_int status, const char* what) {
    INFO(what);
    REQUIRE(status == CL_SUCCESS);
}

// The count of references to `context`, as the driver keeps it: its queue,
// programs and buffers each hold one (PoCL, and the OpenCL 1.2 spec's
// retain rules for objects made on a context).
static cl_uint context_references(cl_context context) {
    cl_uint count = 0;
    require_cl(clGetContextInfo(context, CL_CONTEXT_REFERENCE_COUNT, sizeof count, &count, nullptr),
               "clGetContextInfo(CL_CONTEXT_REFERENCE_COUNT)");
    return count;
}

TEST_CASE("the device's queue and programs go with the last backend on it", "[opencl]") {
    const PackedScene packed = pack_scene(load_test_scene("cornell_diffuse.json", 8, 8));
    cl_context context = nullptr;
    {
        OpenClBackend backend(0);
        backend.set_scene(packed);
        backend.reset(8, 8);
        context = shared_opencl_queue(0).context;
        require_cl(clRetainContext(context), "clRetainContext");  // ours, to ask after
        REQUIRE(context_references(context) > 2);                 // ours, the queue, ...
        OpenClBackend again(0);  // the same device, open: the same context
        REQUIRE(shared_opencl_queue(0).context == context);
    }
    // Only our own reference is left: queue, program, kernel and buffers are
    // released, and the context with ours.
    REQUIRE(context_references(context) == 1);
    clReleaseContext(context);
    // A backend made now opens the device again and builds its program anew.
    OpenClBackend next(0);
    next.set_scene(packed);
    REQUIRE(next.last_build_seconds() > 0.0);
}

TEST_CASE("a kept device shares its programs with backends made one after another", "[opencl]") {
    const PackedScene packed = pack_scene(load_test_scene("cornell_diffuse.json", 8, 8));
    const std::shared_ptr<OpenClDeviceCache> keep = keep_opencl_device(0);
    { OpenClBackend(0).set_scene(packed); }
    OpenClBackend later(0);
    later.set_scene(packed);
    REQUIRE(later.last_build_seconds() == 0.0);
}

// Both backends run the same code on the same random numbers, so most pixels
// agree to float rounding; a path that takes another branch because of a
// last-bit difference (e.g. fused multiply-add on one side) diverges, so the
// comparison is statistical: the mean over 8x8 blocks must agree within 5
// standard errors of the difference (from the per-pixel spread in the CPU
// image), and most individual pixels must agree closely.
// Both backends on the same structure (--accel auto may choose by backend).
static void compare_backends(const std::string& name, Accel accel,
                             SamplerKind sampler = SamplerKind::random,
                             float aperture_radius = 0.0f,
                             Projection projection = Projection::perspective) {
    // An odd size: the last column and row of tiles (work-groups, with the
    // BVH) cut off.
    Scene scene = load_test_scene(name, 61, 45);
    if (aperture_radius > 0.0f) {
        scene.camera.aperture_radius = aperture_radius;
        scene.camera.focus_distance = 1.5f;  // the back wall's depth (1.7) blurs a little
    }
    scene.camera.projection = projection;
    scene.camera.view_height = 0.9f;  // orthographic: most of the box's 1 m
    const int frames = 16;
    PackOptions options;
    options.accel = accel;
    options.sampler = sampler;
    Renderer cpu(scene, std::make_unique<CpuBackend>(), 11, options);
    Renderer gpu(scene, std::make_unique<OpenClBackend>(0), 11, options);
    for (int i = 0; i < frames; ++i) {
        cpu.render_frame();
        gpu.render_frame();
    }
    const Image a = cpu.image();
    const Image b = gpu.image();
    const auto& moments = cpu.accumulator();
    int close_pixels = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
        if (d.x + d.y + d.z <= 1e-3f * (1.0f + a.pixels[i].x + a.pixels[i].y + a.pixels[i].z)) {
            ++close_pixels;
        }
    }
    CAPTURE(name, close_pixels, a.pixels.size());
    REQUIRE(close_pixels >= static_cast<int>(0.9 * a.pixels.size()));
    const int block = 8;
    for (int by = 0; by < a.height; by += block) {
        for (int bx = 0; bx < a.width; bx += block) {
            double la = 0.0, lb = 0.0, variance = 0.0;
            int n = 0;
            for (int y = by; y < std::min(by + block, a.height); ++y) {
                for (int x = bx; x < std::min(bx + block, a.width); ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * a.width + x;
                    la += kernel::luminance(a.pixels[i]);
                    lb += kernel::luminance(b.pixels[i]);
                    // Variance of one pixel's mean: M2 / (n - 1) / n.
                    variance += moments[i].moments.y / (frames - 1) / frames;
                    ++n;
                }
            }
            // The difference of two independent block means has twice the
            // variance of one (an upper bound: the shared seeds correlate them).
            const double se = std::sqrt(2.0 * variance) / n;
            CAPTURE(bx, by, la / n, lb / n, se);
            REQUIRE(std::fabs(la - lb) / n <= 5.0 * se + 1e-6);
        }
    }
}

TEST_CASE("OpenCL and CPU images of cornell.json agree", "[opencl]") {
    compare_backends("cornell.json", Accel::bvh);
}

TEST_CASE("OpenCL and CPU images of cornell_diffuse.json agree", "[opencl]") {
    compare_backends("cornell_diffuse.json", Accel::bvh);
    compare_backends("cornell_diffuse.json", Accel::flat);
}

TEST_CASE("OpenCL and CPU images agree with the sobol sampler", "[opencl][sampler]") {
    // The same integer arithmetic on both sides: the same numbers.
    compare_backends("cornell.json", Accel::bvh, SamplerKind::sobol);
    compare_backends("cornell_diffuse.json", Accel::bvh, SamplerKind::sobol);
}

TEST_CASE("OpenCL and CPU images through a thin lens agree", "[opencl][camera]") {
    // The lens' numbers, the tile path's bypass of the bundle (BVH), and
    // the flat list's pixel a work-item.
    compare_backends("cornell.json", Accel::bvh, SamplerKind::sobol, 0.03f);
    compare_backends("cornell.json", Accel::flat, SamplerKind::random, 0.03f);
}

TEST_CASE("OpenCL and CPU images from an orthographic camera agree", "[opencl][camera]") {
    // Its rays from all over the view: the tile path's bypass of the
    // bundle (BVH), the flat list's pixel a work-item, and through a lens.
    compare_backends("cornell.json", Accel::bvh, SamplerKind::sobol, 0.0f,
                     Projection::orthographic);
    compare_backends("cornell.json", Accel::flat, SamplerKind::random, 0.03f,
                     Projection::orthographic);
}

TEST_CASE("OpenCL and CPU images of a smooth-shaded mesh agree", "[opencl][smooth]") {
    compare_backends("smooth_demo.json", Accel::bvh);
    compare_backends("smooth_demo.json", Accel::flat, SamplerKind::sobol);
}

TEST_CASE("OpenCL and CPU images of the microfacet materials agree",
          "[opencl][microfacet]") {
    compare_backends("materials_demo.json", Accel::bvh, SamplerKind::sobol);
}

TEST_CASE("a GPU's program renders what the CPU device's does, bit for bit", "[opencl][gpu]") {
    // The program as a GPU builds it (T0_GPU=1: traverse_bvh_groups, a
    // triangle and a child at a time, kernel/tuning.h) against PoCL's own,
    // both on PoCL: the same hits in the same order, so the same image.
    struct Options {
        explicit Options(const char* o) { setenv("TRAC0R_OPENCL_OPTIONS", o, 1); }
        ~Options() { unsetenv("TRAC0R_OPENCL_OPTIONS"); }
    };
    for (const char* name : {"cornell.json", "texture_demo.json", "materials_demo.json"}) {
        const Scene scene = load_test_scene(name, 61, 45);
        PackOptions options;
        options.accel = Accel::bvh;
        std::vector<Image> images;
        for (const char* o : {"-Werror", "-DT0_GPU=1 -Werror"}) {
            const Options set(o);
            Renderer r(scene, std::make_unique<OpenClBackend>(0), 11, options);
            for (int i = 0; i < 4; ++i) {
                r.render_frame();
            }
            images.push_back(r.image());
        }
        int differ = 0;
        for (std::size_t i = 0; i < images[0].pixels.size(); ++i) {
            differ += images[0].pixels[i] == images[1].pixels[i] ? 0 : 1;
        }
        CAPTURE(name);
        REQUIRE(differ == 0);
    }
}

TEST_CASE("furnace on the OpenCL backend", "[opencl][furnace]") {
    // scenes/furnace.json: diffuse walls of albedo rho = 0.5 that emit
    // Le = colour x emittance = 0.5.
    Scene scene = load_test_scene("furnace.json", 32, 24);
    const double expected = furnace_expected_mean(scene);
    Renderer r(scene, std::make_unique<OpenClBackend>(0), 3);
    for (int i = 0; i < 24; ++i) {
        r.render_frame();
    }
    require_furnace_mean(r.accumulator(), expected);
}

namespace {

// A kernel appended to the embedded source: the helpers whose OpenCL and
// C++ code differ (choose_f picks by bits in OpenCL and is ?: in C++), and
// the quarter turn made by bit operations, on the device.
const char* const helpers_kernel_source = R"(
__kernel void bit_helpers(__global const float* u, uint turns, __global float* turned,
                          __global const float4* moves, uint move_count, __global float* moved) {
    const uint i = (uint)get_global_id(0);
    if (i < turns) {
        const float2_cs r = turn_cos_sin(u[i]);
        turned[2 * i] = r.c;
        turned[2 * i + 1] = r.s;
    }
    if (i < move_count) {
        const float4 m = moves[i];
        moved[2 * i] = offset_coordinate(m.x, m.y, m.z);
        moved[2 * i + 1] = next_float_towards(m.x, m.y);
    }
}
)";

}  // namespace

TEST_CASE("the quarter turn and the ray offset give the same floats on OpenCL as in C++",
          "[opencl]") {
    // Angles: a grid of 2^16, and each side of every eighth turn (where the
    // quadrant changes or the reduction reaches pi/4).
    std::vector<float> u;
    for (int i = 0; i < (1 << 16); ++i) {
        u.push_back(static_cast<float>(i) / 65536.0f);
    }
    for (int k = 1; k <= 8; ++k) {
        const float at = static_cast<float>(k) / 8.0f;
        u.push_back(std::nextafter(at, 0.0f));
        if (k < 8) {
            u.push_back(std::nextafter(at, 1.0f));
        }
    }
    // Offsets (p, n, distance): zeros of both signs in p and n, tiny, huge
    // and ordinary coordinates. No subnormal inputs: a device may flush them.
    std::vector<glm::vec4> moves;
    const float ps[] = {0.0f,  -0.0f, FLT_MIN, -FLT_MIN, 1e-30f,  -1e-30f, 0.5f,
                        -0.5f, 1.0f,  -1.0f,   123.456f, -7.0e4f, FLT_MAX, -FLT_MAX};
    const float ns[] = {0.0f, -0.0f, 0.3f, -0.3f, 1.0f, -1.0f};
    const float distances[] = {0.0f, 1e-7f, 1e-3f};
    for (float p : ps) {
        for (float n : ns) {
            for (float distance : distances) {
                moves.push_back(glm::vec4(p, n, distance, 0.0f));
            }
        }
    }

    // Device 0's shared queue (no device: OpenClError fails the test). The
    // kernel is compiled for the built-in scene's mask, as the renderer
    // would; the helpers do not depend on it.
    const OpenClQueue cl = shared_opencl_queue(0);
    cl_program program = embedded_opencl_program(
        cl, helpers_kernel_source, opencl_build_options(pack_scene(builtin_scene()).features));
    cl_int status = CL_SUCCESS;
    const OpenClKernel owned_kernel(clCreateKernel(program, "bit_helpers", &status));
    require_cl(status, "clCreateKernel");
    cl_kernel kernel = owned_kernel.get();

    std::vector<OpenClMem> owned;
    auto buffer = [&](cl_mem_flags flags, std::size_t bytes, void* data) {
        owned.emplace_back(clCreateBuffer(cl.context, flags, bytes, data, &status));
        require_cl(status, "clCreateBuffer");
        return owned.back().get();
    };
    cl_mem u_buffer =
        buffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, u.size() * sizeof(float), u.data());
    cl_mem turned_buffer = buffer(CL_MEM_WRITE_ONLY, 2 * u.size() * sizeof(float), nullptr);
    cl_mem moves_buffer = buffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                 moves.size() * sizeof(glm::vec4), moves.data());
    cl_mem moved_buffer = buffer(CL_MEM_WRITE_ONLY, 2 * moves.size() * sizeof(float), nullptr);
    const cl_uint turns = static_cast<cl_uint>(u.size());
    const cl_uint move_count = static_cast<cl_uint>(moves.size());
    require_cl(clSetKernelArg(kernel, 0, sizeof(cl_mem), &u_buffer), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 1, sizeof turns, &turns), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 2, sizeof(cl_mem), &turned_buffer), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 3, sizeof(cl_mem), &moves_buffer), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 4, sizeof move_count, &move_count), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 5, sizeof(cl_mem), &moved_buffer), "clSetKernelArg");
    const std::size_t global = std::max(u.size(), moves.size());
    require_cl(
        clEnqueueNDRangeKernel(cl.queue, kernel, 1, nullptr, &global, nullptr, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel");
    std::vector<float> turned(2 * u.size());
    std::vector<float> moved(2 * moves.size());
    require_cl(
        clEnqueueReadBuffer(cl.queue, turned_buffer, CL_TRUE, 0, turned.size() * sizeof(float),
                            turned.data(), 0, nullptr, nullptr),
        "clEnqueueReadBuffer");
    require_cl(clEnqueueReadBuffer(cl.queue, moved_buffer, CL_TRUE, 0, moved.size() * sizeof(float),
                                   moved.data(), 0, nullptr, nullptr),
               "clEnqueueReadBuffer");

    int turn_mismatches = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        const kernel::float2_cs r = kernel::turn_cos_sin(u[i]);
        if (bits_of(r.c) != bits_of(turned[2 * i]) || bits_of(r.s) != bits_of(turned[2 * i + 1])) {
            UNSCOPED_INFO("u " << u[i] << ": C++ " << r.c << ", " << r.s << "; OpenCL "
                               << turned[2 * i] << ", " << turned[2 * i + 1]);
            ++turn_mismatches;
        }
    }
    CHECK(turn_mismatches == 0);
    int move_mismatches = 0;
    for (std::size_t i = 0; i < moves.size(); ++i) {
        const glm::vec4 m = moves[i];
        const float offset = kernel::offset_coordinate(m.x, m.y, m.z);
        const float next = kernel::next_float_towards(m.x, m.y);
        if (bits_of(offset) != bits_of(moved[2 * i]) ||
            bits_of(next) != bits_of(moved[2 * i + 1])) {
            UNSCOPED_INFO("p " << m.x << " n " << m.y << " distance " << m.z << ": C++ " << offset
                               << ", " << next << "; OpenCL " << moved[2 * i] << ", "
                               << moved[2 * i + 1]);
            ++move_mismatches;
        }
    }
    CHECK(move_mismatches == 0);
}

namespace {

// The BVH program's camera hits, as render_frame finds them (a tile a
// work-group, tile_sample), and through the tree (intersect_scene),
// per pixel (t, u, v, the triangle's bits), with the pixel's camera ray
// direction and each tile's leaf count.
const char* const tile_hits_kernel_source = R"(
__kernel void tile_hits(__global const TriangleRecord* triangles, __global const BvhNode* nodes,
                        __global const TrianglePacket* packets, CameraRecord camera, ulong seed,
                        uint frame, __global float4* bundled, __global float4* traversed,
                        __global float4* directions, __global int* counts) {
    const SceneView scene = scene_view(triangles, 0, 0, nodes, packets, 0, 0, 0, 0, 0, 0, 0, 0, 0u, 0u, 0u, (float4)(0.0f));
    __local TileShared shared;
    const TileSample t = tile_sample(&scene, camera, seed, frame, &shared);
    if (t.inside) {
        const Hit a = t.first;
        const Hit b = intersect_scene(&scene, &t.sample.ray);
        bundled[t.pixel] = (float4)(a.t, a.u, a.v, as_float(a.triangle));
        traversed[t.pixel] = (float4)(b.t, b.u, b.v, as_float(b.triangle));
        directions[t.pixel] = (float4)(t.sample.ray.direction, 0.0f);
    }
    if (get_local_id(0) == 0u) {
        counts[get_group_id(0)] = shared.leaf_count;
    }
}
)";

struct DeviceTiles {
    long bundled_tiles = 0;
    long traversed_tiles = 0;
    int hits = 0;
};

// Runs tile_hits over a width x height image of `scene` (packed with the
// BVH) on device 0: every pixel written once, by the work-item of its own
// tile (its ray is the host's begin_pixel ray, to within rounding), and
// every camera ray's hit among its tile's leaves is its hit through the
// tree, bit for bit. With `gpu`, the program a GPU gets (T0_GPU: its
// traversal stack, kernel/tuning.h).
DeviceTiles device_tile_hits(const Scene& scene, int width, int height, bool gpu = false) {
    PackOptions options;
    options.accel = Accel::bvh;
    const PackedScene packed = pack_scene(scene, options);
    const kernel::CameraRecord camera =
        scaled_camera(make_camera_record(scene.camera, width, height), packed.scale);
    const kernel::SceneView view = packed.view();
    const OpenClQueue cl = shared_opencl_queue(0);
    cl_program program =
        embedded_opencl_program(cl, tile_hits_kernel_source, opencl_build_options(packed.features, gpu));
    cl_int status = CL_SUCCESS;
    const OpenClKernel owned_kernel(clCreateKernel(program, "tile_hits", &status));
    require_cl(status, "clCreateKernel");
    cl_kernel kernel = owned_kernel.get();
    std::vector<OpenClMem> owned;
    auto upload = [&](const auto& v) {
        owned.emplace_back(clCreateBuffer(
            cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, v.size() * sizeof(v[0]),
            const_cast<void*>(static_cast<const void*>(v.data())), &status));
        require_cl(status, "clCreateBuffer");
        return owned.back().get();
    };
    // Outputs filled with a pattern no written value has (all bits set: a
    // NaN distance; for the counts, a count above any bundle's).
    auto output = [&](std::size_t bytes, cl_uint pattern) {
        owned.emplace_back(clCreateBuffer(cl.context, CL_MEM_READ_WRITE, bytes, nullptr, &status));
        require_cl(status, "clCreateBuffer");
        cl_mem m = owned.back().get();
        require_cl(clEnqueueFillBuffer(cl.queue, m, &pattern, sizeof pattern, 0, bytes, 0, nullptr,
                                       nullptr),
                   "clEnqueueFillBuffer");
        return m;
    };
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    const std::size_t tiles =
        kernel::tile_count(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    const cl_uint unwritten = 0xffffffffu;
    const cl_uint unwritten_count = 0x7fffffffu;
    cl_mem buffers[] = {upload(packed.triangles),
                        upload(packed.nodes),
                        upload(packed.packets),
                        output(pixels * sizeof(glm::vec4), unwritten),
                        output(pixels * sizeof(glm::vec4), unwritten),
                        output(pixels * sizeof(glm::vec4), unwritten),
                        output(tiles * sizeof(cl_int), unwritten_count)};
    const cl_ulong seed = 7;
    const cl_uint frame = 3;
    for (cl_uint i = 0; i < 3; ++i) {
        require_cl(clSetKernelArg(kernel, i, sizeof(cl_mem), &buffers[i]), "clSetKernelArg");
    }
    require_cl(clSetKernelArg(kernel, 3, sizeof camera, &camera), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 4, sizeof seed, &seed), "clSetKernelArg");
    require_cl(clSetKernelArg(kernel, 5, sizeof frame, &frame), "clSetKernelArg");
    for (cl_uint i = 3; i < 7; ++i) {
        require_cl(clSetKernelArg(kernel, i + 3, sizeof(cl_mem), &buffers[i]), "clSetKernelArg");
    }
    const std::size_t local = T0_TILE * T0_TILE;
    const std::size_t global = tiles * local;
    require_cl(
        clEnqueueNDRangeKernel(cl.queue, kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel");
    std::vector<glm::vec4> bundled(pixels);
    std::vector<glm::vec4> traversed(pixels);
    std::vector<glm::vec4> directions(pixels);
    std::vector<cl_int> counts(tiles);
    std::vector<glm::vec4>* per_pixel[] = {&bundled, &traversed, &directions};
    for (int k = 0; k < 3; ++k) {
        require_cl(
            clEnqueueReadBuffer(cl.queue, buffers[3 + k], CL_TRUE, 0, pixels * sizeof(glm::vec4),
                                per_pixel[k]->data(), 0, nullptr, nullptr),
            "clEnqueueReadBuffer");
    }
    require_cl(clEnqueueReadBuffer(cl.queue, buffers[6], CL_TRUE, 0, tiles * sizeof(cl_int),
                                   counts.data(), 0, nullptr, nullptr),
               "clEnqueueReadBuffer");

    int unwritten_pixels = 0;
    int misplaced = 0;
    int mismatches = 0;
    DeviceTiles result;
    for (std::size_t i = 0; i < pixels; ++i) {
        if (bits_of(traversed[i].x) == unwritten || bits_of(directions[i].x) == unwritten) {
            ++unwritten_pixels;
            continue;
        }
        kernel::PixelSample host;
        kernel::begin_pixel(&view, camera, static_cast<std::uint32_t>(i), seed, frame, &host);
        if (glm::length(glm::vec3(directions[i]) - host.ray.direction) > 1e-5f) {
            UNSCOPED_INFO("pixel " << i << ": the device's ray (" << directions[i].x << ", "
                                   << directions[i].y << ", " << directions[i].z
                                   << ") is not the pixel's (" << host.ray.direction.x << ", "
                                   << host.ray.direction.y << ", " << host.ray.direction.z
                                   << ")");
            ++misplaced;
        }
        bool same = true;
        for (int k = 0; k < 4; ++k) {
            same = same && bits_of(bundled[i][k]) == bits_of(traversed[i][k]);
        }
        if (!same) {
            UNSCOPED_INFO("pixel " << i << ": bundled t " << bundled[i].x << ", traversed t "
                                   << traversed[i].x);
            ++mismatches;
        }
        result.hits += bits_of(traversed[i].w) != 0xffffffffu ? 1 : 0;  // triangle -1: no hit
    }
    CHECK(unwritten_pixels == 0);
    CHECK(misplaced == 0);
    CHECK(mismatches == 0);
    for (cl_int c : counts) {
        CHECK(c >= -1);
        CHECK(c <= T0_BUNDLE_LEAVES);
        (c >= 0 ? result.bundled_tiles : result.traversed_tiles) += 1;
    }
    return result;
}

}  // namespace

TEST_CASE("a tile's camera rays find the same hits among their leaves on OpenCL", "[opencl]") {
    // The Cornell box at an odd size (tiles cut off at the right and
    // bottom): most tiles share their leaves, as on the CPU (test_bvh).
    const DeviceTiles cornell = device_tile_hits(builtin_scene(), 157, 121);
    CAPTURE(cornell.bundled_tiles, cornell.traversed_tiles, cornell.hits);
    REQUIRE(cornell.bundled_tiles > 5 * cornell.traversed_tiles);
    REQUIRE(cornell.hits > 157 * 121 / 2);
    // Tiles that meet more leaves than a bundle holds traverse.
    const DeviceTiles sphere = device_tile_hits(cornell_with_dense_sphere(), 96, 72);
    CAPTURE(sphere.bundled_tiles, sphere.traversed_tiles);
    REQUIRE(sphere.traversed_tiles > 0);
    REQUIRE(sphere.bundled_tiles > 0);
}

TEST_CASE("a GPU's program finds the same camera hits, traversing with its own stack",
          "[opencl][gpu]") {
    // The program built as for a GPU (T0_GPU=1: the group stack of
    // traverse_bvh_groups), run on PoCL: the tiles that traverse find the
    // hits that their leaves give, bit for bit.
    const DeviceTiles sphere = device_tile_hits(cornell_with_dense_sphere(), 96, 72, true);
    CAPTURE(sphere.bundled_tiles, sphere.traversed_tiles, sphere.hits);
    REQUIRE(sphere.traversed_tiles > 0);
    REQUIRE(sphere.hits > 96 * 72 / 2);
}

TEST_CASE("an unknown device index is an error", "[opencl]") {
    REQUIRE_THROWS_WITH(OpenClBackend(999), Catch::Contains("--device 999: no such OpenCL device"));
}

TEST_CASE("a kernel that fails to build reports the build log", "[opencl]") {
    // A define that breaks the kernel source.
    setenv("TRAC0R_OPENCL_OPTIONS", "-Dmake_ray=syntax_error(", 1);
    OpenClBackend backend(0);
    const PackedScene packed = pack_scene(load_test_scene("furnace.json", 8, 8));
    REQUIRE_THROWS_WITH(backend.set_scene(packed),
                        Catch::Contains("build log") && Catch::Contains("syntax_error"));
    unsetenv("TRAC0R_OPENCL_OPTIONS");
}

TEST_CASE("the viewer exits non-zero with the build log on a broken kernel", "[opencl][cli]") {
    const std::string command = "TRAC0R_OPENCL_OPTIONS='-Dmake_ray=syntax_error(' " +
                                std::string(TRAC0R_VIEWER) +
                                " --headless --backend opencl --width 8 --height 8 --spp 1 "
                                "--output broken.pfm 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string output;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) {
        output += buffer;
    }
    const int status = pclose(pipe);
    INFO(output);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) != 0);
    REQUIRE(output.find("build log") != std::string::npos);
}
