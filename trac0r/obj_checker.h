// The OBJ checker: the checks of an OBJ file's text that tinyobjloader
// leaves out, one "path:line: ..." message per mistake, before
// tinyobjloader reads the same text (load_obj_mesh, shape.h).
#ifndef TRAC0R_OBJ_CHECKER_H
#define TRAC0R_OBJ_CHECKER_H

#include "trac0r/model_defects.h"

#include <string>
#include <vector>

namespace trac0r {

// The text of the OBJ file `path` once every v and f line is checked, with
// its comments and the statements the mesh does not use blanked out
// (obj_checker.cpp says what and why). Throws std::runtime_error
// "path:line: ..." at the first mistake, or "path: cannot read OBJ mesh:
// ..." when the file cannot be read.
std::string checked_obj_text(const std::string& path);

// A name an OBJ statement gives (a usemtl material, an mtllib file), and
// the line it is on.
struct ObjNameRef {
    std::string name;
    long line;
};

// checked_obj_text's text, and the names its usemtl and mtllib statements
// give, in order (they stay in the text for tinyobjloader).
struct CheckedObj {
    std::string text;
    std::vector<ObjNameRef> materials;  // usemtl
    std::vector<ObjNameRef> libraries;  // mtllib
};
// `defects`: where a face of fewer than 3 distinct vertices is reported
// and skipped (blanked); nullptr: a face of fewer than 3 vertices is an
// error, one of 3 repeating a vertex is kept.
CheckedObj check_obj(const std::string& path, ModelDefects* defects = nullptr);

// What stands for a blank within a material name in checked text (so that
// tinyobjloader reads "usemtl Hard Shiny Plastic" as one name), and for
// the name of a newmtl that has none; and the name of a usemtl without
// one (which no newmtl has).
const char material_name_mark = '\x1f';
const char no_material_mark = '\x1e';

// A material name as tinyobjloader read it from checked text, as the file
// wrote it (marks back to blanks; "" for a newmtl without a name).
std::string decode_material_name(std::string name);

}  // namespace trac0r

#endif
