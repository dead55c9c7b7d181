// Rays per second, apart from shading: fixed sets of rays (one primary ray
// per pixel, and a diffuse bounce from each primary hit) cast through a
// packed scene by the kernel's own intersect_scene, on the CPU (OpenMP) and
// on an OpenCL device (a small cast kernel appended to the embedded kernel
// source). Used by bench_backends.
#ifndef TRAC0R_BENCHMARKS_RAY_CAST_H
#define TRAC0R_BENCHMARKS_RAY_CAST_H

#include "trac0r/kernel/trace.h"
#include "timing.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/packed_scene.h"

#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_program.h"
#endif

#include <omp.h>

#include <string>
#include <vector>

namespace trac0r_bench {

// Rays as the device reads them: xyz of origin and (unit) direction.
struct RaySet {
    std::vector<glm::vec4> origins;
    std::vector<glm::vec4> directions;
    std::size_t size() const { return origins.size(); }
};

struct RaySets {
    RaySet primary;  // one per pixel, jittered as the renderer does
    RaySet bounce;   // from each primary hit that does not emit: a
                     // cosine-distributed direction about the facing normal
};

// The two sets for `packed` seen by `scene_camera` (in the scene's units;
// seed fixed, so every backend and structure casts the same rays), in the
// packed scene's coordinates (PackedScene::scale).
inline RaySets make_ray_sets(const trac0r::PackedScene& packed,
                             const trac0r::kernel::CameraRecord& scene_camera) {
    using namespace trac0r::kernel;
    const SceneView scene = packed.view();
    const CameraRecord camera = trac0r::scaled_camera(scene_camera, packed.scale);
    const t0_u32 pixels = camera.size.x * camera.size.y;
    RaySets sets;
    sets.primary.origins.resize(pixels);
    sets.primary.directions.resize(pixels);
    std::vector<glm::vec4> bounce_origin(pixels, glm::vec4(0.0f));
    std::vector<glm::vec4> bounce_direction(pixels, glm::vec4(0.0f));
#pragma omp parallel for schedule(dynamic, 256)
    for (long p = 0; p < static_cast<long>(pixels); ++p) {
        const t0_u32 pixel = static_cast<t0_u32>(p);
        Rng rng;
        rng_seed_pixel(&rng, 1, pixel, 0);
        const float jitter_x = rng_float(&rng);
        const float jitter_y = rng_float(&rng);
        const Ray ray = camera_ray(camera, static_cast<float>(pixel % camera.size.x),
                                   static_cast<float>(pixel / camera.size.x), jitter_x, jitter_y);
        sets.primary.origins[pixel] = glm::vec4(ray.origin, 0.0f);
        sets.primary.directions[pixel] = glm::vec4(ray.direction, 0.0f);
        const Hit hit = intersect_scene(&scene, &ray);
        if (hit.triangle < 0) {
            continue;
        }
        const TriangleRecord* tri = &scene.triangles[hit.triangle];
        if (scene.materials[tri->ids.x].type.x == T0_MATERIAL_EMISSIVE) {
            continue;
        }
        const float3 n = xyz(tri->normal);
        const float3 facing = dot(ray.direction, n) < 0.0f ? n : -n;
        const float u1 = rng_float(&rng);
        const float u2 = rng_float(&rng);
        const DirectionSample d = sample_cosine_hemisphere(facing, u1, u2);
        const float3 position = hit_position(tri, hit);
        bounce_origin[pixel] =
            glm::vec4(offset_ray_origin(position, facing, hit_magnitude(tri, position)), 0.0f);
        bounce_direction[pixel] = glm::vec4(d.direction, 1.0f);  // w: a ray is here
    }
    for (t0_u32 p = 0; p < pixels; ++p) {
        if (bounce_direction[p].w > 0.0f) {
            sets.bounce.origins.push_back(bounce_origin[p]);
            sets.bounce.directions.push_back(glm::vec4(glm::vec3(bounce_direction[p]), 0.0f));
        }
    }
    return sets;
}

struct CastResult {
    // One pass over the set on machine_cores() free cores: its CPU time (all
    // threads, mean over the passes) / cores; see timing.h.
    double seconds = 0.0;
    std::size_t hits = 0;  // rays that hit something: the same for every caster
};

// Casts `rays` through `packed` on the CPU: `passes` timed passes after one
// warm-up, OpenMP threads as CpuBackend uses them. An empty set (a scene
// with no triangles has no bounces) takes no time and hits nothing.
inline CastResult cast_cpu(const trac0r::PackedScene& packed, const RaySet& rays, int passes) {
    using namespace trac0r::kernel;
    if (rays.size() == 0) {
        return CastResult{};
    }
    const SceneView scene = packed.view();
    const long n = static_cast<long>(rays.size());
    std::vector<int> hit(rays.size());
    CastResult result;
    double cpu_start = 0.0;
    for (int pass = 0; pass <= passes; ++pass) {
        if (pass == 1) {
            cpu_start = process_cpu_seconds();  // after the warm-up pass
        }
#pragma omp parallel
        {
            // The floating-point mode the CPU backend renders in.
            const trac0r::DenormalsAreZero denormals;
#pragma omp for schedule(dynamic, 64)
            for (long i = 0; i < n; ++i) {
                const Ray ray = make_ray(xyz(rays.origins[i]), xyz(rays.directions[i]));
                hit[i] = intersect_scene(&scene, &ray).triangle >= 0;
            }
        }
    }
    result.seconds = (process_cpu_seconds() - cpu_start) / passes / machine_cores();
    for (int h : hit) {
        result.hits += static_cast<std::size_t>(h);
    }
    return result;
}

#ifdef TRAC0R_HAVE_OPENCL

// The cast kernel, appended to the embedded kernel source: the same
// scene_view, make_ray and intersect_scene the renderer runs.
const char* const cast_kernel_source = R"(
__kernel void cast_rays(__global const TriangleRecord* triangles,
                        __global const ShapeRecord* shapes, __global const BvhNode* nodes,
                        uint shape_count, __global const float4* origins,
                        __global const float4* directions, __global int* hit, uint count,
                        __global const TrianglePacket* packets) {
    const uint i = (uint)get_global_id(0);
    if (i >= count) {
        return;
    }
    const SceneView scene = scene_view(triangles, shapes, 0, nodes, packets, 0, 0, 0, 0, 0, 0, 0, 0, shape_count, 0u, 0u, (float4)(0.0f));
    const Ray ray = make_ray(origins[i].xyz, directions[i].xyz);
    hit[i] = intersect_scene(&scene, &ray).triangle >= 0;
}
)";

