// Fuzzes the scene loader: JSON text, as a scene file holds it. Mesh paths
// resolve in an empty directory, so a mutated "file" fails to open fast.
#include "trac0r/scene_loader.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        trac0r::parse_scene(text, "fuzz.json", "/nonexistent-trac0r-fuzz-dir");
    } catch (const trac0r::SceneError&) {
        // the documented answer to a bad scene
    }
    return 0;
}
