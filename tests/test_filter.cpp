// The edge-preserving filter (kernel/filter.h): it keeps the image's
// energy and its edges (of geometry and of light), smooths noise, and
// leaves pixels that see nothing as they are.
#include "test_support.h"
#include "viewer_process.h"

#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/filter.h"
#include "trac0r/image_io.h"
#include "trac0r/renderer.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <utility>
#include <vector>

using namespace trac0r;

namespace {

// A pixel that accumulated n samples of mean `colour` whose luminance has
// sample variance `variance`.
kernel::AccumPixel pixel_of(const glm::vec3& colour, float variance, float n) {
    kernel::AccumPixel p{};
    p.sum = glm::vec4(colour * n, 0.0f);
    p.compensation = glm::vec4(0.0f);
    p.moments = glm::vec4(kernel::luminance(colour), variance * (n - 1.0f), n, 0.0f);
    return p;
}

kernel::FilterGuide guide_of(const glm::vec3& albedo, float depth, const glm::vec3& normal) {
    kernel::FilterGuide g;
    g.albedo = glm::vec4(albedo, depth);
    g.normal = glm::vec4(normal, 0.0f);
    g.emission = glm::vec4(0.0f);
    return g;
}

double mean_luminance(const Image& image, int x0, int x1) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            sum += kernel::luminance(image.at(x, y));
            ++n;
        }
    }
    return sum / n;
}

double spread(const Image& image, int x0, int x1) {
    const double mean = mean_luminance(image, x0, x1);
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            const double d = kernel::luminance(image.at(x, y)) - mean;
            sum += d * d;
            ++n;
        }
    }
    return std::sqrt(sum / n);
}

const int width = 64;
const int height = 32;

// Noisy halves: the left of brightness `left`, the right of `right`, each
// pixel off its half's value by noise of relative size 0.3 (4 samples of
// that spread); the guides from guide(x).
template <typename Guide>
void noisy_halves(float left, float right, Guide guide, std::vector<kernel::AccumPixel>* accum,
                  std::vector<kernel::FilterGuide>* guides) {
    std::mt19937 rng(5);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float base = x < width / 2 ? left : right;
            const float v = base * std::max(0.05f, 1.0f + noise(rng));
            // Four samples: the variance of one is (0.3 base)^2 * 4.
            accum->push_back(pixel_of(glm::vec3(v), 0.36f * base * base, 4.0f));
            guides->push_back(guide(x));
        }
    }
}

// Scene `name` rendered at w x h, 4 spp (NEE) on the CPU, and
// its filter guides.
std::unique_ptr<Renderer> render_4spp(const char* name, int w, int h,
                                      std::vector<kernel::FilterGuide>* guides) {
    PackOptions options;
    options.integrator = Integrator::nee;
    std::unique_ptr<Renderer> r(
        new Renderer(load_test_scene(name, w, h), std::make_unique<CpuBackend>(), 3, options));
    for (int i = 0; i < 4; ++i) {
        r->render_frame();
    }
    *guides = filter_guides(render_guides(r->packed(), r->camera_record()));
    return r;
}

// The kernel's per-pixel filter (filter_input, filter_tap, filter_noise,
// atrous_pixel, filter_output: what OpenCL runs), pixel by pixel on the
// CPU: the reference the CPU's vectorized passes must equal.
Image scalar_filter(const std::vector<kernel::AccumPixel>& accum, int w, int h,
                    const std::vector<kernel::FilterGuide>& guides, int passes) {
    const std::size_t n = accum.size();
    std::vector<kernel::FilterPixel> a(n), b(n);
    std::vector<kernel::FilterTap> taps(n);
    std::vector<kernel::FilterNoise> noise(n);
    for (std::size_t i = 0; i < n; ++i) {
        a[i] = kernel::filter_input(accum[i], guides[i]);
        taps[i] = kernel::filter_tap(guides.data(), w, h, static_cast<int>(i % w),
                                     static_cast<int>(i / w));
    }
    for (int pass = 0; pass < passes; ++pass) {
        for (std::size_t i = 0; i < n; ++i) {
            noise[i] = kernel::filter_noise(a[i]);
        }
        for (std::size_t i = 0; i < n; ++i) {
            b[i] = kernel::atrous_pixel(a.data(), taps.data(), noise.data(), w, h,
                                        static_cast<int>(i % w), static_cast<int>(i / w), pass);
        }
        std::swap(a, b);
    }
    Image out;
    out.width = w;
    out.height = h;
    for (std::size_t i = 0; i < n; ++i) {
        out.pixels.push_back(kernel::filter_output(a[i], guides[i]));
    }
    return out;
}

