// Rendering without a window: batch renders and the benchmark.
#ifndef TRAC0R_VIEWER_HEADLESS_H
#define TRAC0R_VIEWER_HEADLESS_H

#include "cluster.h"
#include "options.h"

#include "trac0r/renderer.h"

#include <functional>

namespace trac0r_viewer {

// Renders until --spp, --seconds or --target-error, with a progress bar on
// stderr, and saves --output. Split across `cluster`'s processes, each
// renders its share of the frames, all stop after the same round, and the
// first merges the accumulators, prints and writes. Returns the exit code.
int run_batch(trac0r::Renderer& renderer, const Options& options, Cluster& cluster);

// Renders --benchmark N frames and prints one JSON line on stdout. Each
// frame's time includes `after_frame` (the window shows the frame there);
// when it returns false the benchmark stops, prints no figures, returns 1.
int run_benchmark(trac0r::Renderer& renderer, const Options& options,
                  const std::function<bool()>& after_frame = nullptr);

// Writes every --output file of the image, each .png through `view`;
// each .exr with the --exr-layers, made from `renderer`'s scene and
// camera and `accumulator` (where both are given).
void save_outputs(const trac0r::Image& image, const Options& options, trac0r::ViewTransform view,
                  const trac0r::Renderer* renderer = nullptr,
                  const std::vector<trac0r::kernel::AccumPixel>* accumulator = nullptr);

}  // namespace trac0r_viewer

#endif
