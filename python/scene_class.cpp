// The Python class trac0r.Scene (docs/python.md): its render settings, the
// materials' names, and what can be added to it: meshes from NumPy arrays,
// and materials, shapes, lights and the environment with the scene
// format's keys (SceneBuilder through the loader's readers).
#include "trac0r/mesh_arrays.h"
#include "trac0r/scene.h"
#include "trac0r/scene_loader.h"
#include "bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace trac0r;

namespace trac0r_python {

namespace {

// Triangle indices: an array of integers in [0, 2^32), each checked.
std::vector<std::uint32_t> index_array(const py::object& value) {
    const py::array a = py::array::ensure(value);
    if (!a || (a.dtype().kind() != 'i' && a.dtype().kind() != 'u')) {
        throw py::value_error("add_mesh: indices: expected an array of integers");
    }
    const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> wide(a);
    std::vector<std::uint32_t> out;
    out.reserve(static_cast<std::size_t>(wide.size()));
    const std::int64_t* data = wide.data();
    for (py::ssize_t i = 0; i < wide.size(); ++i) {
        if (data[i] < 0 || data[i] > 0xffffffffLL) {
            throw py::value_error("add_mesh: indices: triangle " + std::to_string(i / 3) +
                                  " has vertex " + std::to_string(data[i]) +
                                  ", expected an index from 0");
        }
        out.push_back(static_cast<std::uint32_t>(data[i]));
    }
    return out;
}

// An array argument of numbers as a flat vector of `T` (C-contiguous; NumPy
// converts the number type).
template <typename T>
std::vector<T> flat(const py::object& value, const char* name) {
    if (value.is_none()) {
        return {};
    }
    py::array_t<T, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(value);
    } catch (const py::error_already_set&) {
        a = py::array_t<T, py::array::c_style | py::array::forcecast>();
    }
    if (!a) {
        throw py::value_error(std::string("add_mesh: ") + name + ": expected an array of numbers");
    }
    return std::vector<T>(a.data(), a.data() + a.size());
}

// A dict of the scene format as JSON text (NumPy arrays and numbers as
// lists and numbers), for the loader to read.
std::string json_text(const py::object& value) {
    const py::module_ json = py::module_::import("json");
    const py::object to_list = py::cpp_function([](const py::object& o) -> py::object {
        if (py::hasattr(o, "tolist")) {
            return o.attr("tolist")();
        }
        throw py::type_error("expected numbers, lists, strings and booleans, got " +
                             py::str(py::type::of(o)).cast<std::string>());
    });
    // NaN and infinity are no JSON: a ValueError before the loader.
    return json.attr("dumps")(value, py::arg("default") = to_list, py::arg("allow_nan") = false)
        .cast<std::string>();
}

// Adds one object of the scene format to the scene (add_scene_object); its
// mistakes are ValueErrors.
void add_object(Scene& scene, const char* kind, const py::object& description,
                const std::string& call, const std::string& base_dir) {
    const std::string text = json_text(description);
    try {
        add_scene_object(scene, kind, text, call, base_dir);
    } catch (const SceneError& e) {
        throw py::value_error(e.what());
    }
}

}  // namespace

