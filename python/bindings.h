// What the Python module's files share (module.cpp, scene_class.cpp).
#ifndef TRAC0R_PYTHON_BINDINGS_H
#define TRAC0R_PYTHON_BINDINGS_H

#include <pybind11/pybind11.h>

namespace trac0r_python {

// ValueError "NAME: expected an integer in [1, HIGHEST], got VALUE" unless
// value is in [1, highest].
void check_size(const char* name, long value, long highest);

// Adds the class trac0r.Scene to the module.
void bind_scene(pybind11::module_& m);

}  // namespace trac0r_python

#endif
