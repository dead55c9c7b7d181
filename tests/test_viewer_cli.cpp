// The trac0r_viewer program as a user runs it: headless renders, files it
// writes, and the messages and exit codes of bad command lines.
#include <catch2/catch.hpp>

#include "viewer_process.h"

#include "trac0r/image_io.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Run {
    int exit_code;
    std::string output;  // stdout and stderr together
};

Run run_viewer(const std::string& args) {
    const std::string command = std::string(TRAC0R_VIEWER) + " " + args + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string output;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) {
        output += buffer;
    }
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

const std::string cornell = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell.json";

}  // namespace

TEST_CASE("a headless render of cornell.json is deterministic and finite", "[cli]") {
    const std::string args = cornell + " --headless --width 80 --height 60 --spp 4 --seed 5 ";
    const Run a = run_viewer(args + "--output cli_a.pfm");
    const Run b = run_viewer(args + "--output cli_b.pfm");
    INFO(a.output);
    REQUIRE(a.exit_code == 0);
    REQUIRE(b.exit_code == 0);
    REQUIRE(a.output.find("wrote cli_a.pfm") != std::string::npos);
    const std::string bytes = read_bytes("cli_a.pfm");
    REQUIRE(bytes.size() > 80 * 60 * 12);
    REQUIRE(bytes == read_bytes("cli_b.pfm"));

    const trac0r::Image image = trac0r::read_pfm("cli_a.pfm");
    REQUIRE(image.width == 80);
    REQUIRE(image.height == 60);
    double total = 0.0;
    for (const glm::vec3& p : image.pixels) {
        REQUIRE(std::isfinite(p.x + p.y + p.z));
        total += p.x + p.y + p.z;
    }
    REQUIRE(total > 0.0);  // the lamp lights the box
}

TEST_CASE("a PNG and a PFM are written for the built-in scene", "[cli]") {
    const Run r =
        run_viewer("--headless --width 40 --height 30 --spp 2 --output cli.png --output cli.pfm");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const std::string png = read_bytes("cli.png");
    REQUIRE(png.size() > 8);
    REQUIRE(png.compare(1, 3, "PNG") == 0);
    REQUIRE(trac0r::read_pfm("cli.pfm").width == 40);
}

// The number after `key` in the first line of `text` that has it.
double number_after(const std::string& text, const std::string& key) {
    const std::size_t at = text.find(key);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + key.size()));
}

TEST_CASE("--target-error stops at the requested estimated noise", "[cli]") {
    const std::string diffuse = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell_diffuse.json";
    const std::string args = diffuse + " --headless --width 32 --height 24 --output cli_t.pfm";
    // Targets well below the first check's estimate (8 spp: about 0.08
    // with the default integrator, next-event estimation).
    const Run loose = run_viewer(args + " --target-error 0.02");
    INFO(loose.output);
    REQUIRE(loose.exit_code == 0);
    REQUIRE(loose.output.find("target error reached") != std::string::npos);
    REQUIRE(number_after(loose.output, "estimated relative MSE ") <= 0.02);
    // Relative MSE falls as 1 / spp: a 4 times smaller target takes about
    // 4 times the samples (the stop is checked every 10% of samples).
    const Run tight = run_viewer(args + " --target-error 0.005");
    INFO(tight.output);
    REQUIRE(tight.exit_code == 0);
    REQUIRE(number_after(tight.output, "estimated relative MSE ") <= 0.005);
    const double spp_loose = number_after(loose.output, "after ");
    const double spp_tight = number_after(tight.output, "after ");
    CHECK(spp_tight / spp_loose > 3.0);
    CHECK(spp_tight / spp_loose < 5.5);
    REQUIRE(trac0r::read_pfm("cli_t.pfm").width == 32);

    // A time limit that comes first says so, and still saves the image.
    const Run capped = run_viewer(args + " --target-error 1e-6 --spp 16");
    INFO(capped.output);
    REQUIRE(capped.exit_code == 0);
    REQUIRE(capped.output.find("target error NOT reached") != std::string::npos);
    REQUIRE(capped.output.find("after") == std::string::npos);
    REQUIRE(capped.output.find("wrote cli_t.pfm") != std::string::npos);
}

