// --output x.exr (issue 32): linear float RGB that a third-party reader
// (the OpenEXR library itself, not the tinyexr that writes it) reads back
// as exactly the pixels of the PFM of the same render; written safely.
#include "trac0r/cpu_backend.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <Imath/half.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

// The R, G and B channels of `path` as float, read by OpenEXR.
trac0r::Image read_exr_with_openexr(const std::string& path) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    trac0r::Image image;
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    for (const char* name : {"R", "G", "B"}) {
        const Imf::Channel* channel = file.header().channels().findChannel(name);
        REQUIRE(channel != nullptr);
        CHECK(channel->type == Imf::FLOAT);
    }
    image.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
    char* base = reinterpret_cast<char*>(image.pixels.data()) -
                 (window.min.x + static_cast<std::ptrdiff_t>(window.min.y) * image.width) *
                     static_cast<std::ptrdiff_t>(sizeof(glm::vec3));
    Imf::FrameBuffer frame;
    const std::size_t x_stride = sizeof(glm::vec3);
    const std::size_t y_stride = sizeof(glm::vec3) * static_cast<std::size_t>(image.width);
    frame.insert("R", Imf::Slice(Imf::FLOAT, base, x_stride, y_stride));
    frame.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), x_stride, y_stride));
    frame.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), x_stride, y_stride));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
}

// One float channel of `path`, read by OpenEXR; empty when it has none.
std::vector<float> read_exr_channel(const std::string& path, const char* name) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    const Imf::Channel* channel = file.header().channels().findChannel(name);
    if (channel == nullptr) {
        return {};
    }
    CHECK(channel->type == Imf::FLOAT);
    std::vector<float> values(static_cast<std::size_t>(width) * height);
    char* base = reinterpret_cast<char*>(values.data()) -
                 (window.min.x + static_cast<std::ptrdiff_t>(window.min.y) * width) *
                     static_cast<std::ptrdiff_t>(sizeof(float));
    Imf::FrameBuffer frame;
    frame.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                  sizeof(float) * static_cast<std::size_t>(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return values;
}

bool same_floats(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("--exr-layers: albedo, normal, depth and variance layers as OpenEXR reads them",
          "[exr][guides]") {
    const std::string scene_path = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell.json";
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        scene_path +
        " --headless --width 61 --height 45 --spp 3 --output exr_layers.exr --output "
        "exr_layers.pfm --exr-layers albedo,normal,depth,variance");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    // The same render in this process: the guides and the variance exactly.
    trac0r::Scene scene = trac0r::load_scene_file(scene_path);
    scene.render.width = 61;
    scene.render.height = 45;
    trac0r::PackOptions pack;
    pack.integrator = trac0r::Integrator::nee;
    pack.sampler = trac0r::SamplerKind::sobol;
    trac0r::Renderer renderer(scene, std::make_unique<trac0r::CpuBackend>(), 1, pack);
    for (int i = 0; i < 3; ++i) {
        renderer.render_frame();
    }
    const trac0r::GuideImages guides =
        trac0r::render_guides(renderer.packed(), renderer.camera_record());
    const auto component = [](const std::vector<glm::vec3>& v, int c) {
        std::vector<float> out;
        for (const glm::vec3& p : v) {
            out.push_back(p[c]);
        }
        return out;
    };
    const char* const albedo[3] = {"albedo.R", "albedo.G", "albedo.B"};
    const char* const normal[3] = {"normal.X", "normal.Y", "normal.Z"};
    for (int c = 0; c < 3; ++c) {
        CHECK(same_floats(read_exr_channel("exr_layers.exr", albedo[c]),
                          component(guides.albedo, c)));
        CHECK(same_floats(read_exr_channel("exr_layers.exr", normal[c]),
                          component(guides.normal, c)));
    }
    CHECK(same_floats(read_exr_channel("exr_layers.exr", "Z"), guides.depth));
    const std::vector<float> variance = read_exr_channel("exr_layers.exr", "variance.Y");
    CHECK(same_floats(variance, trac0r::mean_variance(renderer.accumulator())));
    // The image itself as without layers: the PFM's pixels; and layers
    // that say something (the box's walls have albedo, the lamp none of
    // the noise).
    const trac0r::Image pfm = trac0r::read_pfm("exr_layers.pfm");
    CHECK(std::memcmp(read_exr_with_openexr("exr_layers.exr").pixels.data(), pfm.pixels.data(),
                      pfm.pixels.size() * sizeof(glm::vec3)) == 0);
    const std::vector<float> red = component(guides.albedo, 0);
    CHECK(*std::max_element(red.begin(), red.end()) > 0.3f);
    CHECK(*std::max_element(variance.begin(), variance.end()) > 0.0f);
    std::remove("exr_layers.exr");
    std::remove("exr_layers.pfm");
}

