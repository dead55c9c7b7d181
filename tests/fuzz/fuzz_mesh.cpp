// Fuzzes the PLY and glTF 2.0 mesh loader (assimp, then trac0r's checks and
// material mapping): each input is written to a file as a .ply, a .glb
// and a .gltf in turn (the loader takes a path and picks the format by its
// extension) and loaded with the file's materials. Loading or a
// std::runtime_error (the loader's documented answer) is correct; anything
// else is a finding. The files lie in a directory of their own, where a
// .gltf's relative buffer URI finds nothing.
//
// assimp 5.2's readers crash on some malformed files, inside libassimp (a
// heap overrun in the PLY reader, a null dereference in the glTF one,
// whose input is in tests/fuzz/findings/). The loader runs them in a
// child process of its own (trac0r/isolated_call.h), so such a crash is
// the loader's clear error, as a hang is after the import's time limit
// (set here below libFuzzer's -timeout for three loads). The child's
// sanitizer report, if any, is in the log, but it does not end the
// fuzzer: what the fuzzer finds is in trac0r's own code, the parent.
#include "trac0r/shape.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace {

const std::string& directory() {
    static const std::string dir = [] {
        std::string d = "/tmp/trac0r_fuzz_mesh_XXXXXX";
        if (mkdtemp(&d[0]) == nullptr) {
            std::perror("fuzz_mesh: mkdtemp");
            std::abort();
        }
        return d;
    }();
    return dir;
}

void load_as(const std::uint8_t* data, std::size_t size, const char* extension) {
    const std::string path = directory() + "/mesh" + extension;
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
        return;
    }
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    try {
        trac0r::load_mesh_parts(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true,
                                true);
    } catch (const std::runtime_error&) {
        // a file that cannot be read or a material that cannot be mapped
    }
    std::remove(path.c_str());
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    trac0r::set_mesh_import_time_limit(3.0);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    load_as(data, size, ".ply");
    load_as(data, size, ".glb");
    load_as(data, size, ".gltf");
    return 0;
}