void bind_scene(py::module_& m) {
    py::class_<Scene>(m, "Scene", "A scene: camera, render settings, materials, shapes, lights.")
        .def_property(
            "width", [](const Scene& s) { return s.render.width; },
            [](Scene& s, int w) {
                check_size("width", w, 16384);
                s.render.width = w;
            })
        .def_property(
            "height", [](const Scene& s) { return s.render.height; },
            [](Scene& s, int h) {
                check_size("height", h, 16384);
                s.render.height = h;
            })
        .def_property(
            "max_depth", [](const Scene& s) { return s.render.max_depth; },
            [](Scene& s, int d) {
                check_size("max_depth", d, 100000);
                s.render.max_depth = d;
            })
        .def_property_readonly("triangle_count", &Scene::triangle_count)
        .def_property_readonly("shape_count", [](const Scene& s) { return s.shapes.size(); })
        .def_property_readonly(
            "materials",
            [](const Scene& s) {
                std::vector<std::string> names;
                for (const Material& mat : s.materials) {
                    names.push_back(mat.name);
                }
                return names;
            },
            "the materials' names")
        .def_readonly("warnings", &Scene::warnings, "what loading passed over in model files")
        .def(
            "add_mesh",
            [](Scene& s, const py::object& positions, const py::object& indices,
               const py::object& normals, const py::object& uvs, const std::string& material,
               std::array<double, 3> position, std::array<float, 3> orientation,
               std::array<float, 3> scale) {
                MeshArrays mesh;
                mesh.positions = flat<float>(positions, "positions");
                mesh.indices = index_array(indices);
                mesh.normals = flat<float>(normals, "normals");
                mesh.uvs = flat<float>(uvs, "uvs");
                MeshPlacement place;
                place.material = material;
                place.position = glm::dvec3(position[0], position[1], position[2]);
                place.orientation = glm::vec3(orientation[0], orientation[1], orientation[2]);
                place.scale = glm::vec3(scale[0], scale[1], scale[2]);
                try {
                    add_mesh(s, mesh, place);
                } catch (const std::invalid_argument& e) {
                    throw py::value_error(e.what());
                }
            },
            py::arg("positions"), py::arg("indices"), py::arg("normals") = py::none(),
            py::arg("uvs") = py::none(), py::arg("material") = "",
            py::arg("position") = std::array<double, 3>{0.0, 0.0, 0.0},
            py::arg("orientation") = std::array<float, 3>{0.0f, 0.0f, 0.0f},
            py::arg("scale") = std::array<float, 3>{1.0f, 1.0f, 1.0f},
            R"(Adds a triangle mesh from arrays: positions (n x 3), indices (m x 3, counter-
clockwise, into the positions), normals (n x 3, smooth shading) and uvs (n x 2),
placed as a scene file's mesh shape (position, orientation in radians, scale),
with the scene's material of that name (none: its 'default', else grey).)")
        .def(
            "add_material",
            [](Scene& s, const std::string& name, const std::string& type,
               const py::kwargs& params) {
                py::dict material(params);
                material["type"] = type;
                py::dict named;
                named[py::str(name)] = material;
                add_object(s, "material", named, "Scene.add_material", ".");
            },
            py::arg("name"), py::arg("type"),
            R"(Adds a material as the scene format's "materials" has it: a name, a type
(diffuse, glossy, glass, conductor, plastic, principled, emissive) and that
type's keys, e.g. add_material("red", "diffuse", color=(0.6, 0.05, 0.05)).
A mistake raises ValueError naming the key.)")
        .def(
            "add_shape",
            [](Scene& s, const std::string& type, const std::string& base_dir,
               const py::kwargs& params) {
                py::dict shape(params);
                shape["type"] = type;
                add_object(s, "shape", shape, "Scene.add_shape", base_dir);
            },
            py::arg("type"), py::arg("base_dir") = ".",
            R"(Adds a shape as the scene format's "shapes" has it: plane, box, icosphere or
mesh (a file, found from base_dir) with its keys, e.g.
add_shape("icosphere", material="red", position=(0, 0.3, 0), radius=0.2).
A mistake raises ValueError naming the key.)")
        .def(
            "add_light",
            [](Scene& s, const std::string& type, const py::kwargs& params) {
                py::dict light(params);
                light["type"] = type;
                add_object(s, "light", light, "Scene.add_light", ".");
            },
            py::arg("type"),
            R"(Adds a point, spot or sun light as the scene format's "lights" has it, e.g.
add_light("point", position=(0, 2, 0), intensity=5). A mistake raises ValueError.)")
        .def(
            "set_environment",
            [](Scene& s, const std::string& base_dir, const py::kwargs& params) {
                add_object(s, "environment", py::dict(params), "Scene.set_environment", base_dir);
            },
            py::arg("base_dir") = ".",
            R"(Sets the environment as the scene format's "environment" has it: color=(r, g, b),
or map="sky.hdr" (found from base_dir) with rotation; strength. A mistake raises
ValueError.)")
        .def(
            "set_camera",
            [](Scene& s, const py::object& camera) {
                const std::string text =
                    py::isinstance<py::str>(camera)
                        ? camera.cast<std::string>()
                        : py::module_::import("json").attr("dumps")(camera).cast<std::string>();
                s.camera = parse_camera_block(text, "<camera>", s.origin);
            },
            py::arg("camera"),
            R"(Replaces the scene's camera by a camera block of the scene format (a dict, or
its JSON text): position, direction, world_up, projection ("perspective" or
"orthographic"), vertical_fov or view_height, aperture_radius, focus_distance;
what the viewer's C key prints, as trac0r_viewer --camera reads it.)")
        .def("__repr__", [](const Scene& s) {
            return "<trac0r.Scene " + std::to_string(s.render.width) + "x" +
                   std::to_string(s.render.height) + ", " + std::to_string(s.shapes.size()) +
                   " shapes, " + std::to_string(s.triangle_count()) + " triangles>";
        });
}

}  // namespace trac0r_python
