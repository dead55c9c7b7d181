#include "trac0r/version.h"

namespace trac0r {

const char* version() { return TRAC0R_VERSION; }

std::string version_line() {
#ifdef TRAC0R_HAVE_OPENCL
    const char* opencl = "yes";
#else
    const char* opencl = "no";
#endif
    return std::string("trac0r ") + version() + " (OpenCL backend: " + opencl + ")";
}

}  // namespace trac0r
