// The interactive window, driven by --replay scripts of key and mouse
// events on a virtual X server. CTest runs this file under xvfb-run
// (tests/CMakeLists.txt); without a display these tests fail.
#include <catch2/catch.hpp>

#include "viewer_process.h"

#include "trac0r/fly_camera.h"
#include "trac0r/image_io.h"
#include "trac0r/scene_loader.h"

#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

using trac0r_test::read_text_file;
using trac0r_test::run_viewer_process;
using trac0r_test::ViewerRun;

namespace trac0r_test {
void check_benchmark_json(const std::string& out, long frames, int width, int height,
                          const std::string& backend);
}

namespace {

const std::string cornell = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell.json";

// A fresh directory for one test's screenshots.
std::string empty_directory(const std::string& name) {
    REQUIRE(std::system(("rm -rf " + name).c_str()) == 0);
    REQUIRE(mkdir(name.c_str(), 0755) == 0);
    return name;
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    REQUIRE(out.good());
}

struct Screenshot {
    std::string png;
    std::string pfm;
    long spp;
};

// The "screenshot: A.png and A.pfm (N spp)" lines, in the order taken.
std::vector<Screenshot> screenshots_said(const std::string& err) {
    std::vector<Screenshot> shots;
    const std::regex line("screenshot: (\\S+\\.png) and (\\S+\\.pfm) \\((\\d+) spp");
    for (std::sregex_iterator i(err.begin(), err.end(), line), end; i != end; ++i) {
        shots.push_back({(*i)[1].str(), (*i)[2].str(), std::stol((*i)[3].str())});
    }
    return shots;
}

// The window on `args` (which pause it at --spp 4), in `dir`: the PNG of
// the screenshot taken once the 4 spp are there.
trac0r::Rgb8Image first_screenshot_png(const std::string& dir, const std::string& args) {
    write_file(dir + "/first.txt", "wait_spp 4\nkey P\nkey Escape\n");
    const ViewerRun r = run_viewer_process(args + " --replay first.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 1);
    return trac0r::read_png(shots[0].png);
}

// Pixels of exactly the overlay's AABB colour (255, 255, 0).
long yellow_pixels(const trac0r::Rgb8Image& image) {
    long count = 0;
    for (std::size_t i = 0; i + 2 < image.bytes.size(); i += 3) {
        count += image.bytes[i] == 255 && image.bytes[i + 1] == 255 && image.bytes[i + 2] == 0;
    }
    return count;
}

double mean_abs_difference(const trac0r::Image& a, const trac0r::Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    double total = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
        total += d.x + d.y + d.z;
    }
    return total / a.pixels.size();
}

bool same_pixels(const trac0r::Image& a, const trac0r::Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels == b.pixels;
}

}  // namespace