// Requires `fast` (the CPU's filter_image of accum with guides, 83 x 47,
// `passes` passes) to be scalar_filter's image bit for bit (NaNs too:
// summed in the same order, without contraction); returns how many of its
// pixels differ from `raw`.
int pixels_the_same_as_the_kernels(const std::vector<kernel::AccumPixel>& accum,
                                   const std::vector<kernel::FilterGuide>& guides,
                                   const Image& fast, const Image& raw,
                                   int passes = T0_FILTER_PASSES) {
    const Image slow = scalar_filter(accum, 83, 47, guides, passes);
    REQUIRE(fast.pixels.size() == slow.pixels.size());
    int differ = 0;
    for (std::size_t i = 0; i < fast.pixels.size(); ++i) {
        CAPTURE(i, fast.pixels[i].x, slow.pixels[i].x);
        REQUIRE(std::memcmp(&fast.pixels[i], &slow.pixels[i], sizeof(glm::vec3)) == 0);
        differ += fast.pixels[i] != raw.pixels[i] ? 1 : 0;
    }
    return differ;
}

}  // namespace

TEST_CASE("the filter smooths noise and keeps a shadow's edge", "[filter]") {
    std::vector<kernel::AccumPixel> accum;
    std::vector<kernel::FilterGuide> guides;
    // One plane (same normal and depth): a lit half and a shadowed one.
    noisy_halves(
        1.0f, 0.1f, [](int) { return guide_of(glm::vec3(0.5f), 3.0f, glm::vec3(0, 0, -1)); },
        &accum, &guides);
    const Image raw = accumulated_image(accum, width, height);
    const Image filtered = filter_image(accum, width, height, guides, T0_FILTER_PASSES);
    // Noise: the lit half's spread at least three times smaller.
    CAPTURE(spread(raw, 0, 28), spread(filtered, 0, 28));
    CHECK(spread(filtered, 0, 28) < spread(raw, 0, 28) / 3.0);
    // The edge: a few pixels from it, each side keeps its brightness (a
    // filter without edge-stopping weights spreads it over its 125-pixel
    // footprint). The pixels right beside it may blend a little.
    const double lit = mean_luminance(filtered, 26, 30);
    const double dark = mean_luminance(filtered, 34, 38);
    CAPTURE(lit, dark, mean_luminance(filtered, 31, 32), mean_luminance(filtered, 32, 33));
    CHECK(lit > 0.9 * mean_luminance(raw, 0, 32));
    CHECK(dark < 1.5 * mean_luminance(raw, 32, 64));
    // Energy: the image mean kept within 1 %.
    const double raw_mean = mean_luminance(raw, 0, width);
    CHECK(std::fabs(mean_luminance(filtered, 0, width) / raw_mean - 1.0) < 0.01);
    // A workspace kept between calls gives the same image, every time.
    FilterWorkspace workspace;
    for (int i = 0; i < 2; ++i) {
        CHECK(filter_image(accum, width, height, guides, T0_FILTER_PASSES, workspace).pixels ==
              filtered.pixels);
    }
    // No passes: the image as it is.
    const Image none = filter_image(accum, width, height, guides, 0);
    CHECK(none.pixels == raw.pixels);
}

