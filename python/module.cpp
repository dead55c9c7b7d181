// The Python module trac0r._trac0r (docs/python.md): scenes loaded (the
// Scene class: scene_class.cpp), batch renders with stop rules, progress
// and cancelling, images as NumPy arrays that share the render's memory,
// and image writing. Errors are the library's messages, raised as ValueError
// (bad arguments) or RuntimeError (files, devices).
#include "trac0r/batch.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/image_io.h"
#include "trac0r/model_scene.h"
#include "trac0r/packed_scene.h"
#include "trac0r/scene_loader.h"
#include "trac0r/version.h"
#include "bindings.h"
#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_backend.h"
#endif

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace trac0r;
using namespace trac0r_python;

namespace trac0r_python {

// The limits of the scene format and the programs' flags.
void check_size(const char* name, long value, long highest) {
    if (value < 1 || value > highest) {
        throw py::value_error(std::string(name) + ": expected an integer in [1, " +
                              std::to_string(highest) + "], got " + std::to_string(value));
    }
}

}  // namespace trac0r_python

namespace {

// A path given as str or path-like (pathlib.Path): os.fspath's str, else
// false.
bool as_path(const py::object& value, std::string* path) {
    if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__")) {
        return false;
    }
    const py::object text = py::module_::import("os").attr("fspath")(value);
    if (!py::isinstance<py::str>(text)) {
        throw py::value_error("scene: expected a Scene or the path of a scene or model file");
    }
    *path = text.cast<std::string>();
    return true;
}

// A scene or model file, loaded without the GIL.
Scene load_released(const std::string& path, const LoadOptions& options) {
    py::gil_scoped_release release;
    return open_scene(path, options);
}

// A stop-rule argument: 0 (not set) or a finite positive number.
void check_stop(const char* name, double value) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
        throw py::value_error(std::string(name) +
                              ": expected 0 (not set) or a finite positive number, got " +
                              py::str(py::float_(value)).cast<std::string>());
    }
}

// A flag that another Python thread sets while a render runs (the GIL is
// released then): CancelToken.cancel().
struct CancelToken {
    std::atomic<int> code{0};
};

// An array over `owner`'s memory, which the array keeps alive: no copy.
template <typename Owner>
py::array_t<float> owned_array(std::unique_ptr<Owner> owner, float* data,
                               std::vector<py::ssize_t> shape) {
    std::vector<py::ssize_t> strides(shape.size());
    py::ssize_t stride = static_cast<py::ssize_t>(sizeof(float));
    for (std::size_t i = shape.size(); i-- > 0;) {
        strides[i] = stride;
        stride *= shape[i];
    }
    Owner* raw = owner.release();
    py::capsule keep(raw, [](void* p) { delete static_cast<Owner*>(p); });
    return py::array_t<float>(shape, strides, data, keep);
}

// height x width x 3 float32 over the image's pixels.
py::array_t<float> image_array(Image image) {
    std::unique_ptr<Image> owner(new Image(std::move(image)));
    float* data = reinterpret_cast<float*>(owner->pixels.data());
    const std::vector<py::ssize_t> shape = {owner->height, owner->width, 3};
    return owned_array(std::move(owner), data, shape);
}

py::array_t<float> plane_array(std::vector<float> values, int width, int height) {
    std::unique_ptr<std::vector<float>> owner(new std::vector<float>(std::move(values)));
    float* data = owner->data();
    return owned_array(std::move(owner), data, {height, width});
}

Image image_from_array(const py::array_t<float, py::array::c_style | py::array::forcecast>& a) {
    if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1) {
        throw py::value_error("write_image: image: expected an array of height x width x 3");
    }
    Image image;
    image.height = static_cast<int>(a.shape(0));
    image.width = static_cast<int>(a.shape(1));
    image.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
    const float* data = a.data();
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = glm::vec3(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
    }
    return image;
}

std::unique_ptr<Backend> make_backend(const std::string& name, int device, int threads) {
    if (name == "cpu") {
        return std::unique_ptr<Backend>(new CpuBackend(threads));
    }
    if (name == "opencl") {
#ifdef TRAC0R_HAVE_OPENCL
        return std::unique_ptr<Backend>(new OpenClBackend(device));
#else
        (void)device;
        throw py::value_error("backend: 'opencl' is not in this build (built without OpenCL)");
#endif
    }
    throw py::value_error("backend: expected 'cpu' or 'opencl', got '" + name + "'");
}

ExrLayerChoice layer_choice(const std::vector<std::string>& names) {
    ExrLayerChoice c;
    for (const std::string& n : names) {
        if (n == "albedo") {
            c.albedo = true;
        } else if (n == "normal") {
            c.normal = true;
        } else if (n == "depth") {
            c.depth = true;
        } else if (n == "variance") {
            c.variance = true;
        } else {
            throw py::value_error("layers: expected albedo, normal, depth or variance, got '" + n +
                                  "'");
        }
    }
    return c;
}

