// The stability cases that run the OpenCL backend (issue 5,
// docs/stability.md): emitters far smaller than their distance on both
// backends, and the OpenCL backend's determinism, dropped non-finite
// samples and scenes at 1e5 and 1e15. In one file, so one CTest test (one
// process) builds their programs once.
#include <catch2/catch.hpp>

#include "stability_support.h"
#include "trac0r/opencl_backend.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

using namespace trac0r;
using namespace trac0r::stability;

// A cloud of 2,000 emitting triangles of 1e-7 in a cube of side 2, one
// shape (so the flat list tests every one for each ray through the cube),
// seen from 2 units away: no camera ray passes within 1e-4 of one (the
// chance is below 1e-3 for the whole image), so the image is black.
Scene tiny_emitters() {
    Scene scene;
    scene.materials.push_back(make_material(MaterialType::emissive, glm::vec3(1.0f), 1.0f));
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Shape shape;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        shape.triangles.emplace_back(c, c + 1e-7f * glm::vec3(u(rng), u(rng), u(rng)),
                                     c + 1e-7f * glm::vec3(u(rng), u(rng), u(rng)));
        shape.aabb.extend(shape.triangles.back().bounds());
    }
    scene.shapes.push_back(shape);
    set_view(scene, glm::vec3(0.2f, 0.3f, -3.0f), glm::vec3(0.0f, 0.0f, 1.0f), 50.0f, 24, 2);
    return scene;
}

TEST_CASE(
    "emitters far smaller than their distance from the camera are not seen where no ray "
    "passes them, on both backends",
    "[stability][intersect][opencl]") {
    // Before the exact check of zero edge functions, hundreds of pixels
    // were lit by hits a unit away from any emitter.
    const Scene scene = tiny_emitters();
    const Accel structures[] = {Accel::flat, Accel::bvh};
    for (Accel accel : structures) {
        CAPTURE(accel == Accel::bvh);
        Renderer on_cpu(scene, cpu(), 3, with(accel));
        Renderer on_opencl(scene, std::make_unique<OpenClBackend>(0), 3, with(accel));
        for (int frame = 0; frame < 4; ++frame) {
            on_cpu.render_frame();
            on_opencl.render_frame();
        }
        int lit_cpu = 0;
        int lit_opencl = 0;
        for (std::size_t i = 0; i < on_cpu.image().pixels.size(); ++i) {
            lit_cpu += on_cpu.image().pixels[i] != glm::vec3(0.0f);
            lit_opencl += on_opencl.image().pixels[i] != glm::vec3(0.0f);
        }
        CHECK(lit_cpu == 0);
        CHECK(lit_opencl == 0);
    }
}

TEST_CASE(
    "the OpenCL backend: bit-identical for the same seed, non-finite samples dropped, "
    "and a scene at 1e5 renders as the CPU's at the origin",
    "[stability][numerics][opencl]") {
    // All three scenes have the room's feature mask, so PoCL builds one
    // program (seconds) and every backend below reuses it. The offset and
    // the hit point's pull into its triangle are bit tricks and float steps
    // that OpenCL C compiles on its own: the scene at 1e5 checks them there.
    auto opencl = [](const Scene& scene, std::uint64_t seed, int frames) {
        std::unique_ptr<Renderer> r(
            new Renderer(scene, std::make_unique<OpenClBackend>(0), seed, with(Accel::automatic)));
        for (int i = 0; i < frames; ++i) {
            r->render_frame();
        }
        return r;
    };
    SECTION("same seed, same bits; another seed, another image; infinities dropped") {
        // The block emits infinitely: paths that reach it are (inf, inf, inf)
        // and dropped; those that reach the lamp carry finite light.
        Scene scene = room(1.0f, glm::vec3(0.0f));
        scene.materials[2] = make_material(MaterialType::emissive, glm::vec3(0.3f, 0.5f, 0.7f),
                                           std::numeric_limits<float>::infinity());
        const int frames = 3;
        std::unique_ptr<Renderer> a = opencl(scene, 21, frames);
        std::unique_ptr<Renderer> b = opencl(scene, 21, frames);
        std::unique_ptr<Renderer> c = opencl(scene, 22, frames);
        const std::vector<kernel::AccumPixel>& accum_a = a->accumulator();
        const std::vector<kernel::AccumPixel>& accum_b = b->accumulator();
        REQUIRE(accum_a.size() == accum_b.size());
        CHECK(std::memcmp(accum_a.data(), accum_b.data(),
                          accum_a.size() * sizeof(kernel::AccumPixel)) == 0);
        CHECK(a->image().pixels != c->image().pixels);
        CHECK(a->stats().samples_dropped > 0);
        CHECK(a->stats().samples_dropped == b->stats().samples_dropped);
        CHECK(non_finite_pixels(a->image()) == 0);
        int lit = 0;
        for (const kernel::AccumPixel& p : accum_a) {
            REQUIRE(p.moments.z + p.moments.w == static_cast<float>(frames));  // each sample once
            lit += p.moments.x > 0.0f;
        }
        CHECK(lit > 0);
    }
    SECTION("at 1e5 as on the CPU at the origin") {
        Scene far = room(1.0f, glm::vec3(1e5f));
        far.render.width = 32;
        far.render.height = 32;
        std::unique_ptr<Renderer> gpu = opencl(far, 6, room_frames);
        require_same_image(room_at_origin(), *gpu, 0.1);
    }
    SECTION(
        "scaled by 1e15 (packed at ordinary size, the camera scaled by the backend) as on "
        "the CPU at scale 1") {
        Scene huge = room(1e15f, glm::vec3(0.0f));
        huge.render.width = 32;
        huge.render.height = 32;
        std::unique_ptr<Renderer> gpu = opencl(huge, 6, room_frames);
        REQUIRE(gpu->packed().scale != 1.0f);
        require_same_image(room_at_origin(), *gpu, 0.1);
    }
}
