// The command line of trac0r_viewer (docs/viewer.md).
#ifndef TRAC0R_VIEWER_OPTIONS_H
#define TRAC0R_VIEWER_OPTIONS_H

#include "cli/parse.h"

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "trac0r/guides.h"
#include "trac0r/packed_scene.h"
#include "trac0r/renderer.h"

namespace trac0r_viewer {

struct Options {
    std::string scene_path;  // empty: the built-in thesis scene
    std::string camera_path;  // --camera: a camera block over the scene's; empty: none
    std::string backend = "cpu";
    int device = -1;
    int width = 0;  // 0: the scene's
    int height = 0;
    long spp = 0;                      // 0: not given
    double seconds = 0.0;              // 0: not given
    std::vector<std::string> outputs;  // --output, may be repeated
    bool headless = false;
    long benchmark_frames = 0;
    std::uint64_t seed = trac0r::default_seed;
    int max_depth = 0;  // 0: the scene's
    int threads = 0;    // 0: OpenMP's default
    // The library's defaults (trac0r::PackOptions).
    std::string accel = trac0r::to_string(trac0r::PackOptions().accel);
    std::string integrator = trac0r::to_string(trac0r::PackOptions().integrator);
    std::string sampler = trac0r::to_string(trac0r::PackOptions().sampler);
    std::string light_sampler = trac0r::to_string(trac0r::PackOptions().light_sampler);
    double target_error = 0.0;
    float exposure = 1.0f;
    std::string view;                   // --view standard|filmic; empty: the scene's render.view
    trac0r::ExrLayerChoice exr_layers;  // --exr-layers
    bool exr_half = false;              // --exr-half
    bool filter = false;                // --filter
    std::string replay_path;            // --replay: scripted window input (replay.h)
    long max_input_mb = 0;              // --max-input-mb; 0: the library's limit (4000)
    bool verbose = false;
    bool strict = false;
    bool print_scene = false;  // --print-scene: the scene around a model file, as JSON  // --strict: a model file's defects are errors (trac0r::LoadOptions)
    bool list_devices = false;
    bool help = false;
    bool version = false;
    std::set<std::string> given;  // the options on the command line (-h as --help)
};

// A bad command line: the message names the flag and what was expected.
using UsageError = trac0r_cli::UsageError;

// The options (help and version as flags: the caller prints them).
Options parse_options(int argc, const char* const* argv);

// --accel, --integrator, --sampler and --light-sampler as the library's
// packing options.
trac0r::PackOptions pack_options(const Options& options);

// The name messages begin with: "trac0r_viewer", or what set_program_name
// set (trac0r_mpi sets its own before it starts).
const char* program_name();
void set_program_name(const char* name);
// --help of trac0r_viewer, generated from the options.
std::string usage_text();
// --help of a program with the viewer's options (trac0r_mpi): `usage`
// after "Usage: ", then `description`, the options and `footer`.
std::string help_text(const std::string& usage, const std::string& description,
                      const std::string& footer);
// The window's keys and mouse, one per line: in --help and behind H.
const char* key_help_text();
// The same, shorter, for small windows.
const char* key_help_short_text();

}  // namespace trac0r_viewer

#endif
