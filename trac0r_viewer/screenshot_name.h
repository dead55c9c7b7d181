// Where the window's screenshots go: a timestamped name in the working
// directory that no earlier screenshot has.
#ifndef TRAC0R_VIEWER_SCREENSHOT_NAME_H
#define TRAC0R_VIEWER_SCREENSHOT_NAME_H

#include <string>

namespace trac0r_viewer {

// "/dir/trac0r-20250101-120000-123": the working directory and the local
// time to the millisecond, so that screenshots sort by time; a name whose
// .png or .pfm exists already (two in one millisecond, a script's) gets
// "-2", "-3", ... Without the extension.
std::string unused_screenshot_base();

}  // namespace trac0r_viewer

#endif
