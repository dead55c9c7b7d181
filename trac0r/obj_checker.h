// The OBJ checker: the checks of an OBJ file's text that tinyobjloader
// leaves out, one "path:line: ..." message per mistake, before
// tinyobjloader reads the same text (load_obj_mesh, shape.h).
#ifndef TRAC0R_OBJ_CHECKER_H
#define TRAC0R_OBJ_CHECKER_H

#include <string>

namespace trac0r {

// The text of the OBJ file `path` once every v and f line is checked, with
// its comments and the statements the mesh does not use blanked out
// (obj_checker.cpp says what and why). Throws std::runtime_error
// "path:line: ..." at the first mistake, or "path: cannot read OBJ mesh:
// ..." when the file cannot be read.
std::string checked_obj_text(const std::string& path);

}  // namespace trac0r

#endif
