// Rendering without a window: batch renders and the benchmark.
#ifndef TRAC0R_VIEWER_HEADLESS_H
#define TRAC0R_VIEWER_HEADLESS_H

#include "options.h"

#include "trac0r/batch.h"
#include "trac0r/render_cluster.h"
#include "trac0r/renderer.h"

#include <functional>

namespace trac0r_viewer {

// Renders until --spp, --seconds or --target-error (trac0r::render_batch),
// with a progress bar on stderr, and saves --output. Split across
// `cluster`'s processes, the first prints and writes. Returns the exit code.
int run_batch(trac0r::Renderer& renderer, const Options& options, trac0r::Cluster& cluster);

// Renders --benchmark N frames and prints one JSON line on stdout. Each
// frame's time includes `after_frame` (the window shows the frame there);
// when it returns false the benchmark stops, prints no figures, returns 1.
int run_benchmark(trac0r::Renderer& renderer, const Options& options,
                  const std::function<bool()>& after_frame = nullptr);

// What --filter and --exr-layers ask render_batch and batch_images for.
trac0r::BatchOptions image_options(const Options& options);

// Writes every --output file of the image, each .png through `view`;
// with a batch's `result`, each .exr with its layers, and with --filter its
// filtered image (the raw one beside it, raw_output_path).
void save_outputs(const trac0r::Image& image, const Options& options, trac0r::ViewTransform view,
                  const trac0r::BatchResult* result = nullptr);

}  // namespace trac0r_viewer

#endif
