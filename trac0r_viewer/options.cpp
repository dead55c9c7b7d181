#include "options.h"

#include "cli/command_line.h"

#include "trac0r/renderer.h"

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
  Shift / Alt        move five times faster / slower
  right mouse drag   look around
  mouse wheel        zoom (field of view; orthographic: view height)
  C                  print the camera as a scene file's "camera" block (stdout
                     and the window); --camera FILE loads it
  Home               back to the scene's camera
  [ / ]              close / open the lens' aperture (depth of field)
  G, middle click    focus on the surface under the mouse
  F1                 debug overlay: AABBs, timings, camera, the pixel under the
                     mouse
  P                  screenshot: the window as a timestamped PNG and the render
                     as a PFM beside it, in the current directory
  B                  switch backend, CPU <-> OpenCL
  R                  restart accumulation
  + / -              exposure up / down
  V                  view: standard (clip at 1) / filmic (AgX)
  F                  display filter on / off (edge-preserving; the accumulation
                     is untouched)
  H                  this help
  Esc                quit
)";
}

const char* key_help_short_text() {
    return R"(W A S D     move (Shift/Alt: faster/slower)
Q / E       down / up
C / Home    print / reset the camera
right drag  look around
wheel       zoom
F1          overlay
F           filter on / off
P           screenshot
B           CPU <-> OpenCL
R           restart
+ / -       exposure
V           standard / filmic
H           help   Esc quit)";
}

namespace {

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

const char* const viewer_description =
    "A real-time Monte Carlo path tracer. Without SCENE.json it renders the built-in scene: the "
    "thesis' Cornell box (scenes/cornell.json). Without --headless it opens a window that "
    "refines the image until you quit. An option's value may follow it or an '=' (--spp 64, "
    "--spp=64).";

// Every option at most once but --output, which may name several files:
// a second value would silently replace the first.
void define_options(trac0r_cli::CommandLine& cl, Options& o) {
    cl.positional("SCENE.json", &o.scene_path,
                  "the scene (default: the built-in Cornell box), or a model file (.obj, .ply, "
                  ".gltf, .glb) to see on its own: framed by the camera, under a white sky");
    cl.group("Rendering");
    cl.choice("--backend", &o.backend, "cpu|opencl", "backend (default cpu)");
    cl.integer("--device", &o.device, 0, 1023, "OpenCL device index (see --list-devices)");
    cl.flag("--list-devices", &o.list_devices, "print the OpenCL platforms and devices, then exit");
    cl.integer("--width", &o.width, 1, 16384, "override the scene's width", "W");
    cl.integer("--height", &o.height, 1, 16384, "override the scene's height", "H");
    cl.integer("--spp", &o.spp, 1, trac0r::Renderer::max_frames,
               "stop after N samples per pixel (window: pause there; at most 16777216, where "
               "every render stops: a pixel's sample count is a float)");
    cl.positive("--seconds", &o.seconds, "stop after S seconds of rendering (window: pause there)",
                "S");
    cl.value("--seed", "N", "random seed (default 1); same seed, same image",
             [&o](const std::string& v) { o.seed = trac0r_cli::parse_u64("--seed", v); });
    cl.value("--camera", "FILE",
             "a camera block over the scene's camera: the JSON the window's C key prints, "
             "{\"camera\": {...}}, or the block alone (docs/viewer.md)",
             [&o](const std::string& v) { o.camera_path = v; });
    cl.integer("--max-depth", &o.max_depth, 1, 100000,
               "maximum path length in vertices (default: the scene's)", "D");
    cl.integer("--threads", &o.threads, 1, 1024, "CPU threads (default: all)");
    cl.choice("--accel", &o.accel, "flat|bvh|auto", "acceleration structure (default auto)");
    cl.choice("--integrator", &o.integrator, "naive|nee|bdpt",
              "next-event estimation with MIS (nee, default), bidirectional path tracing "
              "(bdpt: caustics; at most 64 vertices a path; docs/bdpt.md), or the thesis' "
              "algorithm");
    cl.choice("--sampler", &o.sampler, "random|sobol",
              "Owen-scrambled Sobol points, stratified (sobol, default), or the thesis' "
              "xorshift1024* numbers");
    cl.choice("--light-sampler", &o.light_sampler, "power|tree|auto",
              "how next-event estimation and BDPT's light samples pick a light: by power "
              "alone, or by a light tree "
              "(power, distance, orientation); auto (default): the tree from 32 lights with a "
              "position");
    cl.positive("--target-error", &o.target_error,
                "stop when the estimated relative MSE (no reference needed: from each pixel's "
                "sample variance) reaches E, e.g. 0.01; with --spp or --seconds, whichever "
                "first (window: pause there)",
                "E");
    cl.positive("--exposure", &o.exposure,
                "multiply radiance by X before tone mapping (PNG, window)");
    cl.choice("--view", &o.view, "standard|filmic",
              "how PNG outputs and the window show radiance: each channel clipped at 1 "
              "(standard), or AgX, highlights rolled off to white as in Blender (filmic); "
              "default: the scene's render.view, else standard; never changes .pfm or .exr");
    cl.flag("--print-scene", &o.print_scene,
            "with a model file, print the scene made around it as scene-file JSON (to start "
            "editing from) and exit");
    cl.flag("--strict", &o.strict,
            "refuse a model file with a defect that other importers pass over (a face of two "
            "vertices, a usemtl naming no material, a texture that is not there), which is "
            "otherwise one warning line a kind");
    cl.flag("--verbose", &o.verbose,
            "each mesh (triangles, bounds, material, smooth ones), backend, device, feature "
            "mask and what was left out");
    cl.group("Output");
    cl.repeated("-o,--output", "FILE",
                "save the result: .png (tone-mapped sRGB), .pfm or .exr (linear float); may be "
                "repeated (e.g. both a .png and a .exr); in the window, saved when it closes",
                [&o](const std::string& v) { o.outputs.push_back(v); });
    cl.value("--exr-layers", "LIST",
             "with --headless, add to each .exr output the layers a denoiser or compositor "
             "reads: albedo, normal, depth, variance (comma-separated), or all",
             [&o](const std::string& v) { o.exr_layers = parse_exr_layers("--exr-layers", v); });
    cl.flag("--exr-half", &o.exr_half,
            "store .exr outputs (and their layers) as 16-bit half floats: half the size; "
            "values beyond 65504 are clamped to it");
    cl.flag("--filter", &o.filter,
            "with --headless, each --output FILE.EXT holds the image after the "
            "edge-preserving filter (docs/filter.md) and FILE.raw.EXT beside it the "
            "unfiltered accumulation; in the window, it starts with the display filter on (F)");
    cl.flag("--headless", &o.headless,
            "no window; with --output a batch render with a progress bar on stderr (default "
            "--spp 64 when neither --seconds nor --target-error is given)");
    cl.integer("--benchmark", &o.benchmark_frames, 1, 1000000,
               "render N frames, print one JSON line of timings, exit; in the window (no "
               "vsync, no overlay) or with --headless");
    cl.text("--replay", &o.replay_path, "window: play the scripted input events in FILE");
    cl.integer("--max-input-mb", &o.max_input_mb, 1, 1L << 30,
               "largest scene, mesh or replay file read, in MB (default 4000)");
    cl.help_group("Other");
}

std::string viewer_footer() {
    return std::string("Window keys and mouse:\n") + key_help_text() + R"(
Examples:
  trac0r_viewer
  trac0r_viewer scenes/cornell.json --width 400 --height 300 --backend opencl
  trac0r_viewer --headless --spp 64 --output cornell.png
  trac0r_viewer scenes/cornell_diffuse.json --headless --seconds 30 -o d.pfm
  trac0r_viewer --headless --benchmark 10
)";
}

}  // namespace

