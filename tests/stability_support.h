// What several test_stability_*.cpp files need (issue 5, docs/stability.md):
// the test scenes (the closed room), one-thread CPU renders, the image
// statistics that compare two renders or a render with its expected mean,
// and the room at the origin that the scale and OpenCL cases compare with.
// Cases already proven elsewhere are listed in docs/stability.md, not
// repeated.
#ifndef TRAC0R_TESTS_STABILITY_SUPPORT_H
#define TRAC0R_TESTS_STABILITY_SUPPORT_H

#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/trace.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace trac0r {
namespace stability {

// The kernel's nearest hit, for a ray made in place (the kernel takes it
// by pointer).
inline kernel::Hit nearest_hit(const kernel::SceneView* view, kernel::Ray ray) {
    return kernel::intersect_scene(view, &ray);
}

// ---- Scenes -----------------------------------------------------------------

inline Material make_material(MaterialType type, glm::vec3 color, float emittance = 0.0f,
                              float roughness = 0.0f, float ior = 1.5f) {
    Material m;
    m.name = to_string(type);
    m.type = type;
    m.color = color;
    m.emittance = emittance;
    m.roughness = roughness;
    m.ior = ior;
    return m;
}

// The camera at `position` looking along `direction` with `vertical_fov`
// degrees, an image of size x size pixels, and paths of max_depth vertices.
inline void set_view(Scene& scene, glm::vec3 position, glm::vec3 direction, float vertical_fov,
                     int size, int max_depth) {
    scene.camera.position = position;
    scene.camera.direction = direction;
    scene.camera.vertical_fov = vertical_fov;
    scene.render.width = size;
    scene.render.height = size;
    scene.render.max_depth = max_depth;
}

// A closed room (a box of side 2 s centred on `offset`) with a lamp under the
// ceiling and a block on the floor; the camera stands inside. At s = 1 every
// coordinate relative to `offset` is a multiple of 1/128, so moving the room
// to an integer offset up to 2^17 changes no vertex by rounding: the scene
// is the same, only its distance from the origin differs.
inline Scene room(float s, glm::vec3 offset, float lamp_emittance = 8.0f) {
    Scene scene;
    scene.materials.push_back(make_material(MaterialType::diffuse, glm::vec3(0.7f)));
    scene.materials.push_back(
        make_material(MaterialType::emissive, glm::vec3(1.0f, 0.9f, 0.8f), lamp_emittance));
    scene.materials.push_back(make_material(MaterialType::diffuse, glm::vec3(0.3f, 0.5f, 0.7f)));
    const glm::vec3 no_rotation(0.0f);
    scene.shapes.push_back(make_box(offset, no_rotation, glm::vec3(2.0f * s), 0));
    scene.shapes.push_back(make_plane(offset + s * glm::vec3(0.0f, 0.875f, 0.0f), no_rotation,
                                      glm::vec2(0.75f * s), 1));
    scene.shapes.push_back(make_box(offset + s * glm::vec3(0.25f, -0.625f, 0.25f), no_rotation,
                                    glm::vec3(0.75f * s), 2));
    set_view(scene, offset + s * glm::vec3(0.0f, 0.0f, -0.875f), glm::vec3(0.0f, -0.1f, 1.0f),
             70.0f, 16, 5);
    return scene;
}

// The thesis' algorithm (naive paths, xorshift numbers), which these tests
// were written for: the numerics test replays its random numbers.
inline PackOptions with(Accel accel) {
    PackOptions o;
    o.accel = accel;
    o.integrator = Integrator::naive;
    o.sampler = SamplerKind::random;
    return o;
}

// ---- Rendering and statistics ----------------------------------------------

// One CPU thread: a render is the same for any thread count (test_render.cpp
// proves it), and for images this small, on a machine shared with other
// work, OpenMP's waiting threads cost ten times what they give.
inline std::unique_ptr<CpuBackend> cpu() { return std::make_unique<CpuBackend>(1); }

inline std::unique_ptr<Renderer> render(const Scene& scene, int frames, std::uint64_t seed = 1,
                                        Accel accel = Accel::automatic) {
    std::unique_ptr<Renderer> r(new Renderer(scene, cpu(), seed, with(accel)));
    for (int i = 0; i < frames; ++i) {
        r->render_frame();
    }
    return r;
}

inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline int non_finite_pixels(const Image& image) {
    int count = 0;
    for (const glm::vec3& p : image.pixels) {
        count += !finite(p);
    }
    return count;
}

// The mean luminance of a set of pixels' samples and the variance of that
// mean, from the accumulator's per-pixel Welford moments (samples are
// independent, so the variances of the pixel means add).
struct Estimate {
    double mean = 0.0;
    double variance = 0.0;
    double standard_error() const { return std::sqrt(variance); }
};

inline Estimate estimate(const std::vector<kernel::AccumPixel>& accum,
                         const std::vector<int>& pixels) {
    Estimate e;
    for (int i : pixels) {
        const kernel::AccumPixel& p = accum[static_cast<std::size_t>(i)];
        const double n = p.moments.z;
        e.mean += p.moments.x;
        e.variance += n > 1.0 ? p.moments.y / (n - 1.0) / n : 0.0;
    }
    const double count = static_cast<double>(pixels.size());
    e.mean /= count;
    e.variance /= count * count;
    return e;
}

inline std::vector<int> all_pixels(int width, int height) {
    std::vector<int> pixels(static_cast<std::size_t>(width * height));
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        pixels[i] = static_cast<int>(i);
    }
    return pixels;
}

