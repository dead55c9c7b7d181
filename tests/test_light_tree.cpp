// The light tree (kernel/light_tree.h): at any point, the probabilities of
// picking each light sum to one, a pick's probability is the one its path
// gives (what MIS reads), and picks follow those probabilities (a
// chi-square test); no light that can reach a point is ever left out; and
// next-event estimation with the tree converges to the image that picking
// by power alone gives, on the CPU and on OpenCL alike.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/kernel/light_sampling.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/shape.h"
#include "test_support.h"

#include <cmath>
#include <memory>
#include <random>
#include <vector>

using namespace trac0r;

namespace {

// A floor under 40 small bulbs (icospheres of 20 triangles: 800 emitting
// triangles) in two colours and two powers, some one-sided, with a point
// and a spot lamp and a sun, so the tree holds triangles of both kinds and
// lamps, and the list has a distant light before them.
Scene bulbs_scene(int width, int height) {
    Scene scene;
    Material floor;
    floor.name = "floor";
    floor.color = glm::vec3(0.6f);
    Material warm;
    warm.name = "warm";
    warm.type = MaterialType::emissive;
    warm.color = glm::vec3(1.0f, 0.7f, 0.4f);
    warm.emittance = 20.0f;
    Material cool = warm;
    cool.name = "cool";
    cool.color = glm::vec3(0.4f, 0.7f, 1.0f);
    cool.emittance = 50.0f;
    cool.two_sided = false;
    scene.materials = {floor, warm, cool};
    scene.shapes.push_back(make_plane(glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(12.0f), 0));
    for (int i = 0; i < 40; ++i) {
        const float x = -4.5f + static_cast<float>(i % 8) * 1.3f;
        const float z = -4.0f + static_cast<float>(i / 8) * 2.0f;
        const float y = 0.3f + 0.25f * static_cast<float>(i % 3);
        scene.shapes.push_back(make_icosphere(glm::vec3(x, y, z), glm::vec3(0.3f * i, 0.0f, 0.0f),
                                              0.05f, 0, 1 + i % 2));
    }
    Lamp point;
    point.type = LampType::point;
    point.position = glm::vec3(2.0f, 1.0f, 1.0f);
    point.power = 2.0f;
    Lamp spot = point;
    spot.type = LampType::spot;
    spot.position = glm::vec3(-2.0f, 1.5f, 0.0f);
    spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f));
    spot.angle = 60.0f;
    spot.blend = 0.3f;
    Lamp sun;
    sun.type = LampType::sun;
    sun.direction = glm::normalize(glm::vec3(0.2f, 1.0f, 0.4f));
    sun.power = 0.3f;
    sun.angle = 3.0f;
    scene.lamps = {point, spot, sun};
    scene.camera.position = glm::vec3(0.0f, 3.0f, 5.0f);
    scene.camera.direction = glm::normalize(glm::vec3(0.0f, -0.6f, -1.0f));
    scene.render.width = width;
    scene.render.height = height;
    scene.render.max_depth = 3;
    return scene;
}

PackOptions tree_options(LightSampler sampler) {
    PackOptions options;
    options.integrator = Integrator::nee;
    options.sampler = SamplerKind::sobol;
    options.light_sampler = sampler;
    return options;
}

}  // namespace

TEST_CASE("the light tree is built where lights are many, or asked for", "[light_tree]") {
    const Scene scene = bulbs_scene(8, 8);
    const PackedScene automatic = pack_scene(scene, tree_options(LightSampler::automatic));
    REQUIRE((automatic.features & T0_FEATURE_LIGHT_TREE) != 0u);
    REQUIRE(automatic.distant_count == 1u);
    // 802 lights with a position: 2 x 802 - 1 nodes.
    REQUIRE(automatic.lights.size() == 803u);
    REQUIRE(automatic.light_nodes.size() == 2u * 802u - 1u);
    const PackedScene power = pack_scene(scene, tree_options(LightSampler::power));
    REQUIRE((power.features & T0_FEATURE_LIGHT_TREE) == 0u);
    REQUIRE(power.light_nodes.empty());
    // The Cornell box's two emitting triangles: no tree unless asked.
    const Scene cornell = load_test_scene("cornell.json", 8, 8);
    REQUIRE((pack_scene(cornell, tree_options(LightSampler::automatic)).features &
             T0_FEATURE_LIGHT_TREE) == 0u);
    REQUIRE((pack_scene(cornell, tree_options(LightSampler::tree)).features &
             T0_FEATURE_LIGHT_TREE) != 0u);
}

