// The benchmark programs' command lines as a user meets them: --help, and
// bad input refused with one message that names the flag or argument, exit
// 2 for the command line and 1 for other failures, before any timing starts.
// Every run here but one stops at its check (seconds); none checks a time.
#include <catch2/catch.hpp>

#include "viewer_process.h"

#include "trac0r/image_io.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using trac0r_test::ViewerRun;

namespace {

ViewerRun run_benchmark(const std::string& program, const std::string& args,
                        const std::string& prefix = "") {
    return trac0r_test::run_process(std::string(TRAC0R_BENCHMARKS_DIR) + "/" + program, args,
                                    prefix, 60);
}

struct Case {
    std::string args;
    std::string expected;  // part of the message
};

// Each case exits `code` with one line on stderr that holds its expected
// text, and prints nothing on stdout (no table header before the error).
void check_refused(const std::string& program, const std::vector<Case>& cases, int code) {
    for (const Case& c : cases) {
        CAPTURE(program, c.args);
        const ViewerRun r = run_benchmark(program, c.args);
        CAPTURE(r.err, r.out);
        CHECK(r.exit_code == code);
        CHECK(r.err.find(c.expected) != std::string::npos);
        CHECK((!r.err.empty() && r.err.find('\n') == r.err.size() - 1));  // one line
        CHECK(r.out.empty());
    }
}

void check_help(const std::string& program, const std::vector<std::string>& mentions) {
    for (const char* flag : {"--help", "-h"}) {
        CAPTURE(program, flag);
        const ViewerRun r = run_benchmark(program, flag);
        CAPTURE(r.err);
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK(r.out.find("Usage: " + program) == 0);
        for (const std::string& m : mentions) {
            CHECK(r.out.find(m) != std::string::npos);
        }
    }
}

// A small linear image, to tone-map.
std::string write_test_pfm(const std::string& path) {
    trac0r::Image image;
    image.width = 4;
    image.height = 3;
    image.pixels.assign(12, glm::vec3(0.25f));
    trac0r::write_pfm(path, image);
    return path;
}

}  // namespace

TEST_CASE("tonemap: --help, and outputs and exposures it refuses", "[benchmark_cli]") {
    check_help("tonemap", {"IN.pfm", "OUT.png", "EXPOSURE", "default 1"});
    const std::string in = write_test_pfm("bench_cli_in.pfm");
    check_refused("tonemap",
                  {{in + " " + in, "is the input file"},
                   {in + " bench_cli_out.jpg",
                    "OUT.png 'bench_cli_out.jpg': expected a file name "
                    "ending in .png"},
                   {in + " bench_cli_out", "expected a file name ending in .png"},
                   {in + " bench_cli_out.png 2x", "EXPOSURE: expected a number in [1e-06, 1e+06]"},
                   {in + " bench_cli_out.png inf", "EXPOSURE: expected a number"},
                   {in + " bench_cli_out.png 1e300", "EXPOSURE: expected a number"},
                   {in + " bench_cli_out.png 1e-300", "EXPOSURE: expected a number"},
                   {in + " bench_cli_out.png 0", "EXPOSURE: expected a number"},
                   {in, "expected IN.pfm OUT.png [EXPOSURE], got 1 argument"},
                   {in + " bench_cli_out.png 1 2", "got 4 arguments"},
                   {"--bogus", "--bogus: unknown option"},
                   {in + " bench_cli_out.png 0x10", "EXPOSURE: expected a number"},
                   {in + " no_such_dir/out.png",
                    "OUT.png 'no_such_dir/out.png': cannot be written (directory no_such_dir "
                    "does not exist)"}},
                  2);
    // The input is untouched: still the PFM it was.
    CHECK(trac0r::read_pfm(in).width == 4);
    check_refused("tonemap", {{"no_such_file.pfm bench_cli_out.png", "no_such_file.pfm"}}, 1);

    std::remove("bench_cli_out.png");
    const ViewerRun ok = run_benchmark("tonemap", in + " bench_cli_out.png 2");
    CAPTURE(ok.err);
    CHECK(ok.exit_code == 0);
    const std::string png = trac0r_test::read_text_file("bench_cli_out.png");
    REQUIRE(png.size() > 8);
    CHECK(png.compare(1, 3, "PNG") == 0);
}

