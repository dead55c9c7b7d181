// Rendering without a window: batch renders and the benchmark.
#ifndef TRAC0R_VIEWER_HEADLESS_H
#define TRAC0R_VIEWER_HEADLESS_H

#include "options.h"

#include "trac0r/renderer.h"

namespace trac0r_viewer {

// Renders until --spp or --seconds, with a progress bar on stderr, and
// saves --output. Returns the exit code.
int run_batch(trac0r::Renderer& renderer, const Options& options);

// Renders --benchmark N frames and prints one JSON line on stdout.
int run_benchmark(trac0r::Renderer& renderer, const Options& options);

}  // namespace trac0r_viewer

#endif
