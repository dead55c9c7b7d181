// --output x.exr (issue 32): linear float RGB that a third-party reader
// (the OpenEXR library itself, not the tinyexr that writes it) reads back
// as exactly the pixels of the PFM of the same render; written safely.
#include "trac0r/image_io.h"
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cstdio>
#include <cstring>
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

}  // namespace

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
