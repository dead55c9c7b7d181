// The MTL checker: the checks of a material library's text that
// tinyobjloader leaves out, one "path:line: ..." message per mistake,
// before tinyobjloader reads the same text (obj_mesh.cpp).
#ifndef TRAC0R_MTL_CHECKER_H
#define TRAC0R_MTL_CHECKER_H

#include "trac0r/model_defects.h"

#include <string>

namespace trac0r {

// The text of the MTL file `path` once its colours (Ka, Kd, Ks, Ke, Tf)
// and numbers (Ns, Ni, d, Tr, illum) are checked: decimal numbers, finite
// in float, three for a colour and one for a number. Throws std::runtime_error
// "path:line: ..." at the first mistake.
// Each material's name is the rest of its newmtl line (blanks and all,
// trimmed; decode_material_name), and a colour of one number is that
// number in all three channels, as the MTL format allows. `defects`: where
// a newmtl without a name is reported (the material cannot be named);
// nullptr: it is an error.
std::string checked_mtl_text(const std::string& path, ModelDefects* defects = nullptr);

}  // namespace trac0r

#endif
