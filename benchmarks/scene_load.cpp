// bench_scene_load: how scene loading time grows with the file's size
// (issue 33, point 5). Writes scene files of the given sizes in MB (default
// 1 10 100) into a temporary directory, each a room of many small planes,
// and times trac0r::load_scene_file on each (best of --repeats). Loading is
// linear when the MB/s column stays level. Prints a Markdown table.
#include "timing.h"

#include "trac0r/scene_loader.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

const char* const usage =
    "Usage: bench_scene_load [--repeats N] [MB ...]\n"
    "Times loading generated scene files of the given sizes (default 1 10 100 MB).\n";

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

}  // namespace

int main(int argc, char** argv) {
    int repeats = 3;
    std::vector<double> sizes_mb;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::fputs(usage, stdout);
            return 0;
        }
        char* end = nullptr;
        if (arg == "--repeats" && i + 1 < argc) {
            repeats = static_cast<int>(std::strtol(argv[++i], &end, 10));
            if (*end != '\0' || repeats < 1 || repeats > 100) {
                std::fprintf(stderr, "bench_scene_load: --repeats: expected 1 to 100\n");
                return 2;
            }
            continue;
        }
        const double mb = std::strtod(arg.c_str(), &end);
        if (*end != '\0' || !(mb > 0.0) || mb > 2000.0) {
            std::fprintf(stderr, "bench_scene_load: %s: expected a size in MB (0 to 2000)\n%s",
                         arg.c_str(), usage);
            return 2;
        }
        sizes_mb.push_back(mb);
    }
    if (sizes_mb.empty()) {
        sizes_mb = {1.0, 10.0, 100.0};
    }
    char dir_template[] = "/tmp/trac0r_scene_load_XXXXXX";
    if (!mkdtemp(dir_template)) {
        std::perror("bench_scene_load: mkdtemp");
        return 1;
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