TEST_CASE("--exr-layers: a bad list, no .exr output, or the window is one message", "[exr][cli]") {
    const auto run = [](const std::string& args) { return trac0r_test::run_viewer_process(args); };
    trac0r_test::ViewerRun r =
        run("--headless --spp 1 --output exr_bad.exr --exr-layers albedo,colour");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--exr-layers: expected a comma-separated list of albedo, normal, depth "
                     "and variance, or all, got 'albedo,colour'") != std::string::npos);
    r = run("--headless --spp 1 --output exr_bad.pfm --exr-layers all");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--exr-layers: adds layers to .exr outputs; no --output is a .exr") !=
          std::string::npos);
    r = run("--output exr_bad.exr --exr-layers depth");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--exr-layers: only with --headless") != std::string::npos);
    CHECK(trac0r_test::read_text_file("exr_bad.exr").empty());
    CHECK(trac0r_test::read_text_file("exr_bad.pfm").empty());
}

TEST_CASE("an EXR holds the PFM's pixels, bit for bit, as OpenEXR reads it", "[exr]") {
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        std::string(TRAC0R_SOURCE_DIR) +
        "/scenes/cornell.json --headless --width 61 --height 45 --spp 3 --output exr_same.exr "
        "--output exr_same.pfm");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("wrote exr_same.exr") != std::string::npos);
    const trac0r::Image pfm = trac0r::read_pfm("exr_same.pfm");
    const trac0r::Image exr = read_exr_with_openexr("exr_same.exr");
    REQUIRE(exr.width == 61);
    REQUIRE(exr.height == 45);
    REQUIRE(exr.pixels.size() == pfm.pixels.size());
    // Not all black: a render, row 0 at the top in both.
    double sum = 0.0;
    for (const glm::vec3& p : pfm.pixels) {
        sum += p.x + p.y + p.z;
    }
    CHECK(sum > 0.0);
    CHECK(std::memcmp(exr.pixels.data(), pfm.pixels.data(),
                      pfm.pixels.size() * sizeof(glm::vec3)) == 0);
    std::remove("exr_same.exr");
    std::remove("exr_same.pfm");
}

TEST_CASE("an EXR that does not fit leaves the old file as it was", "[exr]") {
    {
        std::FILE* f = std::fopen("exr_old.exr", "wb");
        REQUIRE(f != nullptr);
        std::fputs("old image", f);
        std::fclose(f);
    }
    // A file-size limit of 8 blocks (4 KiB): far below this EXR.
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        "--headless --width 200 --height 150 --spp 1 --output exr_old.exr", "ulimit -f 8;");
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("exr_old.exr: write failed: File too large") != std::string::npos);
    CHECK(trac0r_test::read_text_file("exr_old.exr") == "old image");
    std::remove("exr_old.exr");
}

