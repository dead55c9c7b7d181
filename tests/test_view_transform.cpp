// The view transform (trac0r/view_transform.h): `standard` is the clamp
// PNGs always had, `filmic` (AgX) maps 0 to 0, never falls as radiance
// rises, and takes bright colours to white instead of clipping them; the
// scene key render.view and --view choose it, and linear outputs (PFM,
// EXR) never see it.
#include <catch2/catch.hpp>

#include "viewer_process.h"

#include "trac0r/image_io.h"
#include "trac0r/scene_loader.h"
#include "trac0r/view_transform.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

using trac0r::ViewTransform;

namespace {

glm::vec3 filmic(const glm::vec3& radiance) {
    return trac0r::apply_view(ViewTransform::filmic, radiance);
}

// The PNG tone mapping of every version before the view transform
// (image_io.cpp before it): exposure, clamp to [0, 1], sRGB curve.
std::uint8_t clamp_tonemap(float linear, float exposure) {
    float v = linear * exposure;
    if (!(v > 0.0f)) {
        return 0;
    }
    v = std::min(v, 1.0f);
    const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(srgb * 255.0f));
}

// Radiances from 1e-6 to 1e4, each 1 % above the one before: some 2300
// steps over 33 stops, 70 a stop.
std::vector<float> ramp() {
    std::vector<float> k;
    for (double v = 1e-6; v <= 1e4; v *= 1.01) {
        k.push_back(static_cast<float>(v));
    }
    return k;
}

const std::string cornell = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell.json";

}  // namespace

TEST_CASE("filmic maps 0 to 0, and black stays black at any exposure", "[view_transform]") {
    CHECK(filmic(glm::vec3(0.0f)) == glm::vec3(0.0f));
    // Negative and NaN channels count as 0, as the standard view's do.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(filmic(glm::vec3(-1.0f, nan, -0.0f)) == glm::vec3(0.0f));
    trac0r::Image black;
    black.width = 4;
    black.height = 2;
    black.pixels.assign(8, glm::vec3(0.0f));
    for (float exposure : {1.0f, 64.0f}) {
        const trac0r::Rgb8Image png = trac0r::tonemap_image(black, exposure, ViewTransform::filmic);
        CHECK(
            std::all_of(png.bytes.begin(), png.bytes.end(), [](std::uint8_t b) { return b == 0; }));
    }
}

TEST_CASE("filmic never falls along a grey ramp from 0 to 1e4, and stays grey",
          "[view_transform]") {
    glm::vec3 previous = filmic(glm::vec3(0.0f));
    for (float k : ramp()) {
        CAPTURE(k);
        const glm::vec3 out = filmic(glm::vec3(k));
        for (int c = 0; c < 3; ++c) {
            CAPTURE(c);
            REQUIRE(out[c] >= previous[c]);
            REQUIRE(out[c] <= 1.0f);
        }
        // Grey to within the rounding of the published matrices (their
        // rows sum to 1 within 1e-4).
        CHECK(std::fabs(out.x - out.y) < 2e-4f);
        CHECK(std::fabs(out.y - out.z) < 2e-4f);
        previous = out;
    }
    // It rises through the range, middle grey in the lower half, and tends
    // to white.
    CHECK(filmic(glm::vec3(0.01f)).y > 0.0f);
    CHECK(filmic(glm::vec3(0.18f)).y > filmic(glm::vec3(0.01f)).y);
    CHECK(filmic(glm::vec3(0.18f)).y < 0.5f);
    CHECK(filmic(glm::vec3(1.0f)).y > filmic(glm::vec3(0.18f)).y);
    CHECK(filmic(glm::vec3(1e4f)).y > 0.99f);
    // A channel clamped at 1 shows as 255: the white the PNG shows.
    CHECK(trac0r::encode_srgb8(filmic(glm::vec3(1e4f)).y) == 255);
}

