// Shared by the benchmark programs' command lines (parsed with
// cli/command_line.h, as trac0r_viewer's): lists of names, and main's exit
// codes (2 for the command line, 1 for everything else).
#ifndef TRAC0R_BENCHMARKS_CLI_H
#define TRAC0R_BENCHMARKS_CLI_H

#include "cli/command_line.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace trac0r_bench {

using trac0r_cli::parse_long;
using trac0r_cli::parse_number;
using trac0r_cli::UsageError;

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

}  // namespace trac0r_bench

#endif