TEST_CASE("a half EXR holds each value rounded to half, beyond 65504 clamped", "[exr]") {
    trac0r::Image image;
    image.width = 4;
    image.height = 2;
    const float values[] = {0.0f,   1.0f,      0.1f,     1.0f / 3.0f, 3.14159f, 1e-5f,
                            -2.5f,  1234.567f, 65504.0f, 65519.0f,    70000.0f, 1e30f,
                            -1e30f, 0.7f,      100.25f,  0.001f,      42.0f,    -0.3f,
                            8.0f,   9.5f,      1e-8f,    2.0f,        0.5f,     0.25f};
    for (int i = 0; i < 8; ++i) {
        image.pixels.emplace_back(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    }
    std::vector<trac0r::ExrChannel> extra(1);
    extra[0].name = "Z";
    extra[0].values = {0.1f, 2.0f, 1e6f, 3.3f, 4.4f, 5.5f, 6.6f, 7.7f};
    trac0r::write_exr("exr_half.exr", image, extra, trac0r::ExrPrecision::Half);
    const auto expect = [](float v) {
        return static_cast<float>(half(std::min(std::max(v, -65504.0f), 65504.0f)));
    };
    Imf::InputFile file("exr_half.exr");
    for (const char* name : {"R", "G", "B", "Z"}) {
        const Imf::Channel* channel = file.header().channels().findChannel(name);
        REQUIRE(channel != nullptr);
        CHECK(channel->type == Imf::HALF);
    }
    std::vector<float> r(8), g(8), b(8), z(8);
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), 4, 16));
    frame.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), 4, 16));
    frame.insert("B", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(b.data()), 4, 16));
    frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), 4, 16));
    file.setFrameBuffer(frame);
    file.readPixels(0, 1);
    for (int i = 0; i < 8; ++i) {
        INFO("pixel " << i);
        CHECK(r[i] == expect(values[3 * i]));
        CHECK(g[i] == expect(values[3 * i + 1]));
        CHECK(b[i] == expect(values[3 * i + 2]));
        CHECK(z[i] == expect(extra[0].values[i]));
    }
    CHECK(b[3] == 65504.0f);  // 1e30: the largest finite half, not infinity
    CHECK(r[4] == -65504.0f);
    CHECK(z[2] == 65504.0f);
    // The float path as before: every value exact.
    trac0r::write_exr("exr_float.exr", image, extra);
    CHECK(read_exr_channel("exr_float.exr", "Z") == extra[0].values);
    const trac0r::Image back = read_exr_with_openexr("exr_float.exr");
    CHECK(std::memcmp(back.pixels.data(), image.pixels.data(),
                      image.pixels.size() * sizeof(glm::vec3)) == 0);
    std::remove("exr_half.exr");
    std::remove("exr_float.exr");
}

TEST_CASE("--exr-half writes the render's pixels as half", "[exr][cli]") {
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        "--headless --width 16 --height 12 --spp 2 --exr-half --output exr_cli_half.exr "
        "--output exr_cli_half.pfm");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const trac0r::Image pfm = trac0r::read_pfm("exr_cli_half.pfm");
    Imf::InputFile file("exr_cli_half.exr");
    REQUIRE(file.header().channels().findChannel("R") != nullptr);
    CHECK(file.header().channels().findChannel("R")->type == Imf::HALF);
    std::vector<float> red(pfm.pixels.size());
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(red.data()), sizeof(float),
                                 sizeof(float) * 16));
    file.setFrameBuffer(frame);
    file.readPixels(0, 11);
    for (std::size_t i = 0; i < red.size(); ++i) {
        INFO("pixel " << i);
        CHECK(red[i] == static_cast<float>(half(std::min(pfm.pixels[i].x, 65504.0f))));
    }
    // Without a .exr output it has nothing to do.
    const trac0r_test::ViewerRun none =
        trac0r_test::run_viewer_process("--headless --spp 1 --exr-half --output exr_cli_half.png");
    CHECK(none.exit_code == 2);
    CHECK(none.err.find("--exr-half: sets how .exr outputs are stored; no --output is a .exr") !=
          std::string::npos);
    std::remove("exr_cli_half.exr");
    std::remove("exr_cli_half.pfm");
}
