// The window as a whole: an interactive session (navigation, keys, the
// debug overlay, screenshots, --replay), or --benchmark N shown in it.
#ifndef TRAC0R_VIEWER_WINDOW_SESSION_H
#define TRAC0R_VIEWER_WINDOW_SESSION_H

#include "options.h"
#include "window_worker.h"

#include "trac0r/renderer.h"

#include <functional>
#include <memory>
#include <string>

namespace trac0r_viewer {

using RendererFactory = std::function<std::unique_ptr<trac0r::Renderer>()>;

// Reads --replay and the font, opens a window for the render size (a
// smaller one on small screens; resizable), and only then makes the
// renderer, so that a missing display or font is reported before the scene
// is packed or an OpenCL program built. Returns the exit code; throws
// WindowError (no display), ReplayError and the renderer's errors.
int run_window(const Options& options, const std::string& title,
               const trac0r::RenderSettings& render, const RendererFactory& make_renderer,
               const RenderWorker::BackendFactory& make_backend);

}  // namespace trac0r_viewer

#endif
