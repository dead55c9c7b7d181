#include "startup.h"

#include "slow_step.h"

#include "trac0r/cpu_backend.h"
#include "trac0r/filter.h"
#include "trac0r/image_io.h"
#include "trac0r/input_file.h"
#include "trac0r/input_checks.h"
#include "trac0r/opencl_backend.h"
#include "trac0r/output_file.h"
#include "trac0r/model_scene.h"
#include "trac0r/scene_loader.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <new>
#include <stdexcept>

namespace trac0r_viewer {

std::string raw_output_path(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
        return path + ".raw";
    }
    return path.substr(0, dot) + ".raw" + path.substr(dot);
}

void check_options(const Options& o, bool writes_outputs) {
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
            "--headless: nothing to do; give --output FILE (.png, .pfm or .exr) or "
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
    if (o.headless && !o.view.empty() &&
        std::none_of(o.outputs.begin(), o.outputs.end(), trac0r::is_png_path)) {
        throw UsageError(
            "--view: sets how PNG outputs (and the window) show the render, never .pfm or .exr; "
            "no --output is a .png");
    }
    if (o.exr_layers.any()) {
        if (!o.headless) {
            throw UsageError(
                "--exr-layers: only with --headless (the window saves the image alone)");
        }
        if (std::none_of(o.outputs.begin(), o.outputs.end(), trac0r::is_exr_path)) {
            throw UsageError("--exr-layers: adds layers to .exr outputs; no --output is a .exr");
        }
    }
    if (o.exr_half && std::none_of(o.outputs.begin(), o.outputs.end(), trac0r::is_exr_path)) {
        throw UsageError("--exr-half: sets how .exr outputs are stored; no --output is a .exr");
    }
    if (o.filter) {
        if (!o.headless && !o.outputs.empty()) {
            throw UsageError(
                "--filter: in the window it filters what is shown (F toggles it); filtered "
                "--output images only with --headless");
        }
        if (o.headless && o.outputs.empty()) {
            throw UsageError("--filter: filters the --output images; no --output is given");
        }
    }
    // Checked before rendering, not after; with --filter the .raw files
    // beside them too.
    std::vector<std::string> written = o.outputs;
    if (o.filter) {
        for (const std::string& f : o.outputs) {
            written.push_back(raw_output_path(f));
        }
    }
    for (const std::string& f : written) {
        if (!trac0r::is_supported_image_path(f)) {
            throw UsageError("--output " + f + ": expected a .png, .pfm or .exr file name");
        }
        const std::string reason = writes_outputs ? trac0r::unwritable_reason(f) : "";
        if (!reason.empty()) {
            throw UsageError("--output " + f + ": cannot be written (" + reason + ")");
        }
    }
}

trac0r::Scene load_scene(const Options& o) {
    trac0r::LoadOptions load;
    load.strict = o.strict;
    trac0r::Scene scene =
        o.scene_path.empty() ? trac0r::builtin_scene() : trac0r::open_scene(o.scene_path, load);
    if (o.width > 0) {
        scene.render.width = o.width;
    }
    if (o.height > 0) {
        scene.render.height = o.height;
    }
    if (o.max_depth > 0) {
        scene.render.max_depth = o.max_depth;
    }
    if (!o.camera_path.empty()) {
        scene.camera = trac0r::load_camera_file(o.camera_path, scene.origin);
    }
    if (!o.view.empty()) {
        scene.render.view = trac0r::parse_view_transform(o.view);
    }
    return scene;
}