TEST_CASE("bench_accel_crossover: --help, and bad flags named", "[benchmark_cli]") {
    check_help("bench_accel_crossover", {"--frames N", "--size W H", "default 30"});
    check_refused("bench_accel_crossover",
                  {{"--bogus", "--bogus: unknown option"},
                   {"--frames", "--frames: expected a value"},
                   {"--size 32", "--size: expected two values, W H"},
                   {"--frames abc", "--frames: expected an integer in [1, 100000], got 'abc'"},
                   {"--frames 99999999999999999999", "--frames: expected an integer"},
                   {"--frames 1.5", "--frames: expected an integer"},
                   {"--size 32 0", "--size H: expected an integer in [1, 16384], got '0'"}},
                  2);
}

TEST_CASE("bench_filter: --help, bad flags and references refused before timing",
          "[benchmark_cli]") {
    check_help("bench_filter",
               {"--rounds N", "--reference FILE", "--seeds N", "default 800 x 600"});
    check_refused("bench_filter",
                  {{"--rounds 0", "--rounds: expected an integer in [1, 10000], got '0'"},
                   {"--spp 1", "--spp: expected an integer in [2, 65536], got '1'"},
                   {"--passes 17", "--passes: expected an integer in [0, 16]"},
                   {"--size 800", "--size: expected two values, W H"},
                   {"a.json b.json", "b.json: only one scene file"},
                   {"--bogus", "--bogus: unknown option"}},
                  2);
    // The reference is read, and its size checked, before the first frame.
    const std::string in = write_test_pfm("bench_cli_filter_ref.pfm");
    check_refused("bench_filter",
                  {{"--size 16 16 --reference no_such_ref.pfm", "no_such_ref.pfm"},
                   {"--size 16 16 --reference " + in,
                    "--reference bench_cli_filter_ref.pfm: is 4 x 3, the render 16 x 16"}},
                  1);
    std::remove(in.c_str());
}

#ifdef TRAC0R_HAVE_OPENCL
// Only the command line: every case stops before an OpenCL device is opened.
TEST_CASE("bench_backends: --help, bad flags named, default scenes missing", "[benchmark_cli]") {
    check_help("bench_backends", {"--frames N", "--accel LIST", "relative to the working"});
    check_refused("bench_backends",
                  {{"--frames abc", "--frames: expected an integer in [1, 100000], got 'abc'"},
                   {"--frames 1.5", "--frames: expected an integer"},
                   {"--width 0", "--width: expected an integer in [1, 16384], got '0'"},
                   {"--height 99999", "--height: expected an integer in [1, 16384]"},
                   {"--width", "--width: expected a value"},
                   {"--accel kd", "--accel: unknown structure 'kd'"},
                   {"--bogus", "--bogus: unknown option"}},
                  2);
    // The tests run in the build tree, where scenes/ is not: nothing is
    // printed before the message, which says where the defaults are read.
    check_refused("bench_backends",
                  {{"",
                    "scenes/cornell.json: cannot open scene file: No such file or directory (the "
                    "default scenes are "
                    "relative to the working directory"},
                   {"no_such_scene.json",
                    "no_such_scene.json: cannot open scene file: No such file or directory"}},
                  1);
}
#endif

TEST_CASE("bench_ray_order: sizes too small to time and scenes with no triangles refused",
          "[benchmark_cli]") {
    check_help("bench_ray_order", {"--size W H", "at least 4096 pixels"});
    check_refused("bench_ray_order",
                  {{"--size 1 1", "--size 1 1: 1 pixel, expected at least 4096"},
                   {"--size 32", "--size: expected two values, W H"},
                   {"--size 0 64", "--size W: expected an integer in [1, 16384], got '0'"},
                   {"--passes 1.5", "--passes: expected an integer in [1, 1000]"}},
                  2);
    // One triangle of zero area: the scene loader refuses the shape (so a
    // scene file cannot reach bench_ray_order's own check of an empty
    // scene, which stays for scenes made in code).
    std::ofstream("bench_cli_degenerate.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
    std::ofstream("bench_cli_degenerate.json")
        << R"({"materials": {"white": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
              "shapes": [{"type": "mesh", "material": "white", "file": "bench_cli_degenerate.obj"}]})";
    check_refused(
        "bench_ray_order",
        {{"bench_cli_degenerate.json --size 64 64",
          "bench_cli_degenerate.json: /shapes/0: no triangle of the shape can be rendered"}},
        1);
}

