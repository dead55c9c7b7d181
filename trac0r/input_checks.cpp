#include "trac0r/input_checks.h"

#include <sys/stat.h>
#include <unistd.h>

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

std::string printable(const std::string& text, std::size_t max_length) {
    std::string out;
    for (const char c : text) {
        if (out.size() >= max_length) {
            return out.substr(0, max_length > 3 ? max_length - 3 : 0) + "...";
        }
        const unsigned char u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) {
            const char* const hex = "0123456789abcdef";
            out += "\\x";
            out += hex[u >> 4];
            out += hex[u & 15];
        } else {
            out += c;
        }
    }
    return out;
}

std::string unwritable_reason(const std::string& path) {
    struct stat info;
    if (stat(path.c_str(), &info) == 0) {
        if (S_ISDIR(info.st_mode)) {
            return "is a directory";
        }
        return access(path.c_str(), W_OK) == 0 ? "" : "exists and is not writable";
    }
    const std::string::size_type slash = path.find_last_of('/');
    const std::string dir =
        slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
    if (stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
        return "directory " + dir + " does not exist";
    }
    return access(dir.c_str(), W_OK | X_OK) == 0 ? "" : "directory " + dir + " is not writable";
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat sa;
    struct stat sb;
    return a == b || (stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 &&
                      sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino);
}

}  // namespace trac0r