// The environment, the lamps and the light list: what each kind's share
// of next-event estimation's picks is.
void print_lights(const trac0r::Scene& scene, const trac0r::PackedScene& p) {
    const trac0r::Environment& e = scene.environment;
    if (e.present && e.map.empty()) {
        std::fprintf(stderr, "environment: constant colour (%g, %g, %g), strength %g\n", e.color.x,
                     e.color.y, e.color.z, e.strength);
    } else if (e.present) {
        std::fprintf(stderr, "environment: map %s (%dx%d), strength %g, rotation %g degrees\n",
                     e.map.c_str(), e.width, e.height, e.strength, e.rotation);
    } else {
        std::fprintf(stderr, "environment: none (rays that leave the scene find black)\n");
    }
    for (std::size_t i = 0; i < scene.lamps.size(); ++i) {
        const trac0r::Lamp& l = scene.lamps[i];
        const glm::dvec3 at = glm::dvec3(l.position) + scene.origin;
        if (l.type == trac0r::LampType::sun) {
            std::fprintf(stderr,
                         "light %zu: sun towards (%g, %g, %g), irradiance %g W/m^2, colour (%g, "
                         "%g, %g), angle %g degrees\n",
                         i, l.direction.x, l.direction.y, l.direction.z, l.power, l.color.x,
                         l.color.y, l.color.z, l.angle);
        } else {
            std::fprintf(stderr,
                         "light %zu: %s at (%.6g, %.6g, %.6g), intensity %g W/sr, colour "
                         "(%g, %g, %g)",
                         i, trac0r::to_string(l.type), at.x, at.y, at.z, l.power, l.color.x,
                         l.color.y, l.color.z);
            if (l.type == trac0r::LampType::spot) {
                std::fprintf(stderr, ", pointing (%g, %g, %g), angle %g degrees, blend %g",
                             l.direction.x, l.direction.y, l.direction.z, l.angle, l.blend);
            }
            std::fprintf(stderr, "\n");
        }
    }
    // The picks' shares by kind (kernel/types.h's T0_LIGHT_* order).
    const char* const kinds[] = {"emitting triangles", "point", "spot", "sun", "environment"};
    double share[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
    std::size_t count[5] = {0, 0, 0, 0, 0};
    for (const trac0r::kernel::LightRecord& light : p.lights) {
        share[light.ids.y] += light.cdf.y;
        ++count[light.ids.y];
    }
    std::string list;
    for (int k = 4; k >= 0; --k) {
        if (count[k] > 0) {
            char text[96];
            std::snprintf(text, sizeof text, "%s%zu %s %.1f%%", list.empty() ? "" : ", ", count[k],
                          kinds[k], 100.0 * share[k]);
            list += text;
        }
    }
    const std::size_t one_sided = static_cast<std::size_t>(std::count_if(
        scene.materials.begin(), scene.materials.end(), [](const trac0r::Material& m) {
            const glm::vec3 e = trac0r::emitted_radiance(m);
            return !m.two_sided && std::max({e.x, e.y, e.z}) > 0.0f;
        }));
    const bool tree = (p.features & T0_FEATURE_LIGHT_TREE) != 0u;
    const bool bdpt = (p.features & T0_FEATURE_BDPT) != 0u;
    const char* how = !tree  ? "power"
                      : bdpt ? "a light tree (distant lights, and light subpaths' starts, by power)"
                             : "a light tree (distant lights by power)";
    std::fprintf(
        stderr, "light list: %zu lights, picked by %s (shares of power: %s)%s\n", p.lights.size(),
        how, list.empty() ? "none" : list.c_str(),
        one_sided > 0
            ? (", " + std::to_string(one_sided) + " one-sided emitting material(s)").c_str()
            : "");
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
    const trac0r::Scene& scene = r.scene();
    for (const trac0r::Shape& s : scene.shapes) {
        if (s.source.empty()) {
            continue;
        }
        // In the file's coordinates: the scene's are relative to its origin.
        const glm::dvec3 lo = glm::dvec3(s.aabb.min) + scene.origin;
        const glm::dvec3 hi = glm::dvec3(s.aabb.max) + scene.origin;
        // How many of its triangles are shaded smooth (vertex normals).
        const std::size_t smooth = static_cast<std::size_t>(std::count_if(
            s.normals.begin(), s.normals.end(),
            [](const trac0r::VertexNormalTriple& n) { return n[0] != glm::vec3(0.0f); }));
        const trac0r::Material& m = scene.materials[static_cast<std::size_t>(s.material)];
        // Its material's texture, if it has one and the triangles have
        // coordinates for it.
        std::string texture;
        if (m.texture >= 0 && !s.uvs.empty()) {
            const trac0r::Texture& t = scene.textures[static_cast<std::size_t>(m.texture)];
            texture = ", texture " + t.source + " (" + std::to_string(t.width) + "x" +
                      std::to_string(t.height) + ")";
        }
        std::fprintf(stderr,
                     "mesh %s: %zu triangles, bounds (%.6g, %.6g, %.6g) to (%.6g, %.6g, %.6g), "
                     "material %s%s, %zu smooth\n",
                     s.source.c_str(), s.triangles.size(), lo.x, lo.y, lo.z, hi.x, hi.y, hi.z,
                     m.name.c_str(), texture.c_str(), smooth);
    }
    print_lights(scene, p);
    std::fprintf(stderr, "backend: %s (%s)\n", r.backend().name().c_str(),
                 r.backend().device().c_str());
    if (o.filter) {
        std::fprintf(stderr,
                     "filter: on (edge-preserving a-trous, %d passes, on the %s backend); each "
                     "output's unfiltered image goes beside it as FILE.raw.EXT\n",
                     T0_FILTER_PASSES, r.backend().name().c_str());
    }
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

std::unique_ptr<trac0r::Backend> make_backend(const Options& o) {
#ifdef TRAC0R_HAVE_OPENCL
    if (o.backend == "opencl" && o.device < 0 && trac0r::list_opencl_devices().empty()) {
        std::fprintf(stderr,
                     "%s: no OpenCL device found; falling back to the "
                     "CPU backend (--device N insists on OpenCL)\n",
                     program_name());
        return backend_named("cpu", o);
    }
#endif
    return backend_named(o.backend, o);
}

Startup::Startup(bool speaks) : speaks_(speaks) {}

std::unique_ptr<SlowStep> Startup::announce(const std::string& what, bool at_once) const {
    return speaks_ ? std::make_unique<SlowStep>(what, at_once) : nullptr;
}

void Startup::prepare(const Options& options, bool writes_outputs) {
    check_options(options, writes_outputs);
    if (options.max_input_mb > 0) {
        trac0r::set_input_size_limit(static_cast<std::uint64_t>(options.max_input_mb) * 1000000u);
    }
}

const trac0r::Scene& Startup::load(const Options& options) {
    {
        const std::unique_ptr<SlowStep> notice = announce(
            "loading " + (options.scene_path.empty() ? "the built-in scene" : options.scene_path),
            options.verbose);
        scene_ = load_scene(options);
    }
    if (speaks_) {
        for (const std::string& line : scene_.warnings) {
            std::fprintf(stderr, "%s\n", line.c_str());
        }
    }
    memory_user_ = "the scene's " + std::to_string(scene_.triangle_count()) +
                   " triangles and their tree, and 48 bytes a pixel for the accumulator: "
                   "a smaller --width and --height, or a smaller mesh";
    return scene_;
}

std::unique_ptr<trac0r::Renderer> Startup::make_renderer(const Options& options) {
    const trac0r::PackOptions pack = pack_options(options);
    std::unique_ptr<trac0r::Renderer> renderer;
    {
        const std::unique_ptr<SlowStep> notice =
            announce("packing " + std::to_string(scene_.triangle_count()) +
                         " triangles and building the acceleration structure",
                     options.verbose);
        renderer =
            std::make_unique<trac0r::Renderer>(scene_, make_backend(options), options.seed, pack);
    }
    if (options.verbose && speaks_) {
        print_verbose(*renderer, options);
    }
    // Not an error (a scene may be built up light by light), but nothing
    // else would say why the image stays black.
    const std::uint32_t lit = T0_FEATURE_EMITTANCE | T0_FEATURE_ENVIRONMENT | T0_FEATURE_LAMPS;
    if ((renderer->packed().features & lit) == 0u && !warned_dark_ && speaks_) {
        std::fprintf(stderr,
                     "%s: warning: nothing emits light (no material that emits is used: an "
                     "emittance and a colour above 0, or a principled material's emission; and "
                     "there is no environment or lamp that is not black), so the image will be "
                     "black\n",
                     program_name());
        warned_dark_ = true;
    } else if ((renderer->packed().features & T0_FEATURE_LAMPS) != 0u &&
               pack.integrator == trac0r::Integrator::naive && !warned_dark_ && speaks_) {
        std::fprintf(stderr,
                     "%s: warning: the naive integrator finds light by scattering alone, so "
                     "point and spot lamps and a sun of angle 0 stay dark (use --integrator "
                     "nee)\n",
                     program_name());
        warned_dark_ = true;
    }
    return renderer;
}

Failure Startup::failure(std::exception_ptr error) const {
    try {
        std::rethrow_exception(error);
    } catch (const UsageError& e) {
        return {2, e.what()};
    } catch (const trac0r::SceneError& e) {
        return {1, e.what()};
    } catch (const std::bad_alloc&) {
        return {1, "error: out of memory (" + memory_user_ + " may help)"};
    } catch (const std::exception& e) {
        return {1, std::string("error: ") + e.what()};
    }
}

}  // namespace trac0r_viewer