TEST_CASE("the benchmark programs: --version, --flag=value, generated --help", "[benchmark_cli]") {
    for (const char* program : {"tonemap", "bench_accel_crossover", "bench_complexity",
                                "bench_convergence", "bench_ray_order", "bench_scene_load",
                                "bench_temporal", "bench_filter", "bench_frame_budget"}) {
        CAPTURE(program);
        const ViewerRun r = run_benchmark(program, "--version");
        CAPTURE(r.err);
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK(r.out.find(std::string(program) + " trac0r " + TRAC0R_PROJECT_VERSION + " (") == 0);
        CHECK(r.out.find('\n') == r.out.size() - 1);  // one line
    }
    check_help("bench_complexity", {"Options:", "--frames N", "--backends LIST", "--csv FILE",
                                    "--version", "-h, --help"});
    check_help("bench_scene_load", {"Arguments:", "MB", "--repeats N"});
    // --flag=value reads as --flag value, its errors too.
    check_refused("bench_ray_order",
                  {{"--passes=1.5", "--passes: expected an integer in [1, 1000], got '1.5'"},
                   {"--passes=", "--passes: expected a value after '='"},
                   {"--passes=2 --passes=3", "--passes: given more than once"},
                   {"--bogus=2", "--bogus: unknown option"}},
                  2);
    check_refused("bench_accel_crossover",
                  {{"--frames=abc", "--frames: expected an integer in [1, 100000], got 'abc'"},
                   {"--version=2", "--version: takes no value, got '2'"},
                   {"stray", "unexpected argument 'stray'"}},
                  2);
}

TEST_CASE("bench_temporal: its figures for a tiny view, and its mistakes refused",
          "[benchmark_cli]") {
    check_refused(
        "bench_temporal",
        {{"--preview-factor 16 --width 8", "--preview-factor 16: leaves no pixel of 8 x 480"},
         {"--steps 0", "--steps: expected an integer in [1, 100000], got '0'"},
         {"--output-prefix /nonexistent/x", "--output-prefix /nonexistent/x: cannot be written"}},
        2);
    const ViewerRun r = run_benchmark(
        "bench_temporal", "--width 64 --height 48 --history-spp 4 --reference-spp 4 --steps 2");
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("view 64 x 48, preview 16 x 12, 4 spp before the move, 2 step(s)") == 0);
    CHECK(r.out.find("temporal reuse") != std::string::npos);
    CHECK(r.out.find("ratio (target <= 0.5)") != std::string::npos);
}

TEST_CASE("the benchmark programs refuse an option given twice", "[benchmark_cli]") {
    check_refused("bench_accel_crossover",
                  {{"--frames 1 --frames 2", "--frames: given more than once"},
                   {"--size 8 6 --size 4 3", "--size: given more than once"}},
                  2);
    check_refused("bench_ray_order", {{"--passes 1 --passes 2", "--passes: given more than once"}},
                  2);
    check_refused("bench_complexity", {{"--frames 1 --frames 1", "--frames: given more than once"}},
                  2);
}

TEST_CASE("bench_complexity: numbers, backends and --csv as the others check them",
          "[benchmark_cli]") {
    std::remove("bench_cli_dir.csv");
    REQUIRE(system("mkdir -p bench_cli_dir.csv") == 0);
    check_refused("bench_complexity",
                  {{"--flat-limit ' 1'", "--flat-limit: expected a number in [0, 1e+06]"},
                   {"--flat-limit +1", "--flat-limit: expected a number in [0, 1e+06]"},
                   {"--flat-limit 0x5", "--flat-limit: expected a number in [0, 1e+06]"},
                   {"--flat-limit 2e6", "--flat-limit: expected a number in [0, 1e+06], got '2e6'"},
                   {"--backends cpu,", "--backends cpu,: unknown backend ''"},
                   {"--backends cpu,cpu", "--backends cpu,cpu: 'cpu' given twice"},
                   {"--csv bench_cli_dir.csv",
                    "--csv bench_cli_dir.csv: cannot be written (is a "
                    "directory)"}},
                  2);
    REQUIRE(system("rmdir bench_cli_dir.csv") == 0);
}