TEST_CASE("filmic: each channel rises with k along k times a colour", "[view_transform]") {
    // Primaries, secondaries, and the Cornell box's walls and lamp.
    const glm::vec3 colours[] = {{1, 0, 0},
                                 {0, 1, 0},
                                 {0, 0, 1},
                                 {1, 0, 1},
                                 {0, 1, 1},
                                 {1, 1, 0},
                                 {0.8f, 0.5f, 0.3f},
                                 {0.63f, 0.065f, 0.05f},
                                 {0.14f, 0.45f, 0.091f},
                                 {1, 0.93f, 0.85f}};
    // Where AgX's outset matrix subtracts a little of a channel's
    // neighbours, a channel can dip where it does not show: by less than
    // 1e-6 in the toe (the smallest 8-bit step is 3e-4 there), or from
    // above the curve's white (about 0.997: the sigmoid tops out at 0.99858)
    // down to it, as the other channels catch up. What is shown, the 8-bit
    // sRGB value, never falls.
    const glm::vec3 white = filmic(glm::vec3(1e6f));
    for (const glm::vec3& colour : colours) {
        CAPTURE(colour.x, colour.y, colour.z);
        glm::vec3 previous = filmic(glm::vec3(0.0f));
        std::uint8_t previous_bytes[3] = {0, 0, 0};
        for (float k : ramp()) {
            CAPTURE(k);
            const glm::vec3 out = filmic(k * colour);
            for (int c = 0; c < 3; ++c) {
                CAPTURE(c, out[c], previous[c]);
                REQUIRE(std::min(out[c], white[c]) >= std::min(previous[c], white[c]) - 1e-6f);
                REQUIRE(out[c] <= 1.0f);
                const std::uint8_t byte = trac0r::encode_srgb8(out[c]);
                REQUIRE(byte >= previous_bytes[c]);
                previous_bytes[c] = byte;
            }
            previous = out;
        }
    }
}

TEST_CASE("filmic takes a bright saturated colour to white, never to a pure primary",
          "[view_transform]") {
    const glm::vec3 red(1.0f, 0.0f, 0.0f);
    // The standard view clips it to pure red at any brightness.
    CHECK(trac0r::apply_view(ViewTransform::standard, 1000.0f * red) == red);
    // Filmic: its green and blue rise with its brightness...
    const glm::vec3 dim = filmic(0.5f * red);
    const glm::vec3 bright = filmic(20.0f * red);
    const glm::vec3 blinding = filmic(1000.0f * red);
    CHECK(dim.x > dim.y);
    CHECK(bright.y > dim.y);
    CHECK(bright.z > dim.z);
    CHECK(blinding.y > bright.y);
    CHECK(blinding.z > bright.z);
    // ...until it is white: no channel stays at 0.
    CHECK(glm::all(glm::greaterThan(blinding, glm::vec3(0.99f))));
    CHECK(bright.x <= 1.0f);
    // Even at 1x it is no pure primary: red light is shown a little less
    // saturated than the clamp shows it.
    CHECK(filmic(red).y > 0.0f);
}

TEST_CASE("standard is the clamp PNGs always had, bit for bit", "[view_transform]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    CHECK(trac0r::apply_view(ViewTransform::standard, glm::vec3(-1.0f, 0.5f, 7.0f)) ==
          glm::vec3(0.0f, 0.5f, 1.0f));
    const glm::vec3 odd = trac0r::apply_view(ViewTransform::standard, glm::vec3(nan, inf, 0.0f));
    CHECK(odd == glm::vec3(0.0f, 1.0f, 0.0f));
    // Every value on a fine ramp, and the odd ones, at three exposures: the
    // same bytes as before the view transform, and tonemap_channel's.
    std::vector<float> values = {-1.0f, 0.0f, nan, inf, 0.0031308f, 0.5f, 1.0f, 2.0f};
    for (float v = 0.0f; v < 1.5f; v += 1.0f / 4096.0f) {
        values.push_back(v);
    }
    trac0r::Image image;
    image.width = static_cast<int>(values.size());
    image.height = 1;
    for (float v : values) {
        image.pixels.push_back(glm::vec3(v, 0.5f * v, 2.0f * v));
    }
    for (float exposure : {1.0f, 0.25f, 3.0f}) {
        CAPTURE(exposure);
        const trac0r::Rgb8Image png = trac0r::tonemap_image(image, exposure);
        CHECK(png.bytes == trac0r::tonemap_image(image, exposure, ViewTransform::standard).bytes);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                const float v = image.pixels[i][c];
                CAPTURE(v, c);
                REQUIRE(png.bytes[3 * i + c] == clamp_tonemap(v, exposure));
                REQUIRE(trac0r::tonemap_channel(v, exposure) == clamp_tonemap(v, exposure));
            }
        }
    }
    CHECK(trac0r::tonemap_channel(0.5f, 1.0f) == 188);
    CHECK(trac0r::tonemap_channel(1.0f, 1.0f) == 255);
}

TEST_CASE("view names: standard and filmic, anything else refused by name", "[view_transform]") {
    CHECK(trac0r::parse_view_transform("standard") == ViewTransform::standard);
    CHECK(trac0r::parse_view_transform("filmic") == ViewTransform::filmic);
    CHECK(std::string(trac0r::to_string(ViewTransform::filmic)) == "filmic");
    CHECK(trac0r::view_transform_names() == std::vector<std::string>{"standard", "filmic"});
    CHECK_THROWS_WITH(trac0r::parse_view_transform("agx"),
                      "unknown view transform 'agx' (expected standard or filmic)");
}

