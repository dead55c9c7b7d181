// A SceneBuilder's refusal (SceneValueError) as a scene file's error: at
// the JSON key it names, with the file's own text of the value.
#ifndef TRAC0R_REFUSED_VALUE_H
#define TRAC0R_REFUSED_VALUE_H

#include "trac0r/json_diagnostics.h"
#include "trac0r/scene_builder.h"

namespace trac0r {

// Throws a JsonError at `object`'s key e.field() where the object has it
// ("expected ..., got <the file's value>" for a range), else at `at`.
[[noreturn]] void fail_refused(const json_diagnostics::json& object,
                               const json_diagnostics::Location& at, const SceneValueError& e);

}  // namespace trac0r

#endif