TEST_CASE("bench_convergence: bad --cache, --config and --reference-spp refused before rendering",
          "[benchmark_cli]") {
    check_help("bench_convergence",
               {"--config SPEC", "key at most once", "not with --reference", "sampler=random|sobol",
                "--target-rmse E", "--target-relmse E"});
    const std::string in = write_test_pfm("bench_cli_reference.pfm");
    std::ofstream("bench_cli_scene.json")
        << R"({"materials": {"white": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
              "shapes": [{"type": "plane", "material": "white", "size": [1, 1]}]})";
    check_refused(
        "bench_convergence",
        {{"--config backend=cpu,backend=cpu",
          "--config backend=cpu,backend=cpu: key "
          "'backend' given twice"},
         {"--config ''", "--config: expected comma-separated key=value"},
         {"--config backend=cpu,", "an empty key=value"},
         {"--config colour=red", "unknown key 'colour'"},
         {"--config sampler=halton", "--config sampler=halton: sampler: unknown value 'halton'"},
         {"--target-rmse 0", "--target-rmse: expected a number in [1e-09, 1e+09], got '0'"},
         {"--target-relmse -1", "--target-relmse: expected a number"},
         {"--reference " + in + " --reference-spp 64",
          "--reference-spp: only for a "
          "rendered reference; --reference"},
         {"--seconds inf", "--seconds: expected a number"},
         {"--reference " + in + " --csv " + in,
          "--csv " + in + ": is the --reference image; it would be overwritten"},
         {"--seconds 1 --seconds 2", "--seconds: given more than once"},
         {"bench_cli_scene.json --csv bench_cli_scene.json",
          "--csv bench_cli_scene.json: is the scene file; it would be overwritten"},
         {"--csv ''", "--csv : cannot be written (the path is empty)"}},
        2);
    // The expensive reference would render first: these fail at once.
    std::ofstream("bench_cli_not_a_dir") << "x";
    check_refused("bench_convergence",
                  {{"--cache /nonexistent_trac0r_dir/cache",
                    "--cache /nonexistent_trac0r_dir/cache: cannot create the directory"},
                   {"--cache bench_cli_not_a_dir", "--cache bench_cli_not_a_dir: not a directory"},
                   {"--csv /nonexistent_trac0r_dir/x.csv --cache bench_cli_cache",
                    "--csv /nonexistent_trac0r_dir/x.csv: cannot be written (directory "
                    "/nonexistent_trac0r_dir does not exist)"}},
                  2);
}

namespace {

// bench_convergence's CSV: each configuration's RMSE at its checkpoints, by spp.
std::map<std::string, std::map<long, double>> convergence_rmse(const std::string& csv_path) {
    std::map<std::string, std::map<long, double>> rmse;
    std::ifstream csv(csv_path);
    std::string line;
    std::getline(csv, line);  // the header
    while (std::getline(csv, line)) {
        // "label",spp,seconds,rmse,...
        const std::size_t close = line.find('"', 1);
        std::istringstream rest(line.substr(close + 2));
        std::string spp, seconds, value;
        std::getline(rest, spp, ',');
        std::getline(rest, seconds, ',');
        std::getline(rest, value, ',');
        rmse[line.substr(1, close - 1)][std::stol(spp)] = std::stod(value);
    }
    return rmse;
}

}  // namespace

// The one run here that renders: the built-in scene at 16 x 12, to 16 spp,
// in well under a second; its times are printed, never checked.
TEST_CASE("bench_convergence: the samples to --target-rmse, and a configuration stops there",
          "[benchmark_cli]") {
    REQUIRE(system("rm -rf bench_cli_conv_cache && mkdir bench_cli_conv_cache") == 0);
    const std::string common =
        "--width=16 --height 12 --max-spp 16 --reference-spp=64 --cache bench_cli_conv_cache "
        "--config integrator=nee --config integrator=nee,sampler=sobol ";
    // Out of reach: every checkpoint is there, and says so.
    ViewerRun r =
        run_benchmark("bench_convergence", common + "--target-rmse 1e-9 --csv bench_cli_conv.csv");
    CAPTURE(r.out, r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("To an RMSE of 1e-09:") != std::string::npos);
    CHECK(r.out.find("cpu nee sobol: not reached by 16 spp") != std::string::npos);
    const auto all = convergence_rmse("bench_cli_conv.csv");
    REQUIRE(all.size() == 2);
    const std::map<long, double>& sobol = all.at("cpu nee sobol");
    REQUIRE(sobol.size() == 5);  // 1, 2, 4, 8, 16 spp
    REQUIRE(sobol.at(2) > sobol.at(4));
    // Halfway (on the log scale) between its RMSE at 2 and at 4 spp: the
    // same seeds give the same curve, interpolated to 2 x sqrt(2) spp, and
    // the sobol configuration stops at 4 spp.
    char target[32];
    std::snprintf(target, sizeof target, "%.9g", std::sqrt(sobol.at(2) * sobol.at(4)));
    r = run_benchmark("bench_convergence",
                      common + "--target-rmse " + target + " --csv bench_cli_conv.csv");
    CAPTURE(r.out, r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("cpu nee sobol: 3 spp, ") != std::string::npos);
    const auto stopped = convergence_rmse("bench_cli_conv.csv");
    CHECK(stopped.at("cpu nee sobol").size() == 3);  // 1, 2, 4 spp
    // Reached at once: nothing to interpolate from.
    r = run_benchmark("bench_convergence", common + "--target-relmse 1e9 --csv bench_cli_conv.csv");
    CAPTURE(r.out, r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("To a relative MSE of 1e+09:") != std::string::npos);
    CHECK(r.out.find("cpu nee: there by its first checkpoint (1 spp)") != std::string::npos);
    CHECK(convergence_rmse("bench_cli_conv.csv").at("cpu nee").size() == 1);
}