inline std::vector<int> block_pixels(int width, int bx, int by, int block) {
    std::vector<int> pixels;
    for (int y = by; y < by + block; ++y) {
        for (int x = bx; x < bx + block; ++x) {
            pixels.push_back(y * width + x);
        }
    }
    return pixels;
}

// Two renders of the same expected image agree within noise: the image means
// and every block's mean (a 4 x 4 grid of blocks) differ by less than five
// standard errors of the difference (the renders are independent: other
// seeds, other float paths). Five standard errors: a false alarm once in
// 1.7 million comparisons, and the seeds are fixed. The comparison must be
// able to fail: five standard errors of the difference of the image means
// must be below `resolution` of the mean (acne, leaks or an offset through
// a wall that change that share of the light are then caught).
inline void require_same_image(Renderer& a, Renderer& b, double resolution) {
    REQUIRE(a.width() == b.width());
    REQUIRE(a.height() == b.height());
    const Estimate ea = estimate(a.accumulator(), all_pixels(a.width(), a.height()));
    const Estimate eb = estimate(b.accumulator(), all_pixels(b.width(), b.height()));
    const double difference_se = std::sqrt(ea.variance + eb.variance);
    CAPTURE(ea.mean, eb.mean, ea.standard_error(), eb.standard_error(), resolution);
    REQUIRE(5.0 * difference_se < resolution * ea.mean);
    REQUIRE(std::fabs(ea.mean - eb.mean) < 5.0 * difference_se);
    const int block = a.width() / 4;
    for (int by = 0; by < a.height(); by += block) {
        for (int bx = 0; bx < a.width(); bx += block) {
            const std::vector<int> pixels = block_pixels(a.width(), bx, by, block);
            const Estimate ba = estimate(a.accumulator(), pixels);
            const Estimate bb = estimate(b.accumulator(), pixels);
            CAPTURE(bx, by, ba.mean, bb.mean, ba.standard_error(), bb.standard_error());
            // 1e-6: blocks that are exactly black (or constant) in both.
            REQUIRE(std::fabs(ba.mean - bb.mean) <
                    5.0 * std::sqrt(ba.variance + bb.variance) + 1e-6 * (1.0 + ba.mean));
        }
    }
    REQUIRE(a.stats().samples_dropped == 0);
    REQUIRE(b.stats().samples_dropped == 0);
}

// ---- The room at the origin ------------------------------------------------

// The room at 32 x 32: 96 frames bring each image's standard error to about
// 1.3 % of its mean, so five standard errors of a difference (sqrt 2 of that)
// stay below the 10 % resolution that require_same_image demands.

const int room_frames = 96;

inline std::unique_ptr<Renderer> render_room(float scale, glm::vec3 offset, std::uint64_t seed) {
    Scene scene = room(scale, offset);
    scene.render.width = 32;
    scene.render.height = 32;
    return render(scene, room_frames, seed);
}

// The reference: the room at the origin at scale 1, seed 5, rendered once
// for the three cases that compare with it.
inline Renderer& room_at_origin() {
    static const std::unique_ptr<Renderer> reference = render_room(1.0f, glm::vec3(0.0f), 5);
    return *reference;
}

}  // namespace stability
}  // namespace trac0r

#endif
