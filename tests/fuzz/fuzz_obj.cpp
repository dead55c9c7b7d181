// Fuzzes the OBJ mesh reader and its checker: the input is written to a
// file (the reader takes a path) and loaded as a mesh shape.
#include "trac0r/scene_loader.h"
#include "trac0r/shape.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string path = "/tmp/trac0r_fuzz_obj_" + std::to_string(getpid()) + ".obj";
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
        return 0;
    }
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    try {
        trac0r::load_obj_mesh(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0);
    } catch (const std::runtime_error&) {
        // SceneError and the like: the documented answer to a bad mesh
    }
    return 0;
}
