// trac0r_viewer: the command-line entry point.
#include "headless.h"
#include "options.h"
#include "startup.h"
#include "window_session.h"

#include "trac0r/model_scene.h"
#include "trac0r/version.h"

#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

using trac0r_viewer::Options;
using trac0r_viewer::UsageError;

int main(int argc, char** argv) {
    // Over a file-size limit (ulimit -f) a write then fails with EFBIG, which
    // the image writers report, instead of the signal killing the program.
    std::signal(SIGXFSZ, SIG_IGN);
    trac0r_viewer::Startup startup;
    try {
        const Options options = trac0r_viewer::parse_options(argc, argv);
        if (options.help) {
            std::fputs(trac0r_viewer::usage_text().c_str(), stdout);
            return 0;
        }
        if (options.version) {
            std::printf("trac0r_viewer %s\n", trac0r::version_line().c_str());
            return 0;
        }
        if (options.list_devices) {
            if (options.given.size() > 1 || !options.scene_path.empty()) {
                throw UsageError(
                    "--list-devices: lists the OpenCL devices and exits; it goes "
                    "with no other option or scene");
            }
            return trac0r_viewer::list_devices();
        }
        if (options.print_scene) {
            if (!trac0r::is_model_path(options.scene_path)) {
                throw UsageError("--print-scene: expected a model file (.obj, .ply, .gltf, "
                                 ".glb) to make a scene around, got " +
                                 (options.scene_path.empty() ? std::string("none")
                                                             : "'" + options.scene_path + "'"));
            }
            startup.prepare(options);
            trac0r::LoadOptions load;
            load.strict = options.strict;
            std::string json;
            const trac0r::Scene scene = trac0r::model_scene(options.scene_path, load, &json);
            for (const std::string& line : scene.warnings) {
                std::fprintf(stderr, "%s\n", line.c_str());
            }
            std::fputs(json.c_str(), stdout);
            return std::fflush(stdout) == 0 ? 0 : 1;
        }
        startup.prepare(options);
        const trac0r::Scene& scene = startup.load(options);
        if (!options.headless) {
            const std::string title = "trac0r_viewer: " + (options.scene_path.empty()
                                                               ? std::string("built-in Cornell box")
                                                               : options.scene_path);
            return trac0r_viewer::run_window(
                options, title, scene.render, [&] { return startup.make_renderer(options); },
                [&](const std::string& name) {
                    return trac0r_viewer::backend_named(name, options);
                });
        }
        const std::unique_ptr<trac0r::Renderer> renderer = startup.make_renderer(options);
        if (options.benchmark_frames > 0) {
            return trac0r_viewer::run_benchmark(*renderer, options);
        }
        trac0r::SingleProcess one;
        return trac0r_viewer::run_batch(*renderer, options, one);
    } catch (...) {
        const trac0r_viewer::Failure failure = startup.failure(std::current_exception());
        std::fprintf(stderr, "trac0r_viewer: %s\n", failure.message.c_str());
        return failure.code;
    }
}