TEST_CASE("a workspace keeps a view's guides for the filter calls that take none", "[filter]") {
    // A plane sloping away from the camera.
    const auto sloping = [](int x) {
        return guide_of(glm::vec3(0.5f), 3.0f + 0.01f * x, glm::vec3(0, 0, -1));
    };
    std::vector<kernel::AccumPixel> accum;
    std::vector<kernel::FilterGuide> guides;
    noisy_halves(1.0f, 0.1f, sloping, &accum, &guides);
    FilterWorkspace workspace;
    CHECK_THROWS_WITH(filter_image(accum, T0_FILTER_PASSES, workspace),
                      Catch::Contains("no guides"));
    workspace.set_guides(guides, width, height);
    // The same image as the calls given the guides, for each accumulation
    // filtered with them.
    const Image full = filter_image(accum, width, height, guides, T0_FILTER_PASSES);
    for (int i = 0; i < 2; ++i) {
        CHECK(filter_image(accum, T0_FILTER_PASSES, workspace).pixels == full.pixels);
    }
    std::vector<kernel::AccumPixel> brighter;
    std::vector<kernel::FilterGuide> same;
    noisy_halves(2.0f, 0.5f, sloping, &brighter, &same);
    const Image other = filter_image(brighter, T0_FILTER_PASSES, workspace);
    CHECK(other.pixels == filter_image(brighter, width, height, guides, T0_FILTER_PASSES).pixels);
    CHECK(other.pixels != full.pixels);
    // Guides of another size are refused, and the workspace keeps its own.
    CHECK_THROWS_WITH(workspace.set_guides(guides, width + 1, height),
                      Catch::Contains("2048 guides for an image of 65 x 32"));
    CHECK(filter_image(accum, T0_FILTER_PASSES, workspace).pixels == full.pixels);
    // So is an accumulation of another size.
    const std::vector<kernel::AccumPixel> small(10, pixel_of(glm::vec3(1.0f), 0.1f, 4.0f));
    CHECK_THROWS_WITH(
        filter_image(small, T0_FILTER_PASSES, workspace),
        Catch::Contains("the accumulator has 10 pixels, the workspace's guides 2048"));
    // An empty image filters to an empty image.
    const Image none = filter_image({}, 0, 0, {}, T0_FILTER_PASSES);
    CHECK((none.width == 0 && none.height == 0 && none.pixels.empty()));
    // So does one of no columns but some rows, or the reverse.
    const Image thin = filter_image({}, 0, 5, {}, T0_FILTER_PASSES);
    CHECK((thin.width == 0 && thin.height == 5 && thin.pixels.empty()));
    const Image flat = filter_image({}, 5, 0, {}, T0_FILTER_PASSES);
    CHECK((flat.width == 5 && flat.height == 0 && flat.pixels.empty()));
}

TEST_CASE("a workspace takes a view's GuideImages as filter_guides makes them", "[filter]") {
    std::vector<kernel::FilterGuide> unused;
    const std::unique_ptr<Renderer> small = render_4spp("cornell_diffuse.json", 40, 30, &unused);
    const std::unique_ptr<Renderer> r = render_4spp("cornell.json", 83, 47, &unused);
    const GuideImages images = render_guides(r->packed(), r->camera_record());
    const Image expected =
        filter_image(r->accumulator(), 83, 47, filter_guides(images), T0_FILTER_PASSES);
    // Given another view's guides first, of another size, then this one's:
    // its buffer holds nothing of the first.
    FilterWorkspace workspace;
    workspace.set_guides(render_guides(small->packed(), small->camera_record()));
    workspace.set_guides(images);
    CHECK(filter_image(r->accumulator(), T0_FILTER_PASSES, workspace).pixels == expected.pixels);
    // Guides without the lamp-edge split are refused, as filter_guides
    // refuses them, and the workspace keeps the guides it had.
    const GuideImages surface = render_surface_guides(r->packed(), r->camera_record());
    CHECK_THROWS_WITH(workspace.set_guides(surface), Catch::Contains("lamp-edge split"));
    CHECK(filter_image(r->accumulator(), T0_FILTER_PASSES, workspace).pixels == expected.pixels);
    // So are guides whose images are not all of their size.
    GuideImages short_depth = images;
    short_depth.depth.pop_back();
    CHECK_THROWS_WITH(filter_guides(short_depth), Catch::Contains("not all 83 x 47"));
    CHECK_THROWS_WITH(workspace.set_guides(short_depth), Catch::Contains("not all 83 x 47"));
    CHECK(filter_image(r->accumulator(), T0_FILTER_PASSES, workspace).pixels == expected.pixels);
}

