#include "trac0r/refused_value.h"

namespace trac0r {

using namespace json_diagnostics;

void fail_refused(const json& object, const Location& at, const SceneValueError& e) {
    if (!e.field().empty() && object.is_object() && object.contains(e.field())) {
        const Location field_at = at.key(e.field());
        if (!e.expected().empty()) {
            fail_expected(field_at, e.expected(), object.at(e.field()));
        }
        fail(field_at, e.problem());
    }
    fail(at, e.problem());
}

}  // namespace trac0r
