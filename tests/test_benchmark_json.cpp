// --benchmark N prints one JSON line with every figure it promises, with
// values that agree with each other and with the command line.
#include <catch2/catch.hpp>

#include "viewer_process.h"

#include <nlohmann/json.hpp>

#include <string>

using trac0r_test::run_viewer_process;
using trac0r_test::ViewerRun;

namespace trac0r_test {

// Shared with test_window.cpp, which checks the window's benchmark.
void check_benchmark_json(const std::string& out, long frames, int width, int height,
                          const std::string& backend) {
    INFO(out);
    // One line: a JSON object and a newline, nothing else on stdout.
    REQUIRE(!out.empty());
    REQUIRE(out.back() == '\n');
    REQUIRE(out.find('\n') == out.size() - 1);
    const nlohmann::json j = nlohmann::json::parse(out);  // throws (fails) when invalid
    REQUIRE(j.is_object());
    for (const char* key : {"frames", "mean_fps", "median_fps", "min_fps", "ms_per_frame",
                            "paths_per_second", "width", "height", "triangles"}) {
        INFO(key);
        REQUIRE(j.contains(key));
        REQUIRE(j[key].is_number());
        REQUIRE(j[key].get<double>() > 0.0);
    }
    for (const char* key : {"backend", "device"}) {
        INFO(key);
        REQUIRE(j.contains(key));
        REQUIRE(j[key].is_string());
        REQUIRE(!j[key].get<std::string>().empty());
    }
    REQUIRE(j.size() == 11);  // no figure without a test
    CHECK(j["frames"].get<long>() == frames);
    CHECK(j["width"].get<int>() == width);
    CHECK(j["height"].get<int>() == height);
    CHECK(j["triangles"].get<long>() == 676);  // the built-in Cornell box
    CHECK(j["backend"].get<std::string>() == backend);
    // Consistent figures; 1e-3 relative: they are printed to 6 digits.
    const double mean_fps = j["mean_fps"].get<double>();
    CHECK(j["min_fps"].get<double>() <= j["median_fps"].get<double>() * (1 + 1e-3));
    CHECK(j["min_fps"].get<double>() <= mean_fps * (1 + 1e-3));
    CHECK(j["ms_per_frame"].get<double>() == Approx(1e3 / mean_fps).epsilon(1e-3));
    CHECK(j["paths_per_second"].get<double>() == Approx(mean_fps * width * height).epsilon(1e-3));
}

}  // namespace trac0r_test

TEST_CASE("--headless --benchmark prints one JSON line with all its figures", "[benchmark]") {
    const ViewerRun r = run_viewer_process("--headless --benchmark 3 --width 40 --height 30");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    trac0r_test::check_benchmark_json(r.out, 3, 40, 30, "cpu");
}

TEST_CASE("--benchmark --output saves the last frame", "[benchmark]") {
    std::remove("bench_last.pfm");
    const ViewerRun r = run_viewer_process(
        "--headless --benchmark 2 --width 24 --height 16 --output bench_last.pfm");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    trac0r_test::check_benchmark_json(r.out, 2, 24, 16, "cpu");
    const std::string pfm = trac0r_test::read_text_file("bench_last.pfm");
    REQUIRE(pfm.compare(0, 2, "PF") == 0);
    REQUIRE(pfm.size() > 24 * 16 * 12);
}

TEST_CASE("--benchmark 0 and a bad count are command-line errors", "[benchmark]") {
    for (const char* count : {"0", "-3", "ten"}) {
        const ViewerRun r = run_viewer_process(std::string("--headless --benchmark ") + count);
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("--benchmark") != std::string::npos);
        CHECK(r.out.empty());
    }
}
