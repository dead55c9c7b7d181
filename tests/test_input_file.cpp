// Input files (trac0r/input_file.h, issue 33 point 3): only regular files
// are read, at most the size limit, and a name with a NUL byte is refused
// rather than cut there. Before, a scene or mesh path naming /dev/zero
// grew memory to many GB with no message, and a FIFO waited for a writer.
#include "trac0r/input_file.h"
#include "trac0r/scene_loader.h"
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

using Catch::Matchers::Equals;

TEST_CASE("only a regular file within the size limit is read", "[input]") {
    CHECK_THROWS_WITH(trac0r::read_input_file("/dev/zero", "scene file"),
                      Equals("/dev/zero: cannot read scene file: it is a device, FIFO or socket, "
                             "not a regular file"));
    std::remove("input_fifo");
    REQUIRE(mkfifo("input_fifo", 0600) == 0);  // no writer: open must not wait
    CHECK_THROWS_WITH(trac0r::read_input_file("input_fifo", "OBJ mesh"),
                      Equals("input_fifo: cannot read OBJ mesh: it is a device, FIFO or socket, "
                             "not a regular file"));
    std::remove("input_fifo");
    CHECK_THROWS_WITH(trac0r::read_input_file(".", "scene file"),
                      Equals(".: cannot read scene file: it is a directory"));
    CHECK_THROWS_WITH(trac0r::read_input_file(std::string("a\0b.json", 8), "scene file"),
                      Equals("a\\x00b.json: cannot read scene file: the path holds a NUL byte"));

    std::ofstream("input_small.txt") << std::string(3000, 'x');
    CHECK(trac0r::read_input_file("input_small.txt", "scene file").size() == 3000);
    const std::uint64_t saved = trac0r::input_size_limit();
    trac0r::set_input_size_limit(2000);
    CHECK_THROWS_WITH(trac0r::read_input_file("input_small.txt", "scene file"),
                      Equals("input_small.txt: cannot read scene file: it is 3000 bytes, over the "
                             "input size limit of 2000 bytes (--max-input-mb raises it)"));
    trac0r::set_input_size_limit(saved);
    std::remove("input_small.txt");
}

TEST_CASE("a scene or replay path naming a device is one message", "[input]") {
    CHECK_THROWS_AS(trac0r::load_scene_file("/dev/zero"), trac0r::SceneError);
    const trac0r_test::ViewerRun r =
        trac0r_test::run_viewer_process("/dev/zero --headless --spp 1 --output x.png", "", 30);
    CHECK(r.exit_code == 1);
    CHECK(r.err ==
          "trac0r_viewer: /dev/zero: cannot read scene file: it is a device, FIFO or "
          "socket, not a regular file\n");
    // --max-input-mb: a scene over it is refused, naming the flag.
    const std::string cornell = std::string(TRAC0R_SOURCE_DIR) + "/scenes/cornell.json";
    const trac0r_test::ViewerRun big = trac0r_test::run_viewer_process(
        cornell + " --max-input-mb 1 --headless --spp 1 --width 4 --height 3 --output x.pfm");
    CHECK(big.exit_code == 0);  // cornell.json is a few KB
    const trac0r_test::ViewerRun bad =
        trac0r_test::run_viewer_process("--max-input-mb 0 --headless --output x.pfm");
    CHECK(bad.exit_code == 2);
}

TEST_CASE("a mesh path naming a device or holding a NUL is one message", "[input]") {
    const std::string zero =
        R"({"shapes": [{"type": "mesh", "file": "/dev/zero", "material": "m"}],
            "materials": {"m": {"type": "diffuse", "color": [1, 1, 1]}}})";
    CHECK_THROWS_WITH(trac0r::parse_scene(zero, "z.json", "."),
                      Catch::Contains("/dev/zero: cannot read OBJ mesh: it is a device, FIFO or "
                                      "socket, not a regular file"));
    // Before, the name was cut at the NUL and meshes/tetrahedron.obj read.
    const std::string nul =
        R"({"shapes": [{"type": "mesh", "file": "meshes/tetrahedron.obj\u0000.bak", "material": "m"}],
            "materials": {"m": {"type": "diffuse", "color": [1, 1, 1]}}})";
    CHECK_THROWS_WITH(
        trac0r::parse_scene(nul, "n.json", std::string(TRAC0R_SOURCE_DIR) + "/scenes"),
        Catch::Contains("tetrahedron.obj\\x00.bak: cannot read OBJ mesh: the path "
                        "holds a NUL byte"));
}

// Issue 33, point 7: a UTF-16 OBJ said only that the mesh had no triangles.
// With a byte-order mark it is read as its UTF-8 (as assimp and Blender
// read it); without one it cannot be told from a binary file, and is named
// as either.
TEST_CASE("a UTF-16 OBJ with a mark loads; without one, or binary, it is named as such",
          "[input]") {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::string utf16;
    for (char c : obj) {
        utf16 += c;
        utf16 += '\0';
    }
    const std::string scene =
        R"({"shapes": [{"type": "mesh", "file": "input_utf16.obj", "material": "m"}],
            "materials": {"m": {"type": "diffuse", "color": [1, 1, 1]}}})";
    std::ofstream("input_utf16.obj", std::ios::binary) << "\xFF\xFE" + utf16;
    CHECK(trac0r::parse_scene(scene, "u.json", ".").triangle_count() == 1);
    std::ofstream("input_utf16.obj", std::ios::binary) << utf16;
    CHECK_THROWS_WITH(trac0r::parse_scene(scene, "u.json", "."),
                      Catch::Contains("input_utf16.obj:1: a NUL byte: this is no OBJ text (a "
                                      "binary file, or UTF-16: save it as UTF-8)"));
    std::remove("input_utf16.obj");
}

// Issue 33, point 3: a load of over a second says so on stderr (a huge
// mesh ran a minute in silence); --verbose says it at once, which this
// test uses rather than a file slow enough on every machine.
TEST_CASE("long steps before the render are announced, at once with --verbose", "[input]") {
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        "--verbose --headless --spp 1 --width 8 --height 6 --output slow_step.pfm");
    INFO(r.err);
    CHECK(r.exit_code == 0);
    CHECK(r.err.find("trac0r_viewer: loading the built-in scene ... 0 s\n") != std::string::npos);
    CHECK(r.err.find("trac0r_viewer: loading the built-in scene: done in ") != std::string::npos);
    CHECK(r.err.find("trac0r_viewer: packing 676 triangles and building the acceleration "
                     "structure: done in ") != std::string::npos);
    // Without --verbose a quick load says nothing.
    const trac0r_test::ViewerRun quiet = trac0r_test::run_viewer_process(
        "--headless --spp 1 --width 8 --height 6 --output slow_step.pfm");
    CHECK(quiet.err.find("loading") == std::string::npos);
}
