// The library's version (CMake's project version) and how it was built.
#ifndef TRAC0R_VERSION_H
#define TRAC0R_VERSION_H

#include <string>

namespace trac0r {

// "0.1.0".
const char* version();

// The version and the build's optional parts, one line:
// "trac0r 0.1.0 (OpenCL backend: yes)".
std::string version_line();

}  // namespace trac0r

#endif
