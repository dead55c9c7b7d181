#include "trac0r/input_checks.h"

#include "trac0r/output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace trac0r {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Advances *at past the digits from there to end; returns how many.
std::size_t skip_digits(const char** at, const char* end) {
    const char* start = *at;
    while (*at < end && is_digit(**at)) {
        ++*at;
    }
    return static_cast<std::size_t>(*at - start);
}

}  // namespace

bool is_decimal_number(const char* begin, const char* end) {
    const char* at = begin;
    if (at < end && *at == '-') {
        ++at;
    }
    std::size_t digits = skip_digits(&at, end);
    if (at < end && *at == '.') {
        ++at;
        digits += skip_digits(&at, end);
    }
    if (digits == 0) {
        return false;
    }
    if (at < end && (*at == 'e' || *at == 'E')) {
        ++at;
        if (at < end && (*at == '+' || *at == '-')) {
            ++at;
        }
        if (skip_digits(&at, end) == 0) {
            return false;
        }
    }
    return at == end;
}

bool is_decimal_number(const std::string& text) {
    return is_decimal_number(text.data(), text.data() + text.size());
}

bool parse_decimal(const std::string& text, long* value) {
    errno = 0;
    char* end = nullptr;
    *value = std::strtol(text.c_str(), &end, 10);
    return is_decimal_number(text) && *end == '\0' && errno == 0;
}

bool parse_decimal(const std::string& text, double* value) {
    errno = 0;
    char* end = nullptr;
    *value = std::strtod(text.c_str(), &end);
    return is_decimal_number(text) && *end == '\0' && errno == 0 && std::isfinite(*value);
}

std::string printable(const std::string& text, std::size_t max_length) {
    // Built a unit at a time, a unit being one character (all the bytes of
    // a UTF-8 sequence) or one escape, so the cut never splits either.
    std::string out;
    std::size_t fits_with_dots = 0;
    std::size_t at = 0;
    while (at < text.size()) {
        const unsigned char lead = static_cast<unsigned char>(text[at]);
        std::size_t length = 1;
        while (at + length < text.size() &&
               (static_cast<unsigned char>(text[at + length]) & 0xC0) == 0x80) {
            ++length;  // continuation bytes belong to the character before
        }
        // C0 controls, DEL, and C1 controls (U+0080 to U+009F: C2 80 to C2 9F)
        // are escaped byte by byte; anything else passes as it is.
        const bool c1 =
            lead == 0xC2 && length == 2 && static_cast<unsigned char>(text[at + 1]) <= 0x9F;
        std::string unit;
        if (lead < 0x20 || lead == 0x7F || c1) {
            const char* const hex = "0123456789abcdef";
            for (std::size_t k = 0; k < (c1 ? 2u : 1u); ++k) {
                const unsigned char u = static_cast<unsigned char>(text[at + k]);
                unit += "\\x";
                unit += hex[u >> 4];
                unit += hex[u & 15];
            }
            length = c1 ? 2 : 1;
        } else {
            unit = text.substr(at, length);
        }
        out += unit;
        at += length;
        if (out.size() + 3 <= max_length) {
            fits_with_dots = out.size();  // the longest prefix "..." may follow
        }
        if (out.size() > max_length) {
            return out.substr(0, fits_with_dots) + "...";
        }
    }
    return out;
}

std::string unwritable_reason(const std::string& path) {
    // An existing file the user may not write is refused, although the
    // rename that replaces it would succeed.
    if (!path.empty() && !is_directory(path) && access(path.c_str(), F_OK) == 0 &&
        access(path.c_str(), W_OK) != 0) {
        return "exists and is not writable";
    }
    return output_file_problem(path);
}

bool is_directory(const std::string& path) {
    struct stat info;
    return stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode);
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat sa;
    struct stat sb;
    return a == b || (stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 &&
                      sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino);
}

bool has_extension(const std::string& path, const std::string& suffix) {
    if (path.size() < suffix.size()) {
        return false;
    }
    return std::equal(
        suffix.begin(), suffix.end(), path.end() - static_cast<long>(suffix.size()),
        [](char lower, char c) { return std::tolower(static_cast<unsigned char>(c)) == lower; });
}

}  // namespace trac0r