TEST_CASE("the filter keeps a corner: normals and depths stop it", "[filter]") {
    for (const int which : {0, 1}) {
        CAPTURE(which);
        std::vector<kernel::AccumPixel> accum;
        std::vector<kernel::FilterGuide> guides;
        // Equal brightness noise on both sides, so only the guides can
        // keep them apart: two walls meeting (normals at right angles), or
        // a near and a far surface (depths 1 and 5).
        noisy_halves(
            1.0f, 0.4f,
            [which](int x) {
                const bool left = x < width / 2;
                return which == 0
                           ? guide_of(glm::vec3(0.5f), 3.0f,
                                      left ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, -1))
                           : guide_of(glm::vec3(0.5f), left ? 1.0f : 5.0f, glm::vec3(0, 0, -1));
            },
            &accum, &guides);
        // A large per-sample variance: luminance alone would not stop it.
        for (kernel::AccumPixel& p : accum) {
            p.moments.y *= 100.0f;
        }
        const Image raw = accumulated_image(accum, width, height);
        const Image filtered = filter_image(accum, width, height, guides, T0_FILTER_PASSES);
        const double near_left = mean_luminance(filtered, 31, 32);
        const double near_right = mean_luminance(filtered, 32, 33);
        CAPTURE(near_left, near_right);
        CHECK(std::fabs(near_left / mean_luminance(raw, 0, 32) - 1.0) < 0.1);
        CHECK(std::fabs(near_right / mean_luminance(raw, 32, 64) - 1.0) < 0.1);
    }
}

TEST_CASE("the filter leaves pixels that see nothing, and divides by albedo", "[filter]") {
    std::vector<kernel::AccumPixel> accum;
    std::vector<kernel::FilterGuide> guides;
    // A textured-looking surface: albedo alternating by column, the
    // colour following it exactly (uniform light); beside a background.
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool background = x >= 48;
            const glm::vec3 albedo(x % 2 == 0 ? 0.8f : 0.2f);
            const glm::vec3 colour = background ? glm::vec3(0.3f, 0.6f, 0.9f) : albedo * 2.0f;
            accum.push_back(pixel_of(colour, 0.05f, 4.0f));
            guides.push_back(background ? guide_of(glm::vec3(0.0f), T0_NO_HIT, glm::vec3(0.0f))
                                        : guide_of(albedo, 2.0f, glm::vec3(0, 0, -1)));
        }
    }
    const Image raw = accumulated_image(accum, width, height);
    const Image filtered = filter_image(accum, width, height, guides, T0_FILTER_PASSES);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            CAPTURE(x, y);
            // The texture's detail is kept (the lighting is uniform), and
            // the background is not touched.
            REQUIRE(glm::length(filtered.at(x, y) - raw.at(x, y)) <
                    1e-5f * (1.0f + glm::length(raw.at(x, y))));
        }
    }
}

TEST_CASE("the filter keeps the lamp's part of a pixel that a lamp's edge runs through",
          "[filter]") {
    // A plane of albedo 0.5 under uniform light 1 (noisy, 4 samples), a
    // lamp of radiance 10 (kept as it is) on the right, and between them a
    // column of pixels half lamp, half plane: their 4 samples saw the lamp
    // 1 to 3 times (mean 5.25 on average, and far apart).
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    std::uniform_int_distribution<int> on_lamp(1, 3);
    std::vector<kernel::AccumPixel> accum;
    std::vector<kernel::FilterGuide> guides;
    const int edge = 40;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            kernel::FilterGuide g = guide_of(glm::vec3(0.5f), 2.0f, glm::vec3(0, 0, -1));
            const float plane = 0.5f * std::max(0.05f, 1.0f + noise(rng));
            if (x < edge) {
                accum.push_back(pixel_of(glm::vec3(plane), 0.36f * 0.25f, 4.0f));
            } else if (x == edge) {
                const float lamp = 0.25f * static_cast<float>(on_lamp(rng));
                const float v = lamp * 10.0f + (1.0f - lamp) * plane;
                accum.push_back(pixel_of(glm::vec3(v), 4.0f * 25.0f * 0.25f, 4.0f));
                g.emission = glm::vec4(glm::vec3(5.0f), 0.5f);
            } else {
                accum.push_back(pixel_of(glm::vec3(10.0f), 0.0f, 4.0f));
                g.normal.w = 1.0f;
            }
            guides.push_back(g);
        }
    }
    const Image raw = accumulated_image(accum, width, height);
    const Image filtered = filter_image(accum, width, height, guides, T0_FILTER_PASSES);
    // The edge's pixels: the lamp's half exact, the plane's half filtered.
    for (int y = 0; y < height; ++y) {
        CAPTURE(y, kernel::luminance(raw.at(edge, y)));
        CHECK(std::fabs(kernel::luminance(filtered.at(edge, y)) - 5.25f) < 0.1f);
    }
    // No lamp light leaks into the plane beside the edge, and the plane
    // is smoothed.
    const double beside = mean_luminance(filtered, edge - 3, edge);
    CAPTURE(beside);
    CHECK(std::fabs(beside - 0.5) < 0.025);
    CHECK(spread(filtered, 0, edge - 3) < spread(raw, 0, edge - 3) / 3.0);
    // The lamp itself is kept.
    CHECK(filtered.at(edge + 1, 5) == raw.at(edge + 1, 5));
}