// A tiny real run of bench_frame_budget: the built-in scene at 32 x 24. A
// budget of a microsecond fits nothing, whatever the machine; the 50-ms one
// may fit or not (its timings are never checked); the rows at --bias-spp
// render whatever the timings.
TEST_CASE("bench_frame_budget: budgets that do not fit say so, and its mistakes refused",
          "[benchmark_cli]") {
    check_help("bench_frame_budget", {"--budgets LIST", "--reference-spp N", "--images DIR",
                                      "--csv FILE", "default 400"});
    check_refused(
        "bench_frame_budget",
        {{"--budgets 10,abc", "--budgets: expected a number in [0.001, 1e+06], got 'abc'"},
         {"--budgets 10,,20", "--budgets: expected a number"},
         {"--budgets 10,10", "--budgets 10,10: a budget is given twice"},
         {"--width 4", "--width: expected an integer in [8, 16384], got '4'"},
         {"--images /nonexistent/dir", "--images /nonexistent/dir: cannot create the directory"},
         {"--csv /nonexistent/x.csv", "--csv /nonexistent/x.csv: cannot be written"},
         {"--bogus", "--bogus: unknown option"},
         {"a.json b.json", "b.json: only one scene file"}},
        2);
    check_refused("bench_frame_budget", {{"no_such_scene.json", "no_such_scene.json"}}, 1);

    REQUIRE(system("rm -rf bench_cli_fb_cache bench_cli_fb_images bench_cli_fb.csv") == 0);
    const std::string args =
        "--width 32 --height 24 --budgets 0.001,50 --repeats 1 --reference-spp 4 --bias-spp 2 "
        "--move-seconds 0.1 --cache bench_cli_fb_cache --images bench_cli_fb_images "
        "--csv bench_cli_fb.csv";
    const ViewerRun r = run_benchmark("bench_frame_budget", args);
    CAPTURE(r.out, r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("reference: rendering 4 spp") != std::string::npos);
    CHECK(r.out.find("scene (built-in), 32 x 24, CPU backend, NEE, Sobol") == 0);
    CHECK(r.out.find("0.001ms raw       does not fit") != std::string::npos);
    CHECK(r.out.find("0.001ms filtered  does not fit") != std::string::npos);
    CHECK(r.out.find("0.001ms temporal  does not fit") != std::string::npos);
    CHECK(r.out.find("largest resolution at which one sample a pixel fits") != std::string::npos);
    // The CSV: a header, three rows a budget, the two at --bias-spp.
    std::istringstream csv(trac0r_test::read_text_file("bench_cli_fb.csv"));
    std::vector<std::string> lines;
    for (std::string line; std::getline(csv, line);) {
        lines.push_back(line);
    }
    REQUIRE(lines.size() == 9);
    CHECK(lines[0].find("scene,width,height,budget_ms,mode,spp,") == 0);
    CHECK(lines[1].find("builtin,32,24,0.001,raw,0,1,0,0,,,,") == 0);
    CHECK(lines[7].find("builtin,32,24,,raw,2,1,") == 0);
    CHECK(lines[8].find("builtin,32,24,,filtered,2,1,") == 0);
    // The images the plot script reads: the reference and the bias rows'.
    for (const char* name : {"reference", "raw-2spp", "filtered-2spp"}) {
        CAPTURE(name);
        const trac0r::Image image =
            trac0r::read_pfm(std::string("bench_cli_fb_images/builtin-32x24-") + name + ".pfm");
        CHECK(image.width == 32);
        CHECK(image.height == 24);
    }
    // A second run takes the reference from the cache.
    const ViewerRun again = run_benchmark("bench_frame_budget", args);
    CAPTURE(again.err);
    REQUIRE(again.exit_code == 0);
    CHECK(again.err.find("reference: cached bench_cli_fb_cache/builtin-") != std::string::npos);
}