std::string help_text(const std::string& usage, const std::string& description,
                      const std::string& footer) {
    Options o;
    trac0r_cli::CommandLine cl(program_name(), usage, description, 26);
    define_options(cl, o);
    cl.app().footer(footer);
    return cl.help();
}

std::string usage_text() {
    return help_text("trac0r_viewer [SCENE.json] [options]", viewer_description, viewer_footer());
}

Options parse_options(int argc, const char* const* argv) {
    Options o;
    trac0r_cli::CommandLine cl(program_name(), "", "");
    define_options(cl, o);
    cl.on_extra([&o](const std::string& arg) {
        throw UsageError("'" + arg + "': only one scene file may be given (already have '" +
                         o.scene_path + "')");
    });
    const trac0r_cli::CommandLine::Outcome outcome = cl.parse(argc, argv);
    o.help = outcome == trac0r_cli::CommandLine::Outcome::help;
    o.version = outcome == trac0r_cli::CommandLine::Outcome::version;
    o.given = cl.given();
    return o;
}

trac0r::PackOptions pack_options(const Options& options) {
    trac0r::PackOptions pack;
    pack.accel = trac0r::parse_accel(options.accel);
    pack.integrator = trac0r::parse_integrator(options.integrator);
    pack.sampler = trac0r::parse_sampler(options.sampler);
    pack.light_sampler = trac0r::parse_light_sampler(options.light_sampler);
    return pack;
}

}  // namespace trac0r_viewer