TEST_CASE(
    "scripted input: movement restarts accumulation and changes the image, F1 draws "
    "the AABBs, P saves screenshots, Esc exits 0",
    "[window]") {
    const std::string dir = empty_directory("window_session");
    // --spp 4: the window pauses at 4 samples per pixel, so every screenshot
    // below is of exactly 4 spp of its view.
    write_file(dir + "/script.txt", R"(# test_window.cpp
wait_spp 4
key P            # 1: the scene's camera
wheel 2          # zoom in two notches: the field of view times 0.9^2
wait_spp 4
key P            # 2: zoomed
key_down W       # fly forward for a moment
wait 300
key_up W
wait_spp 4
key P            # 3: moved
key F1           # the debug overlay (after the screenshot: the window keeps the order)
mouse_move 40 30
wait 100
key P            # 4: with the overlay
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 200 --height 150 --spp 4 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);  // Esc quits cleanly
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 4);

    std::vector<trac0r::Rgb8Image> png;
    std::vector<trac0r::Image> pfm;
    for (const Screenshot& s : shots) {
        INFO(s.png);
        CHECK(s.spp == 4);
        CHECK(s.png.find("/" + dir + "/trac0r-") != std::string::npos);  // where it runs
        png.push_back(trac0r::read_png(s.png));
        pfm.push_back(trac0r::read_pfm(s.pfm));
        CHECK(png.back().width == 200);  // the window shows the render 1:1
        CHECK(png.back().height == 150);
        CHECK(pfm.back().width == 200);
        CHECK(pfm.back().height == 150);
    }

    // The zoom restarted accumulation: the 4 spp shown are exactly those of
    // a fresh render from the zoomed camera (same seed, frames 0 to 3); had
    // the old view's samples stayed in the mean, the images would differ.
    trac0r::Camera zoomed = trac0r::load_scene_file(cornell).camera;
    zoomed = trac0r::zoom_camera(zoomed, std::pow(0.9f, 2.0f));
    nlohmann::json scene = nlohmann::json::parse(read_text_file(cornell));
    scene["camera"]["vertical_fov"] = static_cast<double>(zoomed.vertical_fov);
    write_file(dir + "/zoomed.json", scene.dump());
    const ViewerRun fresh = run_viewer_process(
        "zoomed.json --headless --width 200 --height 150 --spp 4 --output fresh.pfm",
        "cd " + dir + " &&");
    INFO(fresh.err);
    REQUIRE(fresh.exit_code == 0);
    const trac0r::Image fresh_image = trac0r::read_pfm(dir + "/fresh.pfm");
    CHECK(same_pixels(pfm[1], fresh_image));

    // Zooming and flying changed the image, by far more than noise: at 4
    // spp two renders of one view differ by much less than a view change.
    CHECK(mean_abs_difference(pfm[0], pfm[1]) > 0.01);
    CHECK(mean_abs_difference(pfm[1], pfm[2]) > 0.01);
    CHECK(png[0].bytes != png[1].bytes);
    CHECK(png[1].bytes != png[2].bytes);
    // The overlay adds nothing to the render, only to the window.
    CHECK(same_pixels(pfm[2], pfm[3]));

    // F1: yellow AABB wireframes; never that exact colour without them.
    CHECK(yellow_pixels(png[0]) == 0);
    CHECK(yellow_pixels(png[2]) == 0);
    CHECK(yellow_pixels(png[3]) > 100);
}

// How grainy an image is: the mean difference of horizontal neighbours
// over the mean level, both as sums of R, G and B.
double roughness(const trac0r::Image& image) {
    double steps = 0.0;
    double level = 0.0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x + 1 < image.width; ++x) {
            const glm::vec3 a = image.at(x, y);
            const glm::vec3 d = glm::abs(image.at(x + 1, y) - a);
            steps += d.x + d.y + d.z;
            level += a.x + a.y + a.z;
        }
    }
    return steps / level;
}

TEST_CASE("while the camera moves, the window shows the history reprojected, not one sample",
          "[window]") {
    const std::string dir = empty_directory("window_temporal");
    write_file(dir + "/script.txt", R"(wait_spp 16
key_down D
wait 400
key P            # while moving: a preview, blended with what came before
key_up D
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 200 --height 150 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    REQUIRE(r.err.find("low-resolution preview") != std::string::npos);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 1);
    const trac0r::Image moving = trac0r::read_pfm(shots[0].pfm);
    REQUIRE(moving.width == 100);  // the preview: half of 200 x 150
    // One sample a pixel of the scene's view at the preview's size: what
    // the window showed while moving before temporal reuse.
    const ViewerRun one = run_viewer_process(
        "--headless --width 100 --height 75 --spp 1 --output one.pfm", "cd " + dir + " &&");
    REQUIRE(one.exit_code == 0);
    const trac0r::Image single = trac0r::read_pfm(dir + "/one.pfm");
    CAPTURE(roughness(moving), roughness(single));
    // The history holds about 16 samples a pixel: a quarter of one
    // sample's grain; a restart would show all of it.
    CHECK(roughness(moving) < 0.5 * roughness(single));
    // The same room, as bright: no flash to black.
    double moving_sum = 0.0;
    double single_sum = 0.0;
    for (std::size_t i = 0; i < moving.pixels.size(); ++i) {
        moving_sum += moving.pixels[i].x + moving.pixels[i].y + moving.pixels[i].z;
        single_sum += single.pixels[i].x + single.pixels[i].y + single.pixels[i].z;
    }
    CHECK(moving_sum > 0.7 * single_sum);
}

