// What the OpenCL backend says when a request is too large for the device
// (issue 33, point 7): before, 16384 x 16384 on PoCL said only
// "clCreateBuffer(accumulator) failed (error -61)".
#include "viewer_process.h"

#include "trac0r/opencl_backend.h"

#include <catch2/catch.hpp>

#include <cstdint>
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

TEST_CASE("a scene buffer larger than the device's largest is named before upload", "[opencl]") {
    using trac0r::check_opencl_buffer_size;
    CHECK_NOTHROW(check_opencl_buffer_size("the scene's texels", 1024, 1024, "D"));
    CHECK_THROWS_AS(check_opencl_buffer_size("the scene's texels", 1025, 1024, "D"),
                    trac0r::OpenClError);
    // 2^31 texels of 4 bytes on a device that allows 2 GiB in one buffer.
    CHECK_THROWS_WITH(
        check_opencl_buffer_size("the scene's texels", std::uint64_t(8) << 30,
                                 std::uint64_t(2) << 30, "'pthread' (PoCL)"),
        "OpenCL: the scene's texels need 8192.0 MiB in one buffer, more than the 2048.0 MiB "
        "that device 'pthread' (PoCL) allows in one (CL_DEVICE_MAX_MEM_ALLOC_SIZE): use "
        "--backend cpu, or a smaller scene");
    CHECK_THROWS_WITH(check_opencl_buffer_size("the scene's lights", 100, 64, "D"),
                      "OpenCL: the scene's lights need 100 bytes in one buffer, more than the 64 "
                      "bytes that device D allows in one (CL_DEVICE_MAX_MEM_ALLOC_SIZE): use "
                      "--backend cpu, or a smaller scene");
}
