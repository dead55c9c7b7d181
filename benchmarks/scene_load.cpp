// bench_scene_load: how scene loading time grows with the file's size
// (issue 33, point 5). Writes scene files of the given sizes in MB (default
// 1 10 100) into a temporary directory, each a room of many small planes,
// and times trac0r::load_scene_file on each (best of --repeats). Loading is
// linear when the MB/s column stays level. Prints a Markdown table.
#include "cli.h"
#include "timing.h"

#include "trac0r/scene_loader.h"

#include <unistd.h>

#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <fstream>
#include <string>
#include <vector>

namespace {

const char* const description =
    "Times loading generated scene files of the given sizes (default 1 10 100 MB): a room of "
    "many small planes each, loaded with trac0r::load_scene_file, best of --repeats; prints a "
    "Markdown table.";

// A scene of about `bytes` bytes: planes on a grid, one material.
std::string scene_text(std::size_t bytes) {
    std::string text =
        "{\"materials\": {\"white\": {\"type\": \"diffuse\", \"color\": [0.7, 0.7, 0.7]},\n"
        "               \"lamp\": {\"type\": \"emissive\", \"color\": [1, 1, 1], "
        "\"emittance\": 10}},\n \"shapes\": [\n"
        "  {\"type\": \"plane\", \"position\": [0, 2, 0], \"size\": [1, 1], \"material\": "
        "\"lamp\"}";
    char shape[256];
    for (long i = 0; text.size() < bytes; ++i) {
        std::snprintf(shape, sizeof shape,
                      ",\n  {\"type\": \"plane\", \"position\": [%.4f, 0, %.4f], "
                      "\"orientation\": [0, %.3f, 0], \"size\": [0.01, 0.01], \"material\": "
                      "\"white\"}",
                      0.01 * static_cast<double>(i % 1000), 0.01 * static_cast<double>(i / 1000),
                      0.001 * static_cast<double>(i % 997));
        text += shape;
    }
    return text + "\n]}\n";
}

int run(int repeats, const std::vector<double>& sizes_mb) {
    char dir_template[] = "/tmp/trac0r_scene_load_XXXXXX";
    if (!mkdtemp(dir_template)) {
        throw std::runtime_error(std::string("mkdtemp: ") + std::strerror(errno));
    }
    const std::string dir = dir_template;
    std::printf("| file MB | shapes | load s (best of %d) | MB/s |\n|---|---|---|---|\n", repeats);
    for (double mb : sizes_mb) {
        const std::string path = dir + "/scene.json";
        const std::string text = scene_text(static_cast<std::size_t>(mb * 1e6));
        std::ofstream(path, std::ios::binary) << text;
        double best = 1e30;
        std::size_t shapes = 0;
        for (int r = 0; r < repeats; ++r) {
            const double start = trac0r_bench::clock_seconds(CLOCK_MONOTONIC);
            const trac0r::Scene scene = trac0r::load_scene_file(path);
            best = std::min(best, trac0r_bench::clock_seconds(CLOCK_MONOTONIC) - start);
            shapes = scene.shapes.size();
        }
        std::printf("| %.1f | %zu | %.3f | %.1f |\n", static_cast<double>(text.size()) / 1e6,
                    shapes, best, static_cast<double>(text.size()) / 1e6 / best);
        std::fflush(stdout);
        std::remove(path.c_str());
    }
    rmdir(dir.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_scene_load", [&] {
        int repeats = 3;
        std::vector<std::string> sizes;
        trac0r_cli::CommandLine cl("bench_scene_load", "bench_scene_load [--repeats N] [MB ...]",
                                   description, 16);
        cl.app().add_option("MB", sizes, "the sizes of the scene files, each in (0, 2000]");
        cl.integer("--repeats", &repeats, 1, 100, "loads of each file, in [1, 100] (default 3)");
        if (!cl.parse_or_print(argc, argv)) {
            return 0;
        }
        std::vector<double> sizes_mb;
        for (const std::string& text : sizes) {
            const double mb = trac0r_bench::parse_number("MB", text, 0.0, 2000.0);
            if (!(mb > 0.0)) {
                throw trac0r_bench::UsageError("MB: expected a number in (0, 2000], got '" + text +
                                               "'");
            }
            sizes_mb.push_back(mb);
        }
        if (sizes_mb.empty()) {
            sizes_mb = {1.0, 10.0, 100.0};
        }
        return run(repeats, sizes_mb);
    });
}
