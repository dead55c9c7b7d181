// Tone-maps a linear PFM to PNG exactly as trac0r_viewer --output does.
//
//   build/benchmarks/tonemap IN.pfm OUT.png [EXPOSURE]
#include "trac0r/image_io.h"

#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: tonemap IN.pfm OUT.png [EXPOSURE]\n");
        return 2;
    }
    const float exposure = argc == 4 ? static_cast<float>(std::atof(argv[3])) : 1.0f;
    if (!(exposure > 0.0f)) {
        std::fprintf(stderr, "tonemap: EXPOSURE: expected a positive number, got '%s'\n", argv[3]);
        return 2;
    }
    try {
        trac0r::write_png(argv[2], trac0r::read_pfm(argv[1]), exposure);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tonemap: %s\n", e.what());
        return 1;
    }
    return 0;
}