struct RenderArgs {
    py::object scene;
    long spp = 0;
    double seconds = 0.0;
    double target_error = 0.0;
    int width = 0;
    int height = 0;
    int max_depth = 0;
    std::uint64_t seed = default_seed;
    std::string backend = "cpu";
    int device = 0;
    int threads = 0;
    std::string integrator;
    std::string sampler;
    py::object progress;
    CancelToken* cancel = nullptr;
    bool filtered = false;
    std::vector<std::string> layers;
};

// Renders; the GIL is released but while the progress callback runs. A
// KeyboardInterrupt (Ctrl-C) or an exception in the callback cancels the
// render and is raised when it has stopped.
BatchResult run(const RenderArgs& a) {
    if (a.spp < 0 || a.spp > static_cast<long>(Renderer::max_frames)) {
        throw py::value_error("spp: expected 0 (not set) or an integer in [1, " +
                              std::to_string(Renderer::max_frames) + "], got " +
                              std::to_string(a.spp));
    }
    check_stop("seconds", a.seconds);
    check_stop("target_error", a.target_error);
    if (a.width != 0) {
        check_size("width", a.width, 16384);
    }
    if (a.height != 0) {
        check_size("height", a.height, 16384);
    }
    if (a.max_depth != 0) {
        check_size("max_depth", a.max_depth, 100000);
    }
    if (a.device < 0) {
        throw py::value_error("device: expected an OpenCL device index from 0, got " +
                              std::to_string(a.device));
    }
    std::string path;
    Scene scene =
        as_path(a.scene, &path) ? load_released(path, LoadOptions()) : a.scene.cast<Scene>();
    if (a.width > 0) {
        scene.render.width = a.width;
    }
    if (a.height > 0) {
        scene.render.height = a.height;
    }
    if (a.max_depth > 0) {
        scene.render.max_depth = a.max_depth;
    }
    PackOptions pack;
    try {
        if (!a.integrator.empty()) {
            pack.integrator = parse_integrator(a.integrator);
        }
        if (!a.sampler.empty()) {
            pack.sampler = parse_sampler(a.sampler);
        }
    } catch (const std::invalid_argument& e) {
        throw py::value_error(e.what());
    }
    BatchOptions options;
    options.stop.spp = a.spp;
    options.stop.seconds = a.seconds;
    options.stop.target_error = a.target_error;
    options.filtered = a.filtered;
    options.layers = layer_choice(a.layers);
    if (a.cancel != nullptr) {
        options.cancel = &a.cancel->code;
    }
    std::unique_ptr<py::error_already_set> raised;
    const py::object progress = a.progress;
    options.progress = [&](const BatchProgress& p) {
        py::gil_scoped_acquire gil;
        try {
            if (PyErr_CheckSignals() != 0) {
                throw py::error_already_set();
            }
            if (!progress.is_none()) {
                const py::object answer = progress(p);
                return !(py::isinstance<py::bool_>(answer) && !answer.cast<bool>());
            }
            return true;
        } catch (py::error_already_set& e) {
            raised.reset(new py::error_already_set(std::move(e)));
            return false;
        }
    };
    BatchResult result;
    {
        std::unique_ptr<Renderer> renderer;
        py::gil_scoped_release release;
        renderer.reset(
            new Renderer(scene, make_backend(a.backend, a.device, a.threads), a.seed, pack));
        result = render_batch(*renderer, options);
        renderer.reset();
    }
    if (raised) {
        throw std::move(*raised);
    }
    return result;
}

const char* const render_doc = R"(Renders a scene until a stop rule; returns the image.

scene: a Scene, or the path of a scene file (JSON) or model file.
spp, seconds, target_error: stop at whichever comes first (none: 64 spp);
    target_error is the estimated relative MSE (docs/noise.md).
width, height, max_depth: override the scene's.
seed: same seed, same image.
backend: 'cpu' or 'opencl' (device: its index); threads: CPU threads (0: all).
integrator: 'nee' (default), 'bdpt' (bidirectional: caustics; max_depth at
    most 64) or 'naive'; sampler: 'sobol' (default) or 'random'.
progress: called about 10 times a second with a Progress; returning False
    cancels (the frames so far come back).
cancel: a CancelToken another thread may cancel.
Ctrl-C cancels and raises KeyboardInterrupt.

Returns the mean radiance, a float32 array of height x width x 3.)";

}  // namespace