TEST_CASE("an output that is a directory is refused before the render", "[cli]") {
    const std::string dir = "cli_dir.png";
    std::remove(dir.c_str());
    REQUIRE(system(("mkdir -p " + dir).c_str()) == 0);
    const Run r = run_viewer("--headless --width 8 --height 6 --spp 1 --output " + dir);
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output == "trac0r_viewer: --output cli_dir.png: cannot be written (is a directory)\n");
    REQUIRE(system(("rmdir " + dir).c_str()) == 0);
}

TEST_CASE("a time limit shorter than one frame still renders one sample", "[cli]") {
    const Run r =
        run_viewer("--headless --width 16 --height 12 --seconds 1e-30 --output cli_s.pfm");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    REQUIRE(r.output.find("rendered 1 spp") != std::string::npos);
    const trac0r::Image image = trac0r::read_pfm("cli_s.pfm");
    float largest = 0.0f;
    for (const auto& p : image.pixels) {
        largest = std::max(largest, std::max(p.x, std::max(p.y, p.z)));
    }
    CHECK(largest > 0.0f);  // the built-in scene's lamp, at least
}

TEST_CASE("--target-error on a scene whose noise estimate overflows stops with a message",
          "[cli]") {
    // Radiance 1e25 (the loader allows up to 1e30): squared deviations of
    // 1e50 overflow the float moments, and the estimate can never fall.
    const std::string scene = "cli_bright.json";
    std::ofstream(scene) << R"({"camera": {"position": [0, 0, 0], "direction": [0, 0, 1]},
        "materials": {"l": {"type": "emissive", "color": [1, 1, 1], "emittance": 1e25},
                      "w": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
        "shapes": [{"type": "box", "size": [4, 4, 4], "material": "w"},
                   {"type": "box", "size": [0.3, 0.3, 0.3], "position": [0.5, 0.5, 1.5],
                    "material": "l"}]})";
    const Run r = run_viewer(scene +
                             " --headless --width 16 --height 12 --target-error 0.01 "
                             "--output cli_bright.pfm");
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find("--target-error cannot be reached: the noise estimate has overflowed") !=
          std::string::npos);
    CHECK(r.output.find("wrote cli_bright.pfm") != std::string::npos);
    // With --spp (or --seconds) the render is bounded: it runs to the limit
    // and says the estimate overflowed.
    const Run bounded = run_viewer(scene +
                                   " --headless --width 16 --height 12 --target-error 0.01 "
                                   "--spp 20 --output cli_bright.pfm");
    INFO(bounded.output);
    CHECK(bounded.exit_code == 0);
    CHECK(bounded.output.find("rendered 20 spp") != std::string::npos);
    CHECK(bounded.output.find("target error NOT reached") != std::string::npos);
    CHECK(bounded.output.find("the noise estimate has overflowed float") != std::string::npos);
}