TEST_CASE("the filter keeps a rendered image's mean", "[filter]") {
    // Diffuse walls, and the thesis' box with its glass and glossy objects.
    for (const char* name : {"cornell_diffuse.json", "cornell.json"}) {
        CAPTURE(name);
        std::vector<kernel::FilterGuide> guides;
        const std::unique_ptr<Renderer> rendered = render_4spp(name, 80, 60, &guides);
        Renderer& r = *rendered;
        const Image raw = r.image();
        const Image filtered = filter_image(r.accumulator(), 80, 60, guides, T0_FILTER_PASSES);
        for (const glm::vec3& p : filtered.pixels) {
            REQUIRE((std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)));
        }
        const double raw_mean = mean_luminance(raw, 0, 80);
        CAPTURE(raw_mean, mean_luminance(filtered, 0, 80));
        CHECK(std::fabs(mean_luminance(filtered, 0, 80) / raw_mean - 1.0) < 0.01);
        CHECK(spread(filtered, 10, 70) < spread(raw, 10, 70));
    }
}

TEST_CASE("the CPU's vectorized passes equal the kernel's per-pixel filter", "[filter]") {
    // The thesis' box (glass, glossy, the lamp's edge) at a width whose
    // rows have inner pixels for the vector loop and a remainder.
    std::vector<kernel::FilterGuide> guides;
    const std::unique_ptr<Renderer> rendered = render_4spp("cornell.json", 83, 47, &guides);
    Renderer& r = *rendered;
    // Two pixels whose sums are not finite (NaN, infinite), as a damaged
    // accumulation could have: each is a tap of weight zero.
    std::vector<kernel::AccumPixel> accum = r.accumulator();
    const std::size_t bad[2] = {83 * 20 + 40, 83 * 30 + 10};
    accum[bad[0]].sum.x = std::nanf("");
    accum[bad[1]].sum = glm::vec4(std::numeric_limits<float>::infinity());
    const Image fast = filter_image(accum, 83, 47, guides, T0_FILTER_PASSES);
    // The filter did something, so the comparison means something.
    CHECK(pixels_the_same_as_the_kernels(accum, guides, fast, r.image()) > 83 * 47 / 2);
    // The bad pixels spoil no neighbour.
    for (const std::size_t i : bad) {
        for (const std::size_t q : {i - 1, i + 1, i - 83, i + 83}) {
            CAPTURE(i, q);
            CHECK(std::isfinite(fast.pixels[q].x + fast.pixels[q].y + fast.pixels[q].z));
        }
    }
}

