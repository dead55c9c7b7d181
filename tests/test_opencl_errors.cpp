// What the OpenCL backend says when a request is too large for the device
// (issue 33, point 7): before, 16384 x 16384 on PoCL said only
// "clCreateBuffer(accumulator) failed (error -61)".
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("an accumulator larger than the device's largest buffer is named as such", "[opencl]") {
    // 16384^2 pixels of 48 bytes: 12 GiB, beyond PoCL's largest buffer on
    // any machine this project builds on (a quarter of its memory or less).
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        "--headless --backend opencl --width 16384 --height 16384 --spp 1 --output "
        "opencl_huge.pfm");
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("the accumulator of 16384 x 16384 pixels needs 12288 MiB, more than the "
                     "device's largest buffer") != std::string::npos);
    CHECK(r.err.find("try a smaller --width and --height") != std::string::npos);
}