TEST_CASE("a pause shows the accumulation itself, without what the moves left", "[window]") {
    const std::string dir = empty_directory("window_pause_after_move");
    // --spp 8 pauses within the 64 frames that blend in the moves' history.
    write_file(dir + "/script.txt", R"(wait_spp 4
key_down D
wait 300
key_up D
wait_spp 8
key P
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 160 --height 120 --spp 8 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 1);
    CHECK(shots[0].spp == 8);
    // The window (PNG) shows exactly the running mean (PFM), tone-mapped.
    const trac0r::Rgb8Image shown = trac0r::read_png(shots[0].png);
    const trac0r::Rgb8Image mean = trac0r::tonemap_image(trac0r::read_pfm(shots[0].pfm), 1.0f);
    CHECK(shown.width == mean.width);
    CHECK(shown.bytes == mean.bytes);
}

TEST_CASE("right-drag looks around, the wheel zooms, R restarts, B says what it did", "[window]") {
    const std::string dir = empty_directory("window_look");
    write_file(dir + "/script.txt", R"(wait_spp 3
key P
mouse_move 60 45
mouse_down right
mouse_move 80 45   # drag 20 pixels to the right: turn right
mouse_up right
wait_spp 3
key P
key R
wait_spp 3
key P
key B            # to OpenCL (PoCL), or a message why not
wait 200
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 120 --height 90 --spp 3 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 3);
    const trac0r::Image before = trac0r::read_pfm(shots[0].pfm);
    const trac0r::Image turned = trac0r::read_pfm(shots[1].pfm);
    const trac0r::Image restarted = trac0r::read_pfm(shots[2].pfm);
    CHECK(mean_abs_difference(before, turned) > 0.01);
    // R restarts the same view: the same seed gives the same 3 spp.
    CHECK(same_pixels(turned, restarted));
    CHECK(r.err.find("accumulation restarted") != std::string::npos);
    CHECK(r.err.find("switching to the opencl backend") != std::string::npos);
}

TEST_CASE("after B the window renders what --backend opencl renders, integrator and all",
          "[window]") {
    // Before, the renderer made on a switch had the library's default
    // integrator (naive), not the command line's: its 3 spp were another
    // image than the batch render's.
    const std::string dir = empty_directory("window_switch");
    write_file(dir + "/script.txt", R"(wait_spp 3
key B            # to OpenCL (PoCL): accumulation starts again there
wait 1000
wait_spp 3
key P
key Escape
)");
    const std::string view = cornell + " --width 64 --height 48 --spp 3";
    const ViewerRun r = run_viewer_process(view + " --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    REQUIRE(r.err.find("backend: opencl") != std::string::npos);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 1);
    const ViewerRun batch = run_viewer_process(
        view + " --headless --backend opencl --output batch.pfm", "cd " + dir + " &&");
    REQUIRE(batch.exit_code == 0);
    const trac0r::Image window = trac0r::read_pfm(shots[0].pfm);
    const trac0r::Image headless = trac0r::read_pfm(dir + "/batch.pfm");
    INFO("mean |difference| " << mean_abs_difference(window, headless));
    CHECK(same_pixels(window, headless));
}

TEST_CASE("while W is held the window shows low-resolution previews of the moving view",
          "[window]") {
    // Before, a new camera came in during every preview (one a tick of the
    // event loop) and each was thrown away: the old view stayed on screen
    // until the key was released.
    const std::string dir = empty_directory("window_moving");
    write_file(dir + "/script.txt", R"(wait_spp 1
key_down W
wait 2000
key P            # while moving
key_up W
wait_spp 1
key P            # stopped: full resolution again
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 640 --height 480 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 2);
    const trac0r::Image moving = trac0r::read_pfm(shots[0].pfm);
    const trac0r::Image stopped = trac0r::read_pfm(shots[1].pfm);
    CHECK(r.err.find("spp, low-resolution preview)") != std::string::npos);
    CHECK(moving.width == 160);  // a quarter of 640
    CHECK(shots[0].spp == 1);
    CHECK(stopped.width == 640);
}

TEST_CASE("while the right button drags the view the window shows previews, between motions too",
          "[window]") {
    // Before, a full-resolution frame started in every gap between the
    // drag's motion events, and was shown until the next one: at this size
    // within 120 ms of a motion. The drag holds for 250 ms (drag_hold_ms).
    const std::string dir = empty_directory("window_drag");
    write_file(dir + "/script.txt", R"(wait_spp 1
mouse_move 160 120
mouse_down right
mouse_move 170 120
wait 60
mouse_move 180 120
wait 60
mouse_move 190 120
wait 120
key P            # a gap in the drag, shorter than its hold: still moving
wait 1000
key P            # the pointer has stopped, the button still held: full size
mouse_up right
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 320 --height 240 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 2);
    CHECK(trac0r::read_pfm(shots[0].pfm).width == 80);  // the preview: a quarter of 320
    CHECK(trac0r::read_pfm(shots[1].pfm).width == 320);
}

TEST_CASE("a resized window renders at its new size, from a fresh accumulation", "[window]") {
    // Before, the render kept its size and was scaled to the window.
    const std::string dir = empty_directory("window_resize");
    write_file(dir + "/script.txt", R"(wait_spp 2
key P
resize 320 180   # wider: the same vertical field of view, more at the sides
wait_spp 2
key P
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 200 --height 150 --spp 2 --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("rendering at 320 x 180") != std::string::npos);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 2);
    CHECK(trac0r::read_pfm(shots[0].pfm).width == 200);
    const trac0r::Image resized = trac0r::read_pfm(shots[1].pfm);
    const trac0r::Rgb8Image window = trac0r::read_png(shots[1].png);
    CHECK(resized.width == 320);
    CHECK(resized.height == 180);
    CHECK(window.width == 320);  // one render pixel a window pixel
    CHECK(window.height == 180);
    // The samples of a render at that size from the start: none of the old
    // size's are in it.
    const ViewerRun batch = run_viewer_process(
        cornell + " --headless --width 320 --height 180 --spp 2 --output batch.pfm",
        "cd " + dir + " &&");
    REQUIRE(batch.exit_code == 0);
    CHECK(same_pixels(resized, trac0r::read_pfm(dir + "/batch.pfm")));
}

