// Fuzzes the window's replay-script parser (--replay FILE).
#include "replay.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        trac0r_viewer::parse_replay(text, "fuzz.replay");
    } catch (const trac0r_viewer::ReplayError&) {
        // the documented answer to a bad script
    }
    return 0;
}
