// SIGINT and SIGTERM during a headless render (issue 33, point 2): the
// frame in flight finishes, what has accumulated is written, the exit
// status is 130 or 143; a second signal ends the program at once. Before,
// an interrupt exited with nothing written. (The window closes on them as
// on Escape: test_window.cpp.)
#include "trac0r/image_io.h"
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

namespace {

// The viewer, sent `signal` after `seconds` by GNU timeout, whose exit
// status is then the viewer's (--preserve-status).
trac0r_test::ViewerRun interrupted_after(const char* signal, double seconds,
                                         const std::string& args) {
    return trac0r_test::run_process("timeout --preserve-status -s " + std::string(signal) + " " +
                                        std::to_string(seconds) + " " + TRAC0R_VIEWER,
                                    args);
}

long spp_said(const std::string& err) {
    const std::size_t at = err.find(" after ");
    return at == std::string::npos ? -1 : std::stol(err.substr(at + 7));
}

}  // namespace

TEST_CASE("an interrupted headless render writes what it has and exits 128 + signal",
          "[interrupt]") {
    const std::string args = "--headless --spp 10000000 --width 40 --height 30 --output ";
    for (const auto& c : {std::make_pair("INT", 130), std::make_pair("TERM", 143)}) {
        INFO(c.first);
        const std::string pfm = std::string("interrupt_") + c.first + ".pfm";
        std::remove(pfm.c_str());
        const trac0r_test::ViewerRun r = interrupted_after(c.first, 1.5, args + pfm);
        INFO(r.err);
        CHECK(r.exit_code == c.second);
        CHECK(r.err.find(std::string("interrupted by SIG") + c.first + " after ") !=
              std::string::npos);
        CHECK(r.err.find("wrote " + pfm) != std::string::npos);
        const long spp = spp_said(r.err);
        CHECK(spp >= 1);
        CHECK(spp < 10000000);
        REQUIRE(trac0r::read_pfm(pfm).width == 40);
    }
}

TEST_CASE("a second signal ends the render at once, writing nothing", "[interrupt]") {
    std::remove("interrupt_twice.pfm");
    // One thread, 3200 x 2400: a frame takes seconds, so the second TERM,
    // half a second after the first, comes while the first frame renders.
    const trac0r_test::ViewerRun r = trac0r_test::run_process(
        "sh", "-c '" + std::string(TRAC0R_VIEWER) +
                  " --headless --threads 1 --spp 1000 --width 3200 --height 2400 --output "
                  "interrupt_twice.pfm & p=$!; sleep 0.5; kill -TERM $p; sleep 0.5; "
                  "kill -TERM $p; wait $p'");
    INFO(r.err);
    CHECK(r.exit_code == 143);  // the shell's status for a death by SIGTERM
    CHECK(r.err.find("wrote") == std::string::npos);
    CHECK(std::fopen("interrupt_twice.pfm", "rb") == nullptr);
}