TEST_CASE("a scene with nothing that emits renders, with a warning", "[cli]") {
    const std::string scene = "cli_dark.json";
    std::ofstream(scene) << R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
        "shapes": [{"type": "plane", "size": [1, 1], "material": "white"}]})";
    const Run r = run_viewer(scene + " --headless --width 8 --height 6 --spp 1 --output cli_d.png");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(r.output.find("warning: nothing emits light") != std::string::npos);
    // An emissive material of colour 0 emits nothing either.
    const std::string black_lamp = "cli_black_lamp.json";
    std::ofstream(black_lamp) << R"({"materials": {"lamp": {"type": "emissive", "color": [0, 0, 0],
        "emittance": 15}}, "shapes": [{"type": "plane", "size": [1, 1], "material": "lamp"}]})";
    const Run black =
        run_viewer(black_lamp + " --headless --width 8 --height 6 --spp 1 --output cli_d.png");
    CHECK(black.exit_code == 0);
    CHECK(black.output.find("warning: nothing emits light") != std::string::npos);
    const Run lit = run_viewer("--headless --width 8 --height 6 --spp 1 --output cli_d.png");
    CHECK(lit.exit_code == 0);
    CHECK(lit.output.find("warning") == std::string::npos);
    // A sky lights a scene; a black one does not.
    for (const char* sky : {"[0.5, 0.6, 1]", "[0, 0, 0]"}) {
        const std::string outdoor = "cli_sky.json";
        std::ofstream(outdoor) << R"({"materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
            "shapes": [{"type": "plane", "size": [1, 1], "material": "white"}],
            "environment": {"color": )" << sky << "}}";
        const Run run =
            run_viewer(outdoor + " --headless --width 8 --height 6 --spp 1 --output cli_d.png");
        INFO(run.output);
        CHECK(run.exit_code == 0);
        CHECK((run.output.find("warning: nothing emits light") != std::string::npos) ==
              (std::string(sky) == "[0, 0, 0]"));
    }
}

TEST_CASE("what the checks let through: any case of .png, exponents as %g writes them", "[cli]") {
    std::remove("cli_up.PNG");
    const Run r = run_viewer(
        "--headless --width 8 --height 6 --spp 1 --seconds 1e+1 --exposure 2 --output cli_up.PNG");
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK(read_bytes("cli_up.PNG").compare(1, 3, "PNG") == 0);
}

TEST_CASE("--flag=value and -o FILE are the same as --flag value and --output FILE", "[cli]") {
    const Run a = run_viewer("--headless --width=16 --height=12 --spp=2 -o cli_eq_a.pfm");
    INFO(a.output);
    REQUIRE(a.exit_code == 0);
    const Run b = run_viewer("--headless --width 16 --height 12 --spp 2 --output=cli_eq_b.pfm");
    INFO(b.output);
    REQUIRE(b.exit_code == 0);
    CHECK(trac0r_test::read_text_file("cli_eq_a.pfm") ==
          trac0r_test::read_text_file("cli_eq_b.pfm"));
    CHECK(!trac0r_test::read_text_file("cli_eq_a.pfm").empty());
    std::remove("cli_eq_a.pfm");
    std::remove("cli_eq_b.pfm");
}

TEST_CASE("--help lists the options and exits 0", "[cli]") {
    const Run r = run_viewer("--help");
    REQUIRE(r.exit_code == 0);
    REQUIRE(r.output.find("--headless") != std::string::npos);
    REQUIRE(r.output.find("--spp") != std::string::npos);
}

TEST_CASE("--help is generated from the options: every group, the keys, examples", "[cli]") {
    for (const char* flag : {"--help", "-h"}) {
        CAPTURE(flag);
        const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(flag);
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK(r.out.find("Usage: trac0r_viewer [SCENE.json] [options]\n") == 0);
        // Each group's name, then one of its options, in that order.
        std::size_t at = 0;
        for (const char* part :
             {"Arguments:\n", "SCENE.json", "Rendering:\n", "--backend cpu|opencl", "--spp N",
              "--sampler random|sobol", "Output:\n", "-o, --output FILE", "--headless",
              "--max-input-mb N", "Other:\n", "-h, --help", "--version", "Window keys and mouse:\n",
              "Esc", "Examples:\n"}) {
            CAPTURE(part);
            at = r.out.find(part, at);
            CHECK(at != std::string::npos);
        }
        // Refilled to 80 columns.
        std::istringstream lines(r.out);
        for (std::string line; std::getline(lines, line);) {
            CAPTURE(line);
            CHECK(line.size() <= 80);
        }
        // No option is missing from it.
        for (const char* option :
             {"--device", "--list-devices", "--width", "--height", "--seconds", "--seed",
              "--max-depth", "--threads", "--accel", "--integrator", "--target-error", "--exposure",
              "--view", "--verbose", "--exr-layers", "--benchmark", "--replay"}) {
            CHECK(r.out.find(std::string("  ") + option + " ") != std::string::npos);
        }
    }
}

