#include "options.h"

#include "trac0r/input_checks.h"
#include "trac0r/renderer.h"

#include <cerrno>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <string>

namespace trac0r_viewer {

namespace {
const char* current_program_name = "trac0r_viewer";
}  // namespace

const char* program_name() { return current_program_name; }

void set_program_name(const char* name) { current_program_name = name; }

const char* key_help_text() {
    return R"(  W A S D            move forward, left, back, right
  Q / E              move down / up (also Ctrl / Space)
  Shift              move five times faster
  right mouse drag   look around
  mouse wheel        field of view (zoom)
  F1                 debug overlay: AABBs, timings, camera, pixel under the mouse
  P                  screenshot: the window as a timestamped PNG and the render
                     as a PFM beside it, in the current directory
  B                  switch backend, CPU <-> OpenCL
  R                  restart accumulation
  + / -              exposure up / down
  H                  this help
  Esc                quit
)";
}

const char* usage_text() {
    static const std::string text = std::string(R"(Usage: trac0r_viewer [SCENE.json] [options]

A real-time Monte Carlo path tracer. Without SCENE.json it renders the
built-in scene: the thesis' Cornell box (scenes/cornell.json). Without
--headless it opens a window that refines the image until you quit.
An option's value may follow it or an '=' (--spp 64, --spp=64).

Rendering:
  --backend cpu|opencl   backend (default cpu)
  --device N             OpenCL device index (see --list-devices)
  --list-devices         print the OpenCL platforms and devices, then exit
  --width W --height H   override the scene's resolution
  --spp N                stop after N samples per pixel (window: pause there;
                         at most 16777216, where every render stops: a
                         pixel's sample count is a float)
  --seconds S            stop after S seconds of rendering (window: pause there)
  --seed N               random seed (default 1); same seed, same image
  --max-depth D          maximum path length in vertices (default: the scene's)
  --threads N            CPU threads (default: all)
  --accel flat|bvh|auto  acceleration structure (default auto)
  --integrator nee|naive next-event estimation with MIS (default), or the
                         thesis' algorithm
  --sampler sobol|random Owen-scrambled Sobol points, stratified (default),
                         or the thesis' xorshift1024* numbers
  --target-error E       stop when the estimated relative MSE (no reference
                         needed: from each pixel's sample variance) reaches E,
                         e.g. 0.01; with --spp or --seconds, whichever first
                         (window: pause there)
  --exposure X           multiply radiance by X before tone mapping (PNG, window)
  --verbose              each mesh (triangles, bounds, material, smooth ones),
                         backend, device, feature mask and what was left out

Output:
  -o, --output FILE      save the result: .png (tone-mapped sRGB), .pfm or .exr
                         (linear float); may be repeated (e.g. both a .png and
                         a .exr); in the window, saved when it closes
  --exr-layers LIST      with --headless, add to each .exr output the layers a
                         denoiser or compositor reads: albedo, normal, depth,
                         variance (comma-separated), or all
  --headless             no window; with --output a batch render with a
                         progress bar on stderr (default --spp 64 when
                         neither --seconds nor --target-error is given)
  --benchmark N          render N frames, print one JSON line of timings, exit;
                         in the window (no vsync, no overlay) or with --headless
  --replay FILE          window: play the scripted input events in FILE
  --max-input-mb N       largest scene, mesh or replay file read, in MB
                         (default 4000)
  -h, --help             this text
  --version              the version and whether OpenCL is built in

Window keys and mouse:
)") + key_help_text() + R"(
Examples:
  trac0r_viewer
  trac0r_viewer scenes/cornell.json --width 400 --height 300 --backend opencl
  trac0r_viewer --headless --spp 64 --output cornell.png
  trac0r_viewer scenes/cornell_diffuse.json --headless --seconds 30 --output d.pfm
  trac0r_viewer --headless --benchmark 10
)";
    return text.c_str();
}

namespace {

long parse_integer(const std::string& flag, const std::string& text, long min, long max) {
    long value = 0;
    if (!trac0r::parse_decimal(text, &value) || value < min || value > max) {
        throw UsageError(flag + ": expected an integer in [" + std::to_string(min) + ", " +
                         std::to_string(max) + "], got '" + text + "'");
    }
    return value;
}

double parse_positive(const std::string& flag, const std::string& text) {
    double value = 0.0;
    if (!trac0r::parse_decimal(text, &value) || !(value > 0.0)) {
        throw UsageError(flag + ": expected a positive number, got '" + text + "'");
    }
    return value;
}

std::uint64_t parse_seed(const std::string& flag, const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
    if (!trac0r::is_decimal_number(text) || text[0] == '-' || *end != '\0' || errno != 0) {
        throw UsageError(flag + ": expected a non-negative 64-bit integer, got '" + text + "'");
    }
    return static_cast<std::uint64_t>(value);
}

std::string parse_choice(const std::string& flag, const std::string& text,
                         const std::string& choices) {
    const std::string padded = "|" + choices + "|";
    if (text.empty() || padded.find("|" + text + "|") == std::string::npos) {
        throw UsageError(flag + ": expected one of " + choices + ", got '" + text + "'");
    }
    return text;
}

// --exr-layers: a comma-separated list of albedo, normal, depth, variance,
// or all.
trac0r::ExrLayerChoice parse_exr_layers(const std::string& flag, const std::string& text) {
    trac0r::ExrLayerChoice c;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string name =
            text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (name == "albedo" || name == "all") {
            c.albedo = true;
        }
        if (name == "normal" || name == "all") {
            c.normal = true;
        }
        if (name == "depth" || name == "all") {
            c.depth = true;
        }
        if (name == "variance" || name == "all") {
            c.variance = true;
        }
        if (name != "albedo" && name != "normal" && name != "depth" && name != "variance" &&
            name != "all") {
            throw UsageError(flag +
                             ": expected a comma-separated list of albedo, normal, depth and "
                             "variance, or all, got '" +
                             text + "'");
        }
        if (comma == std::string::npos) {
            return c;
        }
        start = comma + 1;
    }
}

}  // namespace

Options parse_options(int argc, const char* const* argv) {
    Options o;
    using Setter = std::function<void(const std::string&, const std::string&)>;
    const std::map<std::string, Setter> with_value = {
        {"--backend", [&](auto f, auto v) { o.backend = parse_choice(f, v, "cpu|opencl"); }},
        {"--device", [&](auto f, auto v) { o.device = (int)parse_integer(f, v, 0, 1023); }},
        {"--width", [&](auto f, auto v) { o.width = (int)parse_integer(f, v, 1, 16384); }},
        {"--height", [&](auto f, auto v) { o.height = (int)parse_integer(f, v, 1, 16384); }},
        {"--spp",
         [&](auto f, auto v) { o.spp = parse_integer(f, v, 1, trac0r::Renderer::max_frames); }},
        {"--seconds", [&](auto f, auto v) { o.seconds = parse_positive(f, v); }},
        {"--output", [&](auto, auto v) { o.outputs.push_back(v); }},
        {"--benchmark",
         [&](auto f, auto v) { o.benchmark_frames = parse_integer(f, v, 1, 1000000); }},
        {"--seed", [&](auto f, auto v) { o.seed = parse_seed(f, v); }},
        {"--max-depth", [&](auto f, auto v) { o.max_depth = (int)parse_integer(f, v, 1, 100000); }},
        {"--threads", [&](auto f, auto v) { o.threads = (int)parse_integer(f, v, 1, 1024); }},
        {"--accel", [&](auto f, auto v) { o.accel = parse_choice(f, v, "flat|bvh|auto"); }},
        {"--integrator", [&](auto f, auto v) { o.integrator = parse_choice(f, v, "naive|nee"); }},
        {"--sampler", [&](auto f, auto v) { o.sampler = parse_choice(f, v, "random|sobol"); }},
        {"--target-error", [&](auto f, auto v) { o.target_error = parse_positive(f, v); }},
        {"--exposure", [&](auto f, auto v) { o.exposure = (float)parse_positive(f, v); }},
        {"--exr-layers", [&](auto f, auto v) { o.exr_layers = parse_exr_layers(f, v); }},
        {"--replay", [&](auto, auto v) { o.replay_path = v; }},
        {"--max-input-mb",
         [&](auto f, auto v) { o.max_input_mb = parse_integer(f, v, 1, 1L << 30); }},
    };
    const std::map<std::string, bool*> switches = {
        {"--headless", &o.headless}, {"--verbose", &o.verbose}, {"--list-devices", &o.list_devices},
        {"--help", &o.help},         {"--version", &o.version}, {"-h", &o.help}};
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        // --flag=value is --flag value; -o is --output.
        std::string attached;
        bool has_attached = false;
        const std::size_t equals = arg.find('=');
        if (arg.compare(0, 2, "--") == 0 && equals != std::string::npos) {
            attached = arg.substr(equals + 1);
            arg = arg.substr(0, equals);
            has_attached = true;
            if (switches.count(arg) != 0) {
                throw UsageError(arg + ": takes no value, got '" + attached + "'");
            }
            if (with_value.count(arg) != 0 && attached.empty()) {
                throw UsageError(arg + ": expected a value after '='");
            }
        }
        if (arg == "-o") {
            arg = "--output";
        }
        // Every option but --output (which may name several files) at most
        // once: a second value would silently replace the first.
        if ((switches.count(arg) != 0 || with_value.count(arg) != 0) &&
            !o.given.insert(arg == "-h" ? "--help" : arg).second && arg != "--output") {
            throw UsageError(arg + ": given more than once");
        }
        const auto sw = switches.find(arg);
        if (sw != switches.end()) {
            *sw->second = true;
            continue;
        }
        const auto setter = with_value.find(arg);
        if (setter != with_value.end() && has_attached) {
            setter->second(arg, attached);
            continue;
        }
        if (setter != with_value.end()) {
            if (i + 1 >= argc) {
                throw UsageError(arg + ": expected a value after it");
            }
            const std::string value = argv[i + 1];
            if (value.size() > 2 && value.compare(0, 2, "--") == 0) {
                throw UsageError(arg + ": expected a value after it, got the option " + value);
            }
            setter->second(arg, argv[++i]);
            continue;
        }
        if (arg.size() > 1 && arg[0] == '-') {
            throw UsageError(arg + ": unknown option (see --help)");
        }
        if (!o.scene_path.empty()) {
            throw UsageError("'" + arg + "': only one scene file may be given (already have '" +
                             o.scene_path + "')");
        }
        o.scene_path = arg;
    }
    return o;
}

trac0r::PackOptions pack_options(const Options& options) {
    trac0r::PackOptions pack;
    pack.accel = trac0r::parse_accel(options.accel);
    pack.integrator = trac0r::parse_integrator(options.integrator);
    pack.sampler = trac0r::parse_sampler(options.sampler);
    return pack;
}

}  // namespace trac0r_viewer
