// Values on the command lines of trac0r_viewer, trac0r_mpi and the
// benchmark programs: each parsed whole (no leading space, sign or hex
// that strtol would take), or a UsageError that names the flag, the range
// or names expected, and what was given.
#ifndef TRAC0R_CLI_PARSE_H
#define TRAC0R_CLI_PARSE_H

#include "trac0r/input_checks.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace trac0r_cli {

// A bad command line: the message names the flag and what was expected.
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// text as an integer in [lo, hi], or a UsageError naming flag. The whole
// text, written in decimal (trac0r::is_decimal_number).
inline long parse_long(const std::string& flag, const std::string& text, long lo, long hi) {
    long v = 0;
    if (!trac0r::parse_decimal(text, &v) || v < lo || v > hi) {
        throw UsageError(flag + ": expected an integer in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got '" + text + "'");
    }
    return v;
}

// text as a finite number in [lo, hi], or a UsageError naming flag.
inline double parse_number(const std::string& flag, const std::string& text, double lo, double hi) {
    double v = 0.0;
    if (!trac0r::parse_decimal(text, &v) || v < lo || v > hi) {
        char range[64];
        std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
        throw UsageError(flag + ": expected a number in " + range + ", got '" + text + "'");
    }
    return v;
}

// text as a finite number above 0, or a UsageError naming flag.
inline double parse_positive(const std::string& flag, const std::string& text) {
    double v = 0.0;
    if (!trac0r::parse_decimal(text, &v) || !(v > 0.0)) {
        throw UsageError(flag + ": expected a positive number, got '" + text + "'");
    }
    return v;
}

// text as a non-negative 64-bit integer in decimal, or a UsageError.
inline std::uint64_t parse_u64(const std::string& flag, const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (!trac0r::is_decimal_number(text) || text[0] == '-' || *end != '\0' || errno != 0) {
        throw UsageError(flag + ": expected a non-negative 64-bit integer, got '" + text + "'");
    }
    return static_cast<std::uint64_t>(v);
}

// text if it is one of `choices` ("a|b|c"), else a UsageError.
inline std::string parse_choice(const std::string& flag, const std::string& text,
                                const std::string& choices) {
    if (text.empty() || ("|" + choices + "|").find("|" + text + "|") == std::string::npos) {
        throw UsageError(flag + ": expected one of " + choices + ", got '" + text + "'");
    }
    return text;
}

}  // namespace trac0r_cli

#endif
