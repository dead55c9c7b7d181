// Names of enum values ("glass", "bvh", "nee"): one table per enum serves
// both directions, to_string and parsing, so that a name cannot be added to
// one and not to the other.
#ifndef TRAC0R_ENUM_NAMES_H
#define TRAC0R_ENUM_NAMES_H

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r {

template <typename Enum>
struct EnumName {
    Enum value;
    const char* name;
};

// The name of `value` in `table`, or `fallback` where the table lacks it.
template <typename Enum, std::size_t N>
const char* enum_name(const EnumName<Enum> (&table)[N], Enum value, const char* fallback) {
    for (const EnumName<Enum>& entry : table) {
        if (entry.value == value) {
            return entry.name;
        }
    }
    return fallback;
}

// Every name of `table`, in its order.
template <typename Enum, std::size_t N>
std::vector<std::string> enum_names(const EnumName<Enum> (&table)[N]) {
    std::vector<std::string> names;
    for (const EnumName<Enum>& entry : table) {
        names.push_back(entry.name);
    }
    return names;
}

// "a, b or c".
inline std::string one_of_text(const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        text += (i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ")) + names[i];
    }
    return text;
}

// The value named `name` in `table`. Throws std::invalid_argument
// "unknown WHAT 'NAME' (expected a, b or c)" where no entry has that name.
template <typename Enum, std::size_t N>
Enum enum_value(const EnumName<Enum> (&table)[N], const std::string& name, const char* what) {
    for (const EnumName<Enum>& entry : table) {
        if (name == entry.name) {
            return entry.value;
        }
    }
    throw std::invalid_argument("unknown " + std::string(what) + " '" + name + "' (expected " +
                                one_of_text(enum_names(table)) + ")");
}

}  // namespace trac0r

#endif
