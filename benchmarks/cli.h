// Shared by the benchmark programs' command lines: the usage error, an
// integer with its allowed range, and main's exit codes (2 for the command
// line, 1 for everything else), as trac0r_viewer has them.
#ifndef TRAC0R_BENCHMARKS_CLI_H
#define TRAC0R_BENCHMARKS_CLI_H

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

namespace trac0r_bench {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// text as an integer in [lo, hi], or a UsageError naming flag.
inline long parse_long(const std::string& flag, const std::string& text, long lo, long hi) {
    std::size_t used = 0;
    long v = 0;
    try {
        v = std::stol(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || v < lo || v > hi) {
        throw UsageError(flag + ": expected an integer in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got '" + text + "'");
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

}  // namespace trac0r_bench

#endif