PYBIND11_MODULE(_trac0r, m) {
    m.doc() = "trac0r: a real-time Monte Carlo path tracer (docs/python.md)";
    m.attr("__version__") = version();
    m.attr("default_spp") = default_batch_spp;

    bind_scene(m);

    py::class_<BatchProgress>(m, "Progress", "Where a render is, for a progress bar.")
        .def_readonly("spp", &BatchProgress::spp)
        .def_readonly("seconds", &BatchProgress::seconds)
        .def_readonly("paths_per_second", &BatchProgress::paths_per_second)
        .def_readonly("estimate", &BatchProgress::estimate,
                      "estimated relative MSE (inf before 2 spp)")
        .def_readonly("fraction", &BatchProgress::fraction, "of the stop rule, in [0, 1]")
        .def("__repr__", [](const BatchProgress& p) {
            return "<trac0r.Progress " + std::to_string(p.spp) + " spp, " +
                   std::to_string(p.fraction) + ">";
        });

    py::class_<CancelToken>(m, "CancelToken",
                            "Cancels a render from another thread: pass it as cancel=.")
        .def(py::init<>())
        .def(
            "cancel", [](CancelToken& t) { t.code = 1; },
            "the running render stops after its frame in flight")
        .def(
            "reset", [](CancelToken& t) { t.code = 0; },
            "not cancelled again: a cancelled token stops every render it is given until then")
        .def_property_readonly("cancelled", [](const CancelToken& t) { return t.code != 0; });

    m.def(
        "load_scene",
        [](const py::object& path, bool strict) {
            std::string text;
            if (!as_path(path, &text)) {
                throw py::value_error("path: expected a str or path-like, got " +
                                      py::str(py::type::of(path)).cast<std::string>());
            }
            LoadOptions o;
            o.strict = strict;
            return load_released(text, o);
        },
        py::arg("path"), py::arg("strict") = false,
        "Loads a scene file (JSON) or a model file (.obj, .ply, .gltf, .glb). strict: refuse "
        "a model's defects instead of warning (Scene.warnings).");
    m.def(
        "parse_scene",
        [](const std::string& text, const std::string& base_dir, bool strict) {
            LoadOptions o;
            o.strict = strict;
            o.shapes_optional = true;
            return parse_scene(text, "<scene>", base_dir, o);
        },
        py::arg("text"), py::arg("base_dir") = ".", py::arg("strict") = false,
        "A scene from JSON text in the scene format (docs/scene-format.md); 'shapes' may be "
        "empty, for shapes added with Scene.add_mesh. Mesh files are found from base_dir.");
    m.def("builtin_scene", &builtin_scene, "The thesis' Cornell box (scenes/cornell.json).");

    m.def(
        "render_images",
        [](const py::object& scene, long spp, double seconds, double target_error, int width,
           int height, int max_depth, std::uint64_t seed, const std::string& backend, int device,
           int threads, const std::string& integrator, const std::string& sampler,
           const py::object& progress, CancelToken* cancel, bool filtered,
           const std::vector<std::string>& layers) {
            RenderArgs a{scene,     spp,      seconds, target_error, width,   height,
                         max_depth, seed,     backend, device,       threads, integrator,
                         sampler,   progress, cancel,  filtered,     layers};
            BatchResult r = run(a);
            const int w = r.image.width;
            const int h = r.image.height;
            py::dict out;
            out["image"] = image_array(std::move(r.image));
            out["variance"] = plane_array(std::move(r.variance), w, h);
            if (filtered) {
                out["filtered"] = image_array(std::move(r.filtered));
            }
            py::dict planes;
            for (ExrChannel& c : r.layers) {
                planes[py::str(c.name)] = plane_array(std::move(c.values), w, h);
            }
            out["layers"] = planes;
            out["spp"] = r.spp;
            out["seconds"] = r.seconds;
            out["estimate"] = r.estimate;
            out["cancelled"] = r.cancelled != 0;
            out["samples_dropped"] = r.samples_dropped;
            return out;
        },
        py::arg("scene"), py::arg("spp") = 0, py::arg("seconds") = 0.0,
        py::arg("target_error") = 0.0, py::arg("width") = 0, py::arg("height") = 0,
        py::arg("max_depth") = 0, py::arg("seed") = default_seed, py::arg("backend") = "cpu",
        py::arg("device") = 0, py::arg("threads") = 0, py::arg("integrator") = "",
        py::arg("sampler") = "", py::arg("progress") = py::none(),
        py::arg("cancel") = static_cast<CancelToken*>(nullptr), py::arg("filtered") = false,
        py::arg("layers") = std::vector<std::string>(), render_doc);

    m.def(
        "write_image",
        [](const std::string& path,
           const py::array_t<float, py::array::c_style | py::array::forcecast>& image,
           float exposure, const std::string& view) {
            Image picture = image_from_array(image);
            ViewTransform transform;
            try {
                transform = parse_view_transform(view);
            } catch (const std::invalid_argument& e) {
                throw py::value_error(e.what());
            }
            py::gil_scoped_release release;
            if (is_exr_path(path)) {
                write_exr(path, picture, {}, ExrPrecision::Float);
            } else {
                write_image(path, picture, exposure, transform);
            }
        },
        py::arg("path"), py::arg("image"), py::arg("exposure") = 1.0f, py::arg("view") = "standard",
        "Writes a height x width x 3 image: .png (tone-mapped sRGB through view, 'standard' or "
        "'filmic', after exposure), .pfm or .exr (linear float). The file is whole or not there.");
}