TEST_CASE("--verbose names each mesh: file, triangles, bounds, material", "[cli]") {
    const Run r = run_viewer(std::string(TRAC0R_SOURCE_DIR) +
                             "/scenes/mesh_demo.json --headless --width 16 --height 12 --spp 1 "
                             "--verbose --output cli_verbose.png");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(r.output.find("scene: ") != std::string::npos);
    CHECK(r.output.find("backend: cpu") != std::string::npos);
    // scenes/meshes/tetrahedron.obj, scaled and placed by mesh_demo.json.
    CHECK(r.output.find("mesh " + std::string(TRAC0R_SOURCE_DIR) +
                        "/scenes/meshes/tetrahedron.obj: 4 triangles, bounds (-0.271402, -0.09, "
                        "-0.271402) to (0.271402, 0.31, 0.271402), material metal, 0 smooth\n") !=
          std::string::npos);
    std::remove("cli_verbose.png");
}

TEST_CASE("--version says the version and exits 0", "[cli]") {
    const Run r = run_viewer("--version");
    REQUIRE(r.exit_code == 0);
    CHECK(r.output.find("trac0r_viewer trac0r " + std::string(TRAC0R_PROJECT_VERSION)) == 0);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    // With other options too; a bad one is still refused.
    CHECK(run_viewer("--width 8 --version").exit_code == 0);
    CHECK(run_viewer("--version=1").exit_code == 2);
}