TEST_CASE("F filters what the window shows, never the accumulation", "[window]") {
    const std::string dir = empty_directory("window_filter");
    write_file(dir + "/script.txt", R"(wait_spp 4
key P            # 1: unfiltered
key F
wait_spp 4       # the frame the filter request reflects
key P            # 2: filtered
key F
wait_spp 4
key P            # 3: off again
key Escape
)");
    const std::string view = cornell + " --width 200 --height 150 --spp 4";
    const ViewerRun r = run_viewer_process(view + " --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("filter on") != std::string::npos);
    CHECK(r.err.find("filter off") != std::string::npos);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 3);
    std::vector<trac0r::Rgb8Image> png;
    std::vector<trac0r::Image> pfm;
    for (const Screenshot& s : shots) {
        png.push_back(trac0r::read_png(s.png));
        pfm.push_back(trac0r::read_pfm(s.pfm));
        CHECK(s.spp == 4);
    }
    // The accumulation (the PFM) is the same 4 spp throughout.
    CHECK(same_pixels(pfm[0], pfm[1]));
    CHECK(same_pixels(pfm[0], pfm[2]));
    CHECK(png[0].bytes != png[1].bytes);
    CHECK(png[0].bytes == png[2].bytes);
    // What is shown is the batch render's filtered image.
    const ViewerRun batch =
        run_viewer_process(view + " --headless --filter --output batch.png", "cd " + dir + " &&");
    REQUIRE(batch.exit_code == 0);
    CHECK(trac0r::read_png(dir + "/batch.png").bytes == png[1].bytes);

    // --filter starts the window with it on.
    CHECK(first_screenshot_png(dir, view + " --filter").bytes == png[1].bytes);
}

TEST_CASE("V switches the view to filmic and back; the accumulation stays as it was", "[window]") {
    const std::string dir = empty_directory("window_view");
    write_file(dir + "/script.txt", R"(wait_spp 4
key P            # 1: standard
key V
key P            # 2: filmic
key V
key P            # 3: standard again
key Escape
)");
    // Exposure 4: much of the box above 1, where the views differ.
    const std::string view = cornell + " --width 200 --height 150 --spp 4 --exposure 4";
    const ViewerRun r = run_viewer_process(view + " --replay script.txt", "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("view filmic") != std::string::npos);
    CHECK(r.err.find("view standard") != std::string::npos);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 3);
    std::vector<trac0r::Rgb8Image> png;
    for (const Screenshot& s : shots) {
        png.push_back(trac0r::read_png(s.png));
        CHECK(same_pixels(trac0r::read_pfm(s.pfm), trac0r::read_pfm(shots[0].pfm)));
    }
    CHECK(png[0].bytes != png[1].bytes);
    CHECK(png[0].bytes == png[2].bytes);
    // What is shown is the batch render's PNG in that view.
    for (const char* v : {"standard", "filmic"}) {
        const ViewerRun batch = run_viewer_process(
            view + " --headless --view " + v + " --output batch.png", "cd " + dir + " &&");
        REQUIRE(batch.exit_code == 0);
        CHECK(trac0r::read_png(dir + "/batch.png").bytes == png[v[0] == 'f' ? 1 : 0].bytes);
    }
    // --view filmic starts the window with it.
    CHECK(first_screenshot_png(dir, view + " --view filmic").bytes == png[1].bytes);
}

