// What temporal reuse gives the first frame after a camera move, against
// starting again: issue 31's target, "after a one-step move, the first
// displayed frame's error against the converged image at the new view is
// at most half of what a restart gives".
//
// As the window does it (trac0r_viewer/view_history.cpp): the view is
// accumulated at full resolution (--history-spp), then the camera steps to
// the right and the window shows one low-resolution frame (1 sample a
// pixel, next-event estimation) per step. Shown with temporal reuse
// (trac0r/temporal.h) and without (a restart), both are compared with a
// converged render of the final view at the preview's resolution.
#include "cli.h"
#include "viewer_like.h"

#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/fly_camera.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/input_checks.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"
#include "trac0r/temporal.h"

#include <glm/glm.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace {

using namespace trac0r;
using trac0r_bench::UsageError;

const char* const description =
    "Renders SCENE at full resolution to --history-spp samples a pixel, then steps the camera "
    "to the right --steps times, rendering one low-resolution preview frame (1 sample a pixel, "
    "next-event estimation) per step as trac0r_viewer's window does while moving. Prints the "
    "error of the last frame shown, with temporal reuse and without it (a restart), against a "
    "converged render of the final view at the preview's resolution, and their ratio (issue "
    "31's target: at most 0.5 after one step).";

struct Options {
    std::string scene_path;
    long width = 640;
    long height = 480;
    long preview_factor = 4;
    long history_spp = 64;
    long steps = 1;
    double step = 1.0 / 120.0;
    long reference_spp = 1024;
    double max_history = TemporalSettings().max_history;
    std::string prefix;
};

Options parse_options(int argc, char** argv) {
    Options o;
    trac0r_cli::CommandLine cl("bench_temporal", "bench_temporal [SCENE.json] [options]",
                               description, 24);
    cl.positional("SCENE.json", &o.scene_path, "the scene (default: the built-in Cornell box)");
    cl.on_extra([](const std::string& a) { throw UsageError(a + ": only one scene file"); });
    cl.integer("--width", &o.width, 8, 16384, "full resolution (default 640)", "W");
    cl.integer("--height", &o.height, 8, 16384, "full resolution (default 480)", "H");
    cl.integer("--preview-factor", &o.preview_factor, 1, 16,
               "the preview's resolution divisor, as the window's (default 4)", "F");
    cl.integer("--history-spp", &o.history_spp, 1, 1L << 24,
               "samples a pixel accumulated before the move (default 64)", "N");
    cl.integer("--steps", &o.steps, 1, 100000, "camera steps, one preview frame each (default 1)",
               "N");
    cl.number("--step", &o.step, 1e-9, 1e3,
              "one step, in scene diagonals (default 1/120: the window's quarter diagonal a "
              "second at 30 frames a second)",
              "D");
    cl.integer("--reference-spp", &o.reference_spp, 1, 1L << 24,
               "samples a pixel of the converged final view (default 1024)", "N");
    cl.number("--max-history", &o.max_history, 0.0, 1e9,
              "the most samples the history counts for (default: the library's)", "N");
    cl.text("--output-prefix", &o.prefix,
            "also write PREFIX.temporal.pfm, PREFIX.restart.pfm and PREFIX.reference.pfm",
            "PREFIX");
    if (!cl.parse_or_print(argc, argv)) {
        std::exit(0);
    }
    if (o.width / o.preview_factor < 1 || o.height / o.preview_factor < 1) {
        throw UsageError("--preview-factor " + std::to_string(o.preview_factor) +
                         ": leaves no pixel of " + std::to_string(o.width) + " x " +
                         std::to_string(o.height));
    }
    if (!o.prefix.empty()) {
        const std::string reason = unwritable_reason(o.prefix + ".temporal.pfm");
        if (!reason.empty()) {
            throw UsageError("--output-prefix " + o.prefix + ": cannot be written (" + reason +
                             ")");
        }
    }
    return o;
}

std::unique_ptr<Renderer> make_renderer(Scene scene, int width, int height, std::uint64_t seed) {
    scene.render.width = width;
    scene.render.height = height;
    return std::make_unique<Renderer>(scene, std::make_unique<CpuBackend>(), seed,
                                      trac0r::PackOptions());
}

int run(int argc, char** argv) {
    const Options o = parse_options(argc, argv);
    const Scene scene = o.scene_path.empty() ? builtin_scene() : load_scene_file(o.scene_path);
    const int w = static_cast<int>(o.width);
    const int h = static_cast<int>(o.height);
    const int pw = w / static_cast<int>(o.preview_factor);
    const int ph = h / static_cast<int>(o.preview_factor);
    TemporalSettings settings;
    settings.max_history = static_cast<float>(o.max_history);

    std::unique_ptr<Renderer> full = make_renderer(scene, w, h, 1);
    for (long i = 0; i < o.history_spp; ++i) {
        full->render_frame();
    }
    TemporalFrame history = temporal_blend(
        TemporalFrame(), full->image(), static_cast<float>(full->frames()), full->camera_record(),
        render_surface_guides(full->packed(), full->camera_record()), settings);

    std::unique_ptr<Renderer> preview = make_renderer(scene, pw, ph, 1);
    Camera camera = scene.camera;
    const float step = static_cast<float>(o.step) * trac0r_bench::scene_diagonal(scene);
    Image restart;
    TemporalStats stats;
    for (long i = 0; i < o.steps; ++i) {
        camera = move_camera(camera, glm::vec3(step, 0.0f, 0.0f));
        preview->set_camera(camera);
        // Each frame its own samples, as the window's previews.
        preview->set_frame_sequence(static_cast<std::uint32_t>(i), 1);
        preview->render_frame();
        restart = preview->image();
        history = temporal_blend(history, restart, 1.0f, preview->camera_record(),
                                 render_surface_guides(preview->packed(), preview->camera_record()),
                                 settings, &stats);
    }
    const Image temporal = history.image();

    std::unique_ptr<Renderer> reference_renderer = make_renderer(scene, pw, ph, 2);
    reference_renderer->set_camera(camera);
    for (long i = 0; i < o.reference_spp; ++i) {
        reference_renderer->render_frame();
    }
    const Image reference = reference_renderer->image();
    const ImageError with = image_error(temporal, reference);
    const ImageError without = image_error(restart, reference);
    std::printf("view %d x %d, preview %d x %d, %ld spp before the move, %ld step(s) of %g\n", w, h,
                pw, ph, o.history_spp, o.steps, static_cast<double>(step));
    std::printf("pixels on a surface with history in the last frame: %.1f %%\n",
                100.0 * stats.reused / static_cast<double>(stats.reused + stats.dropped));
    std::printf("%-26s %10s %12s\n", "last frame shown", "RMSE", "relative MSE");
    std::printf("%-26s %10.4f %12.5f\n", "temporal reuse", with.rmse, with.relative_mse);
    std::printf("%-26s %10.4f %12.5f\n", "restart", without.rmse, without.relative_mse);
    std::printf("ratio (target <= 0.5)      %10.3f %12.3f\n", with.rmse / without.rmse,
                with.relative_mse / without.relative_mse);
    if (!o.prefix.empty()) {
        write_pfm(o.prefix + ".temporal.pfm", temporal);
        write_pfm(o.prefix + ".restart.pfm", restart);
        write_pfm(o.prefix + ".reference.pfm", reference);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("bench_temporal", [&] { return run(argc, argv); });
}