TEST_CASE("bad command lines give one clear message and a non-zero exit", "[cli]") {
    struct Case {
        std::string args;
        std::string expected;  // part of the message
        int exit_code = 2;     // 2: the command line; 1: anything else (README, "Running a scene")
    };
    const Case cases[] = {
        {"--headless --spp abc --output x.png", "--spp: expected an integer"},
        {"--headless --spp 0 --output x.png", "--spp: expected an integer in [1"},
        // A pixel's sample count is a float, exact to 2^24 (Renderer::max_frames).
        {"--headless --spp 16777217 --output x.png",
         "--spp: expected an integer in [1, 16777216], got '16777217'"},
        {"--frobnicate", "--frobnicate: unknown option"},
        {"--headless --output x.jpg", "expected a .png, .pfm or .exr"},
        {"--headless", "give --output FILE"},
        {"--headless --seconds -1 --output x.png", "--seconds: expected a positive number"},
        {"--headless --target-error 0 --output x.png", "--target-error: expected a positive"},
        {"--headless --accel kd --output x.png", "--accel: expected one of flat|bvh|auto"},
        {"--headless --width", "--width: expected a value"},
        {"--headless --output --spp", "--output: expected a value after it, got the option --spp"},
        {"--headless --benchmark 3 --spp 8", "--benchmark: renders exactly N frames"},
        {"--replay .", "--replay .: cannot read replay script: it is a directory", 1},
        {"no_such_scene.json --headless --output x.png", "no_such_scene.json", 1},
        // Checked before the render, which would otherwise be lost.
        {"--headless --output no_such_dir/x.png",
         "--output no_such_dir/x.png: cannot be written (directory no_such_dir does not exist)"},
        {"--headless --output . --output x.pfm", "--output .: expected a .png, .pfm or .exr"},
        {"--headless --width 32 --width 16 --output x.png", "--width: given more than once"},
        {"--headless --seconds 0x10 --output x.png", "--seconds: expected a positive number"},
        {"--headless --spp +3 --output x.png", "--spp: expected an integer"},
        {"--headless --spp ' 3' --output x.png", "--spp: expected an integer"},
        {"--headless --output x.pfm --exposure 4", "--exposure: scales the tone mapping of PNG"},
        {"--headless --view agx --output x.png", "--view: expected one of standard|filmic"},
        {"--headless --output x.pfm --output x.exr --view filmic",
         "--view: sets how PNG outputs (and the window) show the render, never .pfm or .exr"},
        {"--list-devices --output x.png", "--list-devices: lists the OpenCL devices and exits"},
        {"--headless=yes --output x.png", "--headless: takes no value, got 'yes'"},
        {"--headless --spp= --output x.png", "--spp: expected a value after '='"},
        {"--headless --spp=abc --output x.png", "--spp: expected an integer"},
        {"--headless --spp=2 --spp 3 --output x.png", "--spp: given more than once"},
        {"--headless -o x.jpg", "expected a .png, .pfm or .exr"},
        {"--headless -o", "--output: expected a value"},
        {"--headless --frobnicate=3 --output x.png", "--frobnicate: unknown option"},
        {"a.json b.json --headless", "'b.json': only one scene file may be given"},
        {"--headless --headless --output x.png", "--headless: given more than once"},
        {"--headless --seed -1 --output x.png", "--seed: expected a non-negative 64-bit"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const Run r = run_viewer(c.args);
        CAPTURE(r.output);
        REQUIRE(r.exit_code == c.exit_code);
        REQUIRE(r.output.find(c.expected) != std::string::npos);
        // One message: a single line, no progress bar, no crash.
        REQUIRE(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    }
}

// No SDL_VIDEODRIVER: a user's shell has none, and "dummy" or "offscreen"
// would open an invisible window instead of saying there is no display.
TEST_CASE("without a display: one message pointing to --headless, exit 1, no crash", "[cli]") {
    using trac0r_test::run_viewer_process;
    const std::string no_display = "env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER";
    const trac0r_test::ViewerRun runs[] = {
        run_viewer_process(cornell + " --width 32 --height 24", no_display),
        run_viewer_process("--benchmark 3 --width 32 --height 24", no_display),
        // A display that is set but not there (no X server on :64999).
        run_viewer_process("--width 32 --height 24",
                           "env -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER DISPLAY=:64999"),
        // A Wayland display that is not there: libwayland printed its own
        // error line before SDL gave up.
        run_viewer_process("--width 32 --height 24",
                           "env -u DISPLAY -u SDL_VIDEODRIVER -u XDG_RUNTIME_DIR "
                           "WAYLAND_DISPLAY=wayland-64999"),
        run_viewer_process("--width 32 --height 24",
                           "env -u DISPLAY -u SDL_VIDEODRIVER XDG_RUNTIME_DIR=/tmp "
                           "WAYLAND_DISPLAY=wayland-64999"),
    };
    for (const trac0r_test::ViewerRun& r : runs) {
        CAPTURE(r.err);
        CHECK(r.exit_code == 1);
        CHECK((r.err.find("no display") != std::string::npos ||
               r.err.find("cannot open a window on DISPLAY=:64999") != std::string::npos));
        CHECK(r.err.find("use --headless") != std::string::npos);
        CHECK(r.err.find('\n') == r.err.size() - 1);  // one line
        CHECK(r.out.empty());
    }
}

TEST_CASE("a mesh file that crashes assimp's reader is a message and exit 1", "[cli]") {
    // tests/fuzz/findings/assimp_gltf_segv.glb made assimp 5.2's glTF
    // reader dereference null: the viewer died of SIGSEGV with it.
    const std::string finding =
        std::string(TRAC0R_SOURCE_DIR) + "/tests/fuzz/findings/assimp_gltf_segv.glb";
    const std::string scene = "assimp_segv_scene.json";
    {
        std::ofstream out(scene);
        out << R"({"materials": {"white": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
                   "lamp": {"type": "emissive", "color": [1, 1, 1], "emittance": 5}},
                   "shapes": [{"type": "plane", "size": [1, 1], "material": "lamp"},
                              {"type": "mesh", "file": ")"
            << finding << R"(", "material": "white"}]})";
    }
    const Run run = run_viewer(scene + " --headless --width 8 --height 6 --spp 1 --output x.png");
    std::remove(scene.c_str());
    CHECK(run.exit_code == 1);
    CHECK(run.output == "trac0r_viewer: " + scene + ": /shapes/1/file: " + finding +
                            ": the glTF reader (assimp) crashed on this file (SIGSEGV): it is "
                            "malformed\n");
}