TEST_CASE("--target-error pauses the window once the estimate reaches it", "[window]") {
    // Before, the window accepted --target-error and went on forever.
    const std::string dir = empty_directory("window_target");
    write_file(dir + "/script.txt", R"(wait 4000
key P
wait 1500
key P            # 1.5 s later: the same spp when paused
key Escape
)");
    const ViewerRun r = run_viewer_process(
        cornell + " --width 64 --height 48 --target-error 0.2 --replay script.txt",
        "cd " + dir + " &&");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::vector<Screenshot> shots = screenshots_said(r.err);
    REQUIRE(shots.size() == 2);
    CHECK(shots[0].spp >= 8);
    CHECK(shots[1].spp == shots[0].spp);
}

TEST_CASE("--benchmark in the window prints its JSON line and exits 0", "[window]") {
    const ViewerRun r = run_viewer_process("--benchmark 3 --width 64 --height 48");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    trac0r_test::check_benchmark_json(r.out, 3, 64, 48, "cpu");
}

TEST_CASE("a bad --replay file is one message naming the line, before any window", "[window]") {
    write_file("bad_replay.txt", "wait 10\nkey NoSuchKey\n");
    const ViewerRun r = run_viewer_process("--replay bad_replay.txt");
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("bad_replay.txt:2: expected an SDL key name") != std::string::npos);
    CHECK(r.err.find("got 'NoSuchKey'") != std::string::npos);  // the argument, not the line
    CHECK(r.err.find('\n') == r.err.size() - 1);                // one line
    const ViewerRun missing = run_viewer_process("--replay no_such_replay.txt");
    CHECK(missing.exit_code == 1);
    CHECK(missing.err.find("no_such_replay.txt") != std::string::npos);
    const ViewerRun headless = run_viewer_process(
        "--replay bad_replay.txt --headless "
        "--output x.png");
    CHECK(headless.exit_code == 2);
    CHECK(headless.err.find("--replay") != std::string::npos);
}

// Issue 33, point 4: a script that cannot end is an error, not a window
// that stays open for ever (before, each of these hung until killed).
TEST_CASE("a replay that cannot finish stops with a message naming the line", "[window]") {
    // The window pauses at --spp 4: a wait for 8 is refused before it opens.
    write_file("unreachable.txt", "wait_spp 2\nwait_spp 8\nkey Escape\n");
    const ViewerRun spp =
        run_viewer_process("--width 32 --height 24 --spp 4 --replay unreachable.txt");
    CHECK(spp.exit_code == 1);
    CHECK(spp.err ==
          "trac0r_viewer: error: unreachable.txt:2: wait_spp 8 cannot be reached: the "
          "window stops at 4 spp (--spp)\n");

    // A held W moves the view every frame: it never reaches full resolution.
    write_file("held.txt", "wait_timeout 1\nkey_down W\nwait_spp 1\nkey Escape\n");
    const ViewerRun held = run_viewer_process("--width 32 --height 24 --replay held.txt", "", 60);
    CHECK(held.exit_code == 1);
    CHECK(held.err.find("held.txt:3: wait_spp 1 not reached in 1 s (wait_timeout)") !=
          std::string::npos);
    CHECK(held.err.find("keys held down: W") != std::string::npos);

    // 70,000 events overflowed SDL's queue (65,535), which dropped the
    // final Escape; fed in batches, every one arrives.
    std::string many;
    for (int i = 0; i < 70000; ++i) {
        many += "mouse_move " + std::to_string(i % 32) + " " + std::to_string(i % 24) + "\n";
    }
    write_file("many.txt", many + "key Escape\n");
    const ViewerRun flood = run_viewer_process("--width 32 --height 24 --replay many.txt", "", 60);
    INFO(flood.err);
    CHECK(flood.exit_code == 0);
}