// Casts ray sets on OpenCL device 0, on the queue the backends share, with
// the renderer's build options for the scene's mask.
class OpenClCaster {
  public:
    OpenClCaster() : cl_(trac0r::shared_opencl_queue(0)) {}

    // An empty set is not launched: no time, no hits (reading back zero
    // bytes is CL_INVALID_VALUE).
    CastResult cast(const trac0r::PackedScene& packed, const RaySet& rays, int passes) {
        if (rays.size() == 0) {
            return CastResult{};
        }
        const trac0r::OpenClKernel owned_kernel = make_kernel(packed.features);
        cl_kernel kernel = owned_kernel.get();
        std::vector<trac0r::OpenClMem> buffers;
        auto upload = [&](const void* data, std::size_t bytes) {
            cl_int status = CL_SUCCESS;
            // OpenCL buffers may not be empty; nothing reads a dummy one.
            static const glm::vec4 dummy[5] = {};
            buffers.emplace_back(
                clCreateBuffer(cl_.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                               bytes > 0 ? bytes : sizeof dummy,
                               bytes > 0 ? const_cast<void*>(data) : (void*)dummy, &status));
            check(status, "clCreateBuffer");
            return buffers.back().get();
        };
        cl_mem triangles =
            upload(packed.triangles.data(), packed.triangles.size() * sizeof(packed.triangles[0]));
        cl_mem shapes =
            upload(packed.shapes.data(), packed.shapes.size() * sizeof(packed.shapes[0]));
        cl_mem nodes = upload(packed.nodes.data(), packed.nodes.size() * sizeof(packed.nodes[0]));
        cl_mem packets =
            upload(packed.packets.data(), packed.packets.size() * sizeof(packed.packets[0]));
        cl_mem origins = upload(rays.origins.data(), rays.size() * sizeof(glm::vec4));
        cl_mem directions = upload(rays.directions.data(), rays.size() * sizeof(glm::vec4));
        cl_int status = CL_SUCCESS;
        buffers.emplace_back(clCreateBuffer(cl_.context, CL_MEM_WRITE_ONLY,
                                            rays.size() * sizeof(cl_int) + 4, nullptr, &status));
        check(status, "clCreateBuffer(hit)");
        cl_mem hit = buffers.back().get();
        const cl_uint shape_count = static_cast<cl_uint>(packed.shapes.size());
        const cl_uint count = static_cast<cl_uint>(rays.size());
        const cl_mem args[] = {triangles, shapes, nodes};
        for (cl_uint a = 0; a < 3; ++a) {
            check(clSetKernelArg(kernel, a, sizeof(cl_mem), &args[a]), "clSetKernelArg");
        }
        check(clSetKernelArg(kernel, 3, sizeof shape_count, &shape_count), "clSetKernelArg");
        check(clSetKernelArg(kernel, 4, sizeof(cl_mem), &origins), "clSetKernelArg");
        check(clSetKernelArg(kernel, 5, sizeof(cl_mem), &directions), "clSetKernelArg");
        check(clSetKernelArg(kernel, 6, sizeof(cl_mem), &hit), "clSetKernelArg");
        check(clSetKernelArg(kernel, 7, sizeof count, &count), "clSetKernelArg");
        check(clSetKernelArg(kernel, 8, sizeof(cl_mem), &packets), "clSetKernelArg");
        const std::size_t group = 64;
        const std::size_t global = (rays.size() + group - 1) / group * group;
        CastResult result;
        double cpu_start = 0.0;
        for (int pass = 0; pass <= passes; ++pass) {
            if (pass == 1) {
                cpu_start = process_cpu_seconds();  // after the warm-up pass
            }
            check(clEnqueueNDRangeKernel(cl_.queue, kernel, 1, nullptr, &global, nullptr, 0,
                                         nullptr, nullptr),
                  "clEnqueueNDRangeKernel(cast_rays)");
            check(clFinish(cl_.queue), "clFinish");
        }
        result.seconds = (process_cpu_seconds() - cpu_start) / passes / machine_cores();
        std::vector<cl_int> hits(rays.size());
        check(clEnqueueReadBuffer(cl_.queue, hit, CL_TRUE, 0, rays.size() * sizeof(cl_int),
                                  hits.data(), 0, nullptr, nullptr),
              "clEnqueueReadBuffer(hit)");
        for (cl_int h : hits) {
            result.hits += static_cast<std::size_t>(h);
        }
        return result;
    }

  private:
    static void check(cl_int status, const char* what) {
        if (status != CL_SUCCESS) {
            throw trac0r::OpenClError(std::string("OpenCL: ") + what + " failed (error " +
                                      std::to_string(status) + ")");
        }
    }

    trac0r::OpenClKernel make_kernel(std::uint32_t features) {
        cl_program program = trac0r::embedded_opencl_program(
            cl_, cast_kernel_source, trac0r::opencl_build_options(features));
        cl_int status = CL_SUCCESS;
        trac0r::OpenClKernel kernel(clCreateKernel(program, "cast_rays", &status));
        check(status, "clCreateKernel(cast_rays)");
        return kernel;
    }

    trac0r::OpenClQueue cl_;
};

#endif  // TRAC0R_HAVE_OPENCL

}  // namespace trac0r_bench

#endif