TEST_CASE("the tree's pick probabilities sum to one, match its picks, and miss no light",
          "[light_tree]") {
    const PackedScene packed = pack_scene(bulbs_scene(8, 8), tree_options(LightSampler::tree));
    const kernel::SceneView view = packed.view();
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const std::size_t first = packed.distant_count;
    const std::size_t count = packed.lights.size() - first;
    for (int trial = 0; trial < 12; ++trial) {
        // Points over and under the bulbs, normals every way.
        const glm::vec3 p(uniform(rng) * 10.0f - 5.0f, uniform(rng) * 1.2f,
                          uniform(rng) * 10.0f - 5.0f);
        const glm::vec3 n = glm::normalize(
            glm::vec3(uniform(rng) - 0.5f, uniform(rng) - 0.5f, uniform(rng) - 0.5f));
        std::vector<double> pmf(count);
        double sum = 0.0;
        for (std::size_t i = 0; i < count; ++i) {
            pmf[i] = kernel::light_tree_pmf(&view, p, n, packed.lights[first + i].ids.z);
            sum += pmf[i];
        }
        CAPTURE(trial, p.x, p.y, p.z, sum);
        // Below one where a node's bounds let light through but both its
        // children's tighter ones do not: a pick that goes there fails
        // (and brings nothing, as nothing there lights p).
        REQUIRE(sum <= 1.0 + 1e-4);
        REQUIRE(sum > 0.5);
        // No light that reaches p with any cosine at p is left out: every
        // triangle with p in front of it (or behind a two-sided one) and
        // every lamp has a probability above zero.
        for (std::size_t i = 0; i < count; ++i) {
            const kernel::LightRecord& light = packed.lights[first + i];
            if (light.ids.y == T0_LIGHT_TRIANGLE) {
                const kernel::TriangleRecord& t = packed.triangles[light.ids.x];
                const glm::vec3 c = (glm::vec3(t.v0) + glm::vec3(t.v1) + glm::vec3(t.v2)) / 3.0f;
                const float facing = glm::dot(p - c, glm::vec3(t.normal));
                const bool two_sided = packed.materials[t.ids.x].type.z == 0u;
                if (facing > 1e-4f || (two_sided && facing < -1e-4f)) {
                    CAPTURE(i);
                    REQUIRE(pmf[i] > 0.0);
                }
            } else if (light.ids.y == T0_LIGHT_POINT) {
                REQUIRE(pmf[i] > 0.0);
            }
        }
        // 100,000 picks, each with the probability its path gives; their
        // counts against the probabilities by chi-square over the lights
        // expected 5 or more times (the rest pooled) and the failed picks,
        // expected 1 - sum of the time.
        const int picks = 100000;
        std::vector<double> observed(count, 0.0);
        double failed = 0.0;
        int mismatched = 0;  // picks whose probability is not their path's
        for (int k = 0; k < picks; ++k) {
            const kernel::LightPick pick = kernel::light_tree_pick(&view, p, n, uniform(rng));
            if (!(pick.pmf > 0.0f)) {
                failed += 1.0;
                continue;
            }
            if (pick.light < first) {
                ++mismatched;
                continue;
            }
            const std::size_t i = pick.light - first;
            mismatched += std::fabs(pick.pmf - pmf[i]) > 1e-4 * pmf[i];
            observed[i] += 1.0;
        }
        REQUIRE(mismatched == 0);
        std::vector<double> expected;
        for (double probability : pmf) {
            expected.push_back(probability * picks);
        }
        expected.push_back(std::fmax(0.0, 1.0 - sum) * picks);
        observed.push_back(failed);
        // At 1 - 1e-4 (test_support.h's chi_square).
        const ChiSquare chi2 = chi_square(expected, observed);
        CAPTURE(chi2.value, chi2.cells, chi2.critical);
        REQUIRE(chi2.cells > 20);
        REQUIRE(chi2.value < chi2.critical);
    }
}

// As test_nee's comparison of the integrators (require_same_block_means):
// 4 x 4 blocks and the whole image.
TEST_CASE("next-event estimation with the light tree converges to picking by power",
          "[light_tree][nee]") {
    const int width = 32, height = 24;
    const Scene scene = bulbs_scene(width, height);
    // The power picks' variance needs four times the samples for the
    // image's tolerance to be under 5 %.
    const auto render = [&](LightSampler sampler, std::uint64_t seed) {
        Renderer r(scene, std::make_unique<CpuBackend>(), seed, tree_options(sampler));
        const int frames = sampler == LightSampler::tree ? 1024 : 4096;
        for (int i = 0; i < frames; ++i) {
            r.render_frame();
        }
        REQUIRE(r.stats().samples_dropped == 0);
        return r.accumulator();
    };
    const std::vector<kernel::AccumPixel> tree = render(LightSampler::tree, 31);
    const std::vector<kernel::AccumPixel> power = render(LightSampler::power, 32);
    REQUIRE(require_same_block_means(tree, power, width, height, 4) < 0.05);
}

TEST_CASE("the light tree renders alike on OpenCL and the CPU", "[light_tree][opencl]") {
    REQUIRE_FALSE(list_opencl_devices().empty());
    const Scene scene = bulbs_scene(32, 24);
    const PackOptions options = tree_options(LightSampler::tree);
    require_warning_free_build(pack_scene(scene, options));
    Renderer cpu(scene, std::make_unique<CpuBackend>(), 9, options);
    Renderer gpu(scene, std::make_unique<OpenClBackend>(0), 9, options);
    for (int i = 0; i < 8; ++i) {
        cpu.render_frame();
        gpu.render_frame();
    }
    const Image a = cpu.image();
    const Image b = gpu.image();
    const int close = close_pixel_count(a, b);
    CAPTURE(close, a.pixels.size());
    REQUIRE(close >= static_cast<int>(0.95 * a.pixels.size()));
}
