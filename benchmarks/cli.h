// Shared by the benchmark programs' command lines: the usage error, an
// integer or a number with its allowed range, the values after a flag, and
// main's exit codes (2 for the command line, 1 for everything else), as
// trac0r_viewer has them.
#ifndef TRAC0R_BENCHMARKS_CLI_H
#define TRAC0R_BENCHMARKS_CLI_H

#include "trac0r/input_checks.h"

#include <cstdio>
#include <exception>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r_bench {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// text as an integer in [lo, hi], or a UsageError naming flag. The whole
// text, written in decimal (trac0r::is_decimal_number, as trac0r_viewer).
inline long parse_long(const std::string& flag, const std::string& text, long lo, long hi) {
    long v = 0;
    if (!trac0r::parse_decimal(text, &v) || v < lo || v > hi) {
        throw UsageError(flag + ": expected an integer in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got '" + text + "'");
    }
    return v;
}

// text as a finite number in [lo, hi], or a UsageError naming flag; the
// whole text, as parse_long.
inline double parse_number(const std::string& flag, const std::string& text, double lo, double hi) {
    double v = 0.0;
    if (!trac0r::parse_decimal(text, &v) || v < lo || v > hi) {
        char range[64];
        std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
        throw UsageError(flag + ": expected a number in " + range + ", got '" + text + "'");
    }
    return v;
}

// The value after flag argv[*i] (advancing *i past it), or a UsageError
// naming flag.
inline std::string flag_value(int argc, char** argv, int* i, const std::string& flag) {
    if (*i + 1 >= argc) {
        throw UsageError(flag + ": expected a value");
    }
    return std::string(argv[++*i]);
}

// The two integers in [1, max] after flag argv[*i] (`--size W H`),
// advancing *i past them, or a UsageError naming flag.
inline void size_values(int argc, char** argv, int* i, const std::string& flag, long max,
                        int* width, int* height) {
    if (*i + 2 >= argc) {
        throw UsageError(flag + ": expected two values, W H");
    }
    *width = static_cast<int>(parse_long(flag + " W", argv[*i + 1], 1, max));
    *height = static_cast<int>(parse_long(flag + " H", argv[*i + 2], 1, max));
    *i += 2;
}

inline bool is_help(const std::string& arg) { return arg == "-h" || arg == "--help"; }

// A UsageError for the first option ("--" and a name) given twice, but
// those in `repeatable`: a second value would silently replace the first.
// Every value of these programs is a number, a name or a path, never an
// option's spelling, so the arguments are read as they stand.
inline void check_given_once(int argc, char** argv, const std::set<std::string>& repeatable = {}) {
    std::set<std::string> given;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.size() > 2 && a.compare(0, 2, "--") == 0 && repeatable.count(a) == 0 &&
            !given.insert(a).second) {
            throw UsageError(a + ": given more than once");
        }
    }
}

// text split at its commas, every part kept (an empty one too).
inline std::vector<std::string> split_commas(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) {
            return parts;
        }
        start = comma + 1;
    }
}

// Runs body (which returns the exit code) and turns its exceptions into one
// line on stderr, prefixed with the program's name.
template <typename Body>
int run_main(const char* program, Body body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 1;
    }
}

// main for a program whose parse(argc, argv, options) returns false for
// --help: prints usage then (exit 0), or runs run(options), under run_main.
template <typename Options, typename Parse, typename Run>
int parse_and_run(const char* program, const char* usage, int argc, char** argv, Parse parse,
                  Run run) {
    return run_main(program, [&] {
        Options o;
        if (!parse(argc, argv, o)) {
            std::fputs(usage, stdout);
            return 0;
        }
        return run(o);
    });
}

}  // namespace trac0r_bench

#endif