// Issue 33, point 7: a NUL cut the message (and SDL read "W\0..." as W,
// so the script ran on); a binary file is now refused with its bytes shown.
TEST_CASE("a binary replay file is refused, its bytes shown escaped", "[window]") {
    write_file("binary_replay.txt", std::string("wait 10\nkey W\0\x01zz\n", 17));
    const ViewerRun r = run_viewer_process("--replay binary_replay.txt", "", 30);
    CHECK(r.exit_code == 1);
    CHECK(r.err ==
          "trac0r_viewer: error: binary_replay.txt:2: expected a line of text (a binary "
          "file?), got 'key W\\x00\\x01zz'\n");
}

// Issue 33, point 2: SIGINT or SIGTERM closes the window as Escape does
// (SDL turns them into a quit event): the --output image is saved, exit 0.
TEST_CASE("SIGINT and SIGTERM close the window as Escape does", "[window]") {
    for (const char* signal : {"INT", "TERM"}) {
        INFO(signal);
        const std::string pfm = std::string("window_") + signal + ".pfm";
        std::remove(pfm.c_str());
        const ViewerRun r = trac0r_test::run_process(
            "timeout --preserve-status -s " + std::string(signal) + " 2 " + TRAC0R_VIEWER,
            "--width 32 --height 24 --output " + pfm);
        INFO(r.err);
        CHECK(r.exit_code == 0);
        CHECK(r.err.find("wrote " + pfm) != std::string::npos);
        CHECK(trac0r::read_pfm(pfm).width == 32);
    }
}

TEST_CASE("C prints the camera; --camera loads it; the same view renders", "[window][camera]") {
    const std::string dir = empty_directory("window_camera");
    // Move and turn, print the camera (C), and take a screenshot of the
    // new view; Home goes back to the scene's camera, printed too.
    write_file(dir + "/moved.txt", R"(wait_spp 2
key_down W
wait 120
key_up W
mouse_move 60 45
mouse_down right
mouse_move 75 40
mouse_up right
wait_spp 3
key C
key P
key Home
key C
key Escape
)");
    const ViewerRun moved = run_viewer_process(
        cornell + " --width 120 --height 90 --spp 3 --replay moved.txt", "cd " + dir + " &&");
    INFO(moved.err);
    REQUIRE(moved.exit_code == 0);
    // Two blocks on stdout, one a line: the moved view, then the scene's.
    const std::size_t newline = moved.out.find('\n');
    REQUIRE(newline != std::string::npos);
    const std::string block = moved.out.substr(0, newline);
    const std::string home = moved.out.substr(newline + 1);
    const nlohmann::json parsed = nlohmann::json::parse(block);
    REQUIRE(parsed.at("camera").at("position").size() == 3);
    const trac0r::Scene scene = trac0r::load_scene_file(cornell);
    const trac0r::Camera back = trac0r::parse_camera_block(home, "home", scene.origin);
    CHECK(back.position == scene.camera.position);
    CHECK(back.direction == scene.camera.direction);
    const trac0r::Camera there = trac0r::parse_camera_block(block, "moved", scene.origin);
    CHECK(glm::length(there.position - scene.camera.position) > 0.01f);

    // The printed block, loaded with --camera: the same camera printed
    // back, and the same 3 spp, bit for bit.
    write_file(dir + "/camera.json", block + "\n");
    write_file(dir + "/again.txt", "wait_spp 3\nkey C\nkey P\nkey Escape\n");
    const ViewerRun again = run_viewer_process(
        cornell + " --width 120 --height 90 --spp 3 --camera camera.json --replay again.txt",
        "cd " + dir + " &&");
    INFO(again.err);
    REQUIRE(again.exit_code == 0);
    CHECK(again.out == block + "\n");
    const std::vector<Screenshot> a = screenshots_said(moved.err);
    const std::vector<Screenshot> b = screenshots_said(again.err);
    REQUIRE(a.size() == 1);
    REQUIRE(b.size() == 1);
    CHECK(a[0].spp == 3);
    CHECK(b[0].spp == 3);
    CHECK(same_pixels(trac0r::read_pfm(a[0].pfm), trac0r::read_pfm(b[0].pfm)));
}
