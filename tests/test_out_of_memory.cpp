// Out of memory (issue 33, point 7): the message blames what was being
// made when memory ran out. Before, it always suggested a smaller --width,
// even when a huge mesh was loading. Memory is limited with `ulimit -v`,
// which AddressSanitizer's shadow memory cannot start under: tests/
// sanitize.sh runs every test but this file (and test_opencl) for that.
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("out of memory for the accumulator names the size and the scene", "[memory]") {
    // 16384^2 pixels need 12 GiB of accumulator: far over 1 GB.
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        "--headless --width 16384 --height 16384 --spp 1 --output oom.pfm", "ulimit -v 1000000;");
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err ==
          "trac0r_viewer: error: out of memory (the scene's 676 triangles and their "
          "tree, and 48 bytes a pixel for the accumulator: a smaller --width and "
          "--height, or a smaller mesh may help)\n");
}
