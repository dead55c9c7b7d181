// trac0r_viewer: the command-line entry point.
#include "headless.h"
#include "options.h"
#include "slow_step.h"
#include "window_session.h"

#include "trac0r/input_checks.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/image_io.h"
#include "trac0r/input_file.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using trac0r_viewer::Options;
using trac0r_viewer::UsageError;

// Checks combinations of flags that each parse fine alone.
void check_options(const Options& o) {
#ifndef TRAC0R_HAVE_OPENCL
    if (o.backend == "opencl" || o.device >= 0 || o.list_devices) {
        throw UsageError(
            "--backend opencl / --device / --list-devices: this build has no "
            "OpenCL backend (configure with -DTRAC0R_OPENCL=ON)");
    }
#endif
    if (o.device >= 0 && o.backend != "opencl") {
        throw UsageError("--device " + std::to_string(o.device) +
                         ": picks an OpenCL device; add --backend opencl");
    }
    if (o.headless && o.benchmark_frames == 0 && o.outputs.empty()) {
        throw UsageError(
            "--headless: nothing to do; give --output FILE (.png or .pfm) or "
            "--benchmark N");
    }
    if (o.benchmark_frames > 0 && (o.spp > 0 || o.seconds > 0.0 || o.target_error > 0.0)) {
        throw UsageError(
            "--benchmark: renders exactly N frames; it does not go with --spp, "
            "--seconds or --target-error");
    }
    if (!o.replay_path.empty() && (o.headless || o.benchmark_frames > 0)) {
        throw UsageError(
            "--replay: scripts the interactive window; it does not go with "
            "--headless or --benchmark");
    }
    if (o.headless && o.given.count("--exposure") != 0 &&
        std::none_of(o.outputs.begin(), o.outputs.end(), trac0r::is_png_path)) {
        throw UsageError(
            "--exposure: scales the tone mapping of PNG outputs (and the window); no --output is "
            "a .png");
    }
    // Checked before rendering, not after.
    for (const std::string& f : o.outputs) {
        if (!trac0r::is_supported_image_path(f)) {
            throw UsageError("--output " + f + ": expected a .png or .pfm file name");
        }
        const std::string reason = trac0r::unwritable_reason(f);
        if (!reason.empty()) {
            throw UsageError("--output " + f + ": cannot be written (" + reason + ")");
        }
    }
}

trac0r::Scene load_scene(const Options& o) {
    trac0r::Scene scene =
        o.scene_path.empty() ? trac0r::builtin_scene() : trac0r::load_scene_file(o.scene_path);
    if (o.width > 0) {
        scene.render.width = o.width;
    }
    if (o.height > 0) {
        scene.render.height = o.height;
    }
    if (o.max_depth > 0) {
        scene.render.max_depth = o.max_depth;
    }
    return scene;
}

void print_verbose(trac0r::Renderer& r, const Options& o) {
    const trac0r::PackedScene& p = r.packed();
    std::fprintf(stderr,
                 "scene: %s, %zu shapes, %zu triangles (%zu degenerate left out), %dx%d, "
                 "max depth %d, seed %llu\n",
                 o.scene_path.empty() ? "built-in Cornell box" : o.scene_path.c_str(),
                 r.scene().shapes.size(), p.triangles.size(), p.dropped_degenerate_triangles,
                 r.width(), r.height(), r.scene().render.max_depth,
                 static_cast<unsigned long long>(o.seed));
    if (p.nodes.empty()) {
        std::fprintf(stderr, "acceleration: flat list of %zu shapes (--accel %s)\n",
                     p.shapes.size(), o.accel.c_str());
    } else {
        std::fprintf(stderr, "acceleration: BVH of %zu nodes, depth %d%s (--accel %s)\n",
                     p.nodes.size(), p.bvh_depth, p.bvh_by_levels ? ", collapsed by levels" : "",
                     o.accel.c_str());
    }
    std::fprintf(stderr, "backend: %s (%s)\n", r.backend().name().c_str(),
                 r.backend().device().c_str());
    std::fprintf(stderr, "features: %s (mask 0x%02x); left out: %s\n",
                 trac0r::feature_names(p.features).c_str(), p.features,
                 trac0r::left_out_feature_names(p.features).c_str());
#ifdef TRAC0R_HAVE_OPENCL
    if (auto* cl = dynamic_cast<trac0r::OpenClBackend*>(&r.backend())) {
        std::fprintf(stderr, "OpenCL program: built in %.2f s (0: reused) with '%s'\n",
                     cl->last_build_seconds(), cl->build_options().c_str());
    }
#endif
}

int list_devices() {
#ifdef TRAC0R_HAVE_OPENCL
    const std::vector<trac0r::OpenClDeviceInfo> devices = trac0r::list_opencl_devices();
    if (devices.empty()) {
        std::fprintf(stderr,
                     "trac0r_viewer: no OpenCL platform or device found (install an "
                     "OpenCL driver, e.g. Debian's pocl-opencl-icd)\n");
        return 1;
    }
    for (const trac0r::OpenClDeviceInfo& d : devices) {
        std::printf("%d: %s [%s] on %s\n", d.index, d.name.c_str(), d.type.c_str(),
                    d.platform.c_str());
    }
#endif
    return 0;
}

