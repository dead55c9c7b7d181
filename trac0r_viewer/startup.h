// What trac0r_viewer and trac0r_mpi do before they render: check the
// command line, load the scene, make the renderer on the backend asked for,
// and turn whatever went wrong into one message and an exit code.
#ifndef TRAC0R_VIEWER_STARTUP_H
#define TRAC0R_VIEWER_STARTUP_H

#include "options.h"

#include "trac0r/backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"

#include <exception>
#include <memory>
#include <string>

namespace trac0r_viewer {

class SlowStep;

// Where --filter puts the unfiltered image of output `path`: FILE.raw.EXT
// beside FILE.EXT.
std::string raw_output_path(const std::string& path);

// Checks combinations of flags that each parse fine alone (UsageError),
// and, where `writes_outputs`, that every --output can be written.
void check_options(const Options& o, bool writes_outputs = true);

// The scene file (or the built-in scene) with the command line's overrides.
trac0r::Scene load_scene(const Options& o);

// The backend called `name` ("cpu" or "opencl"), or an exception saying
// why it cannot be had. The window's B key uses it as it is: no fallback.
std::unique_ptr<trac0r::Backend> backend_named(const std::string& name, const Options& o);

// The requested backend. Without an OpenCL device, --backend opencl falls
// back to the CPU and says so; an explicit --device insists (an error), and
// a program that fails to build is always an error (its log is printed).
std::unique_ptr<trac0r::Backend> make_backend(const Options& o);

// --verbose's account of the scene, structure, backend and program.
void print_verbose(trac0r::Renderer& r, const Options& o);

// --list-devices. Returns the exit code.
int list_devices();

// The message (without the program's name) and exit code of an error: 2
// for the command line, 1 for everything else.
struct Failure {
    int code;
    std::string message;
};

class Startup {
  public:
    // One that `speaks` prints the slow steps' notices, --verbose and the
    // warnings; trac0r_mpi's ranks but the first do not.
    explicit Startup(bool speaks = true);

    // check_options, then --max-input-mb. A process that writes no outputs
    // (trac0r_mpi's ranks but the first) leaves out their checks.
    void prepare(const Options& options, bool writes_outputs = true);
    // Loads the scene: kept, for make_renderer.
    const trac0r::Scene& load(const Options& options);
    // A renderer of the loaded scene (the window makes one per backend).
    std::unique_ptr<trac0r::Renderer> make_renderer(const Options& options);
    // What to say of an exception thrown by the steps above or the render:
    // an out-of-memory error names what the step in hand needed memory for.
    Failure failure(std::exception_ptr error) const;

  private:
    std::unique_ptr<SlowStep> announce(const std::string& what, bool at_once) const;

    bool speaks_;
    bool warned_dark_ = false;
    trac0r::Scene scene_;
    std::string memory_user_ = "the scene file and its meshes, while loading: a smaller mesh";
};

}  // namespace trac0r_viewer

#endif