TEST_CASE("the CPU's passes copy the pixels beside a row's that the filter keeps", "[filter]") {
    // Pixels that see nothing are kept as they are; where they begin or end
    // a row, the CPU copies them instead of filtering. cornell_diffuse.json:
    // its box against a black background, some rows all background;
    // sky_demo.json: objects against a sky, whose pixels are not black.
    // One workspace for both, as the window keeps one from view to view.
    FilterWorkspace kept;
    for (const char* name : {"cornell_diffuse.json", "sky_demo.json"}) {
        CAPTURE(name);
        std::vector<kernel::FilterGuide> guides;
        const std::unique_ptr<Renderer> rendered = render_4spp(name, 83, 47, &guides);
        const std::vector<kernel::AccumPixel>& accum = rendered->accumulator();
        int nothing = 0;
        for (const kernel::FilterGuide& g : guides) {
            nothing += g.albedo.w < T0_NO_HIT ? 0 : 1;
        }
        CAPTURE(nothing);
        REQUIRE(nothing > 83 * 47 / 10);
        // An odd count too: the passes alternate between two buffers, and
        // each must hold the copied pixels.
        for (const int passes : {T0_FILTER_PASSES, 3}) {
            CAPTURE(passes);
            const Image fast = filter_image(accum, 83, 47, guides, passes);
            CHECK(pixels_the_same_as_the_kernels(accum, guides, fast, rendered->image(), passes) >
                  83 * 47 / 4);
        }
        // Through the kept workspace, the scene before's guides replaced,
        // for two accumulations of this view: the pixels kept are each
        // call's own, in both buffers, whatever the buffers held before
        // (an odd count ends in the second buffer).
        kept.set_guides(guides, 83, 47);
        for (int frame = 0; frame < 2; ++frame) {
            CAPTURE(frame);
            for (const int passes : {T0_FILTER_PASSES, 3}) {
                CAPTURE(passes);
                CHECK(filter_image(rendered->accumulator(), passes, kept).pixels ==
                      filter_image(rendered->accumulator(), 83, 47, guides, passes).pixels);
            }
            rendered->render_frame();
        }
    }
}

TEST_CASE("the filter is the same on OpenCL", "[filter][opencl]") {
    std::vector<kernel::FilterGuide> guides;
    const std::unique_ptr<Renderer> rendered = render_4spp("cornell.json", 64, 48, &guides);
    Renderer& r = *rendered;
    const Image cpu = filter_image(r.accumulator(), 64, 48, guides, T0_FILTER_PASSES);
    const Image gpu = opencl_filter_image(0, r.accumulator(), 64, 48, guides, T0_FILTER_PASSES);
    // exp and sqrt may differ by a few ulp between the compilers.
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
        CAPTURE(i);
        REQUIRE(glm::length(cpu.pixels[i] - gpu.pixels[i]) <=
                1e-4f * (1e-3f + glm::length(cpu.pixels[i])));
    }
}

TEST_CASE("--filter writes the filtered image and the raw one beside it", "[filter][cli]") {
    const std::string scene = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell_diffuse.json";
    const std::string common = scene + " --headless --width 80 --height 60 --spp 4 ";
    const trac0r_test::ViewerRun filtered =
        trac0r_test::run_viewer_process(common + "--filter --verbose -o cli_filter.pfm");
    INFO(filtered.err);
    REQUIRE(filtered.exit_code == 0);
    CHECK(filtered.err.find("filter: on") != std::string::npos);
    CHECK(filtered.err.find("wrote cli_filter.raw.pfm") != std::string::npos);
    const trac0r_test::ViewerRun plain =
        trac0r_test::run_viewer_process(common + "-o cli_plain.pfm");
    REQUIRE(plain.exit_code == 0);
    // The raw image is the render without --filter, bit for bit; the
    // filtered one differs and keeps its mean.
    const Image raw = read_pfm("cli_filter.raw.pfm");
    CHECK(read_pfm("cli_plain.pfm").pixels == raw.pixels);
    const Image f = read_pfm("cli_filter.pfm");
    CHECK(f.pixels != raw.pixels);
    CHECK(std::fabs(mean_luminance(f, 0, 80) / mean_luminance(raw, 0, 80) - 1.0) < 0.01);
    // The window filters what it shows, not its --output.
    const trac0r_test::ViewerRun window =
        trac0r_test::run_viewer_process("--filter -o cli_filter.pfm");
    CHECK(window.exit_code == 2);
    CHECK(window.err.find("filtered --output images only with --headless") != std::string::npos);
    for (const char* f : {"cli_filter.pfm", "cli_filter.raw.pfm", "cli_plain.pfm"}) {
        std::remove(f);
    }
}