TEST_CASE("render.view in a scene file: standard by default, filmic, or one clear message",
          "[view_transform]") {
    const std::string head = R"({"materials": {"w": {"type": "diffuse", "color": [1, 1, 1]}},
        "shapes": [{"type": "plane", "size": [1, 1], "material": "w"}])";
    const auto parse = [&](const std::string& render) {
        return trac0r::parse_scene(head + render + "}", "test.json", "");
    };
    CHECK(parse("").render.view == ViewTransform::standard);
    CHECK(parse(R"(, "render": {"view": "filmic"})").render.view == ViewTransform::filmic);
    CHECK(parse(R"(, "render": {"view": "standard"})").render.view == ViewTransform::standard);
    for (const char* bad : {R"("AgX")", "1", "null"}) {
        CAPTURE(bad);
        CHECK_THROWS_WITH(
            parse(std::string(R"(, "render": {"view": )") + bad + "}"),
            Catch::StartsWith("test.json: /render/view: expected one of \"standard\", \"filmic\""));
    }
}

TEST_CASE("--view filmic changes the PNG and leaves PFM and EXR files bit for bit",
          "[view_transform]") {
    using trac0r_test::read_text_file;
    using trac0r_test::run_viewer_process;
    // Exposure 4: the lamp, the ceiling and the walls' brightest parts
    // above 1, where the two views differ most.
    const std::string base = cornell + " --headless --width 48 --height 36 --spp 4 --exposure 4";
    // Plain, and with the filter (a filtered and a raw file of each kind)
    // and every EXR layer.
    for (const std::string extra : {"", " --filter --exr-layers all"}) {
        CAPTURE(extra);
        const std::string outputs = " -o view_a.png -o view_a.pfm -o view_a.exr";
        const trac0r_test::ViewerRun standard = run_viewer_process(base + extra + outputs);
        INFO(standard.err);
        REQUIRE(standard.exit_code == 0);
        const trac0r_test::ViewerRun filmic = run_viewer_process(
            base + extra + " --view filmic" + " -o view_b.png -o view_b.pfm -o view_b.exr");
        INFO(filmic.err);
        REQUIRE(filmic.exit_code == 0);
        std::vector<std::string> suffixes = {".pfm", ".exr"};
        if (!extra.empty()) {
            suffixes.push_back(".raw.pfm");
            suffixes.push_back(".raw.exr");
        }
        for (const std::string& suffix : suffixes) {
            CAPTURE(suffix);
            const std::string a = read_text_file("view_a" + suffix);
            CHECK(!a.empty());
            CHECK(a == read_text_file("view_b" + suffix));
        }
        CHECK(trac0r::read_png("view_a.png").bytes != trac0r::read_png("view_b.png").bytes);
        // The PNG is the PFM through the view: the same pixels by another road.
        const trac0r::Image pfm = trac0r::read_pfm("view_b.pfm");
        CHECK(trac0r::read_png("view_b.png").bytes ==
              trac0r::tonemap_image(pfm, 4.0f, ViewTransform::filmic).bytes);
    }
    for (const char* f : {"view_a", "view_b"}) {
        for (const char* s : {".png", ".pfm", ".exr", ".raw.png", ".raw.pfm", ".raw.exr"}) {
            std::remove((std::string(f) + s).c_str());
        }
    }
}

TEST_CASE("--view overrides the scene's render.view", "[view_transform]") {
    using trac0r_test::run_viewer_process;
    nlohmann::json scene;
    {
        std::ifstream in(cornell);
        in >> scene;
    }
    scene["render"]["view"] = "filmic";
    {
        std::ofstream out("view_scene.json");
        out << scene.dump();
    }
    const std::string args = " --headless --width 32 --height 24 --spp 2 --exposure 4 -o ";
    const auto png = [&](const std::string& scene_path, const std::string& more,
                         const std::string& name) {
        const trac0r_test::ViewerRun r = run_viewer_process(scene_path + args + name + more);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
        const trac0r::Rgb8Image image = trac0r::read_png(name);
        std::remove(name.c_str());
        return image.bytes;
    };
    const auto from_scene = png("view_scene.json", "", "view_s.png");
    CHECK(from_scene == png(cornell, " --view filmic", "view_f.png"));
    CHECK(from_scene != png(cornell, "", "view_c.png"));
    CHECK(png("view_scene.json", " --view standard", "view_s2.png") ==
          png(cornell, "", "view_c2.png"));
    std::remove("view_scene.json");
}