// The backend called `name` ("cpu" or "opencl"), or an exception saying
// why it cannot be had. The window's B key uses it as it is: no fallback.
std::unique_ptr<trac0r::Backend> backend_named(const std::string& name, const Options& o) {
    if (name == "opencl") {
#ifdef TRAC0R_HAVE_OPENCL
        if (o.device < 0 && trac0r::list_opencl_devices().empty()) {
            throw std::runtime_error(
                "no OpenCL device found (install an OpenCL driver, e.g. "
                "Debian's pocl-opencl-icd)");
        }
        return std::make_unique<trac0r::OpenClBackend>(o.device >= 0 ? o.device : 0);
#else
        throw std::runtime_error(
            "this build has no OpenCL backend (configure with "
            "-DTRAC0R_OPENCL=ON)");
#endif
    }
    return std::make_unique<trac0r::CpuBackend>(o.threads);
}

// The requested backend. Without an OpenCL device, --backend opencl falls
// back to the CPU and says so; an explicit --device insists (an error), and
// a program that fails to build is always an error (its log is printed).
std::unique_ptr<trac0r::Backend> make_backend(const Options& o) {
#ifdef TRAC0R_HAVE_OPENCL
    if (o.backend == "opencl" && o.device < 0 && trac0r::list_opencl_devices().empty()) {
        std::fprintf(stderr,
                     "trac0r_viewer: no OpenCL device found; falling back to the "
                     "CPU backend (--device N insists on OpenCL)\n");
        return backend_named("cpu", o);
    }
#endif
    return backend_named(o.backend, o);
}

}  // namespace

int main(int argc, char** argv) {
    // Over a file-size limit (ulimit -f) a write then fails with EFBIG, which
    // the image writers report, instead of the signal killing the program.
    std::signal(SIGXFSZ, SIG_IGN);
    // What an out-of-memory error is blamed on: the scene file and its
    // meshes while they load, then the packed scene and the accumulator.
    std::string memory_user = "the scene file and its meshes, while loading: a smaller mesh";
    try {
        const Options options = trac0r_viewer::parse_options(argc, argv);
        if (options.help) {
            std::fputs(trac0r_viewer::usage_text(), stdout);
            return 0;
        }
        if (options.list_devices) {
            if (options.given.size() > 1 || !options.scene_path.empty()) {
                throw UsageError(
                    "--list-devices: lists the OpenCL devices and exits; it goes "
                    "with no other option or scene");
            }
            return list_devices();
        }
        check_options(options);
        if (options.max_input_mb > 0) {
            trac0r::set_input_size_limit(static_cast<std::uint64_t>(options.max_input_mb) *
                                         1000000u);
        }
        const trac0r::Scene scene = [&] {
            const trac0r_viewer::SlowStep notice(
                "loading " +
                    (options.scene_path.empty() ? "the built-in scene" : options.scene_path),
                options.verbose);
            return load_scene(options);
        }();
        memory_user = "the scene's " + std::to_string(scene.triangle_count()) +
                      " triangles and their tree, and 48 bytes a pixel for the accumulator: "
                      "a smaller --width and --height, or a smaller mesh";
        trac0r::PackOptions pack;
        pack.accel = trac0r::parse_accel(options.accel);
        pack.integrator = trac0r::parse_integrator(options.integrator);
        bool warned_dark = false;
        const auto make_renderer = [&] {
            std::unique_ptr<trac0r::Renderer> renderer;
            {
                const trac0r_viewer::SlowStep notice(
                    "packing " + std::to_string(scene.triangle_count()) +
                        " triangles and building the acceleration structure",
                    options.verbose);
                renderer = std::make_unique<trac0r::Renderer>(scene, make_backend(options),
                                                              options.seed, pack);
            }
            if (options.verbose) {
                print_verbose(*renderer, options);
            }
            // Not an error (a scene may be built up light by light), but
            // nothing else would say why the image stays black.
            if ((renderer->packed().features & T0_FEATURE_EMITTANCE) == 0u && !warned_dark) {
                std::fprintf(stderr,
                             "trac0r_viewer: warning: no shape emits light (no material "
                             "with an emittance and a colour above 0 is used), so the image "
                             "will be black\n");
                warned_dark = true;
            }
            return renderer;
        };
        if (!options.headless) {
            const std::string title = "trac0r_viewer: " + (options.scene_path.empty()
                                                               ? std::string("built-in Cornell box")
                                                               : options.scene_path);
            return trac0r_viewer::run_window(
                options, title, scene.render, make_renderer,
                [&](const std::string& name) { return backend_named(name, options); });
        }
        const std::unique_ptr<trac0r::Renderer> renderer = make_renderer();
        if (options.benchmark_frames > 0) {
            return trac0r_viewer::run_benchmark(*renderer, options);
        }
        return trac0r_viewer::run_batch(*renderer, options);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "trac0r_viewer: %s\n", e.what());
        return 2;
    } catch (const trac0r::SceneError& e) {
        std::fprintf(stderr, "trac0r_viewer: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "trac0r_viewer: error: out of memory (%s may help)\n",
                     memory_user.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trac0r_viewer: error: %s\n", e.what());
        return 1;
    }
}
