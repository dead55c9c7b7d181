#include "trac0r/obj_text_checker.h"

#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/obj_checker.h"
#include "trac0r/text_encoding.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace trac0r {

std::string ObjTextChecker::checked_text() {
    // Only a regular file within the input size limit (input_file.h).
    std::string text = read_input_file(path_, kind_);
    // UTF-16 with a byte-order mark (Windows tools write it; assimp and
    // Blender read it): the same text in UTF-8.
    text = utf8_of_utf16(text);
    // tinyobjloader would read such a file as no statements at all.
    const std::size_t nul = text.find('\0');
    if (nul != std::string::npos) {
        const long line = 1 + std::count(text.begin(), text.begin() + nul, '\n');
        throw std::runtime_error(path_ + ":" + std::to_string(line) + ": a NUL byte: this is no " +
                                 format_ + " text (a binary file, or UTF-16: save it as UTF-8)");
    }
    // A UTF-8 byte-order mark, which some Windows tools write first.
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) {
        text.replace(0, 3, 3, ' ');
    }
    char* at = &text[0];
    char* const end = at + text.size();
    base_ = at;
    while (at < end) {
        // One statement: a line, and the lines after it while each
        // ends in '\' (a continuation; not in a comment, which ends
        // with its line): the '\' and the line break become blanks, so
        // that tinyobjloader, which knows no continuations, reads one
        // line. A message names the line its word is on (line_of).
        char* const statement = at;
        const long first_line = line_number_ + 1;
        breaks_.clear();
        char* line_end = nullptr;
        for (;;) {
            char* const line_start = at;
            // memchr, not a loop: each byte of a large mesh is looked
            // at here, for '#' and as a word.
            line_end = static_cast<char*>(std::memchr(at, '\n', end - at));
            line_end = line_end != nullptr ? line_end : end;
            char* const cr = static_cast<char*>(std::memchr(at, '\r', line_end - at));
            line_end = cr != nullptr ? cr : line_end;
            ++line_number_;
            at = line_end;
            if (at < end && *at == '\r') {
                ++at;
            }
            if (at < end && *at == '\n') {
                ++at;
            }
            if (line_end == line_start || line_end[-1] != '\\' || line_end == end ||
                std::memchr(line_start, '#', line_end - line_start) != nullptr) {
                break;
            }
            std::fill(line_end - 1, at, ' ');
            breaks_.push_back(line_end - 1);
        }
        const long last_line = line_number_;
        line_number_ = first_line;
        check_line(statement, line_end);
        line_number_ = last_line;
    }
    finish();
    // The rewrites, from the last: earlier offsets stay valid.
    for (auto e = edits_.rbegin(); e != edits_.rend(); ++e) {
        text.replace(e->offset, e->length, e->with);
    }
    return text;
}

void ObjTextChecker::check_line(char* begin, char* end) {
    if (char* const hash = static_cast<char*>(std::memchr(begin, '#', end - begin))) {
        std::fill(hash, end, ' ');
        end = hash;
    }
    statement_end_ = end;
    // tinyobjloader separates words by spaces and tabs only: other
    // blanks become spaces, so that it reads the words checked here.
    std::replace_if(
        begin, end, [](char c) { return c == '\v' || c == '\f'; }, ' ');
    words_.clear();
    const char* at = begin;
    while (at < end) {
        while (at < end && is_blank(*at)) {
            ++at;
        }
        const char* start = at;
        while (at < end && !is_blank(*at)) {
            ++at;
        }
        if (at > start) {
            words_.push_back({start, at});
        }
    }
    if (!words_.empty()) {
        check_statement(begin, end);
    }
}

bool ObjTextChecker::is_word(const Word& w, const char* text) {
    return static_cast<std::size_t>(w.end - w.begin) == std::strlen(text) &&
           std::equal(w.begin, w.end, text);
}

std::string ObjTextChecker::shown(const Word& w) { return printable(w.text(), 40); }

long ObjTextChecker::line_of(const char* p) const {
    return line_number_ + static_cast<long>(std::count_if(breaks_.begin(), breaks_.end(),
                                                          [p](const char* b) { return b < p; }));
}

void ObjTextChecker::fail_at(long line, const std::string& message) const {
    throw std::runtime_error(path_ + ":" + std::to_string(line) + ": " + message);
}

// A defect at `line`: reported (lenient), else the error it names.
void ObjTextChecker::report_or_fail(long line, const std::string& what, const std::string& done) {
    if (defects_ == nullptr) {
        fail_at(line, what);
    }
    defects_->report(path_, line, what, done);  // throws when strict
}

// Whether a decimal number is finite as a float, and as tinyobjloader
// reads it (mantissa times 5^exponent times 2^exponent in double: 0e500
// is 0 times infinity, NaN; 400 digits before the point overflow the
// mantissa): at most 39 significant digits before the point and an
// exponent within +-300, then finite when converted. Only numbers with
// an exponent or 39 significant digits are converted (FLT_MAX is 3.4e38).
bool ObjTextChecker::finite_in_float(const Word& w) {
    const char* const exponent =
        std::find_if(w.begin, w.end, [](char c) { return c == 'e' || c == 'E'; });
    const char* const point = std::find(w.begin, exponent, '.');
    const char* first_digit = *w.begin == '-' ? w.begin + 1 : w.begin;
    while (first_digit < point && *first_digit == '0') {
        ++first_digit;
    }
    const long integer_digits = point - first_digit;
    if (integer_digits > 39) {
        return false;
    }
    if (exponent == w.end) {
        return integer_digits <= 38 || std::isfinite(std::strtof(w.begin, nullptr));
    }
    const char* digit = exponent + 1;
    digit += digit < w.end && (*digit == '+' || *digit == '-') ? 1 : 0;
    long value = 0;
    for (; digit < w.end && value <= 300; ++digit) {
        value = value * 10 + (*digit - '0');
    }
    return value <= 300 && std::isfinite(std::strtof(w.begin, nullptr));
}

// Each word after the first a decimal number finite in float; `what`
// names one in the message.
void ObjTextChecker::check_numbers(const std::string& what) {
    for (std::size_t k = 1; k < words_.size(); ++k) {
        Word& w = words_[k];
        // A leading '+', which some exporters write: a blank for
        // tinyobjloader, the number checked without it ('+-1' stays
        // refused).
        if (w.end - w.begin > 1 && *w.begin == '+' && w.begin[1] != '+' && w.begin[1] != '-') {
            *const_cast<char*>(w.begin) = ' ';
            ++w.begin;
        }
        if (!is_decimal_number(w.begin, w.end)) {
            fail_at(line_of(w.begin),
                    "expected " + what + " as a decimal number, got '" + shown(w) + "'");
        }
        if (!finite_in_float(w)) {
            fail_at(line_of(w.begin), "expected " + what +
                                          " finite in float (below "
                                          "3.4e38, an exponent within +-300), got '" +
                                          shown(w) + "'");
        }
    }
}

// The name after the statement's keyword: the rest of the statement,
// trimmed, as the file wrote it. In the text, its blanks become
// material_name_mark, so that tinyobjloader reads it as one word
// (decode_material_name turns them back), and what follows the
// keyword becomes one blank and the name (tinyobjloader's newmtl takes
// all that follows its keyword and one blank, blanks and all).
std::string ObjTextChecker::name_after_keyword() {
    std::string name(words_[1].begin, words_.back().end);
    std::string marked = name;
    std::replace_if(
        marked.begin(), marked.end(), [](char c) { return is_blank(c); }, material_name_mark);
    edits_.push_back({static_cast<std::size_t>(words_[0].end - base_),
                      static_cast<std::size_t>(statement_end_ - words_[0].end), " " + marked});
    std::replace(name.begin(), name.end(), '\t', ' ');
    return name;
}

void ObjTextChecker::rename(const char* from, const char* to, char name) {
    edit(from, static_cast<std::size_t>(to - from), std::string(" ") + name);
}

void ObjTextChecker::edit(const char* from, std::size_t length, const std::string& with) {
    edits_.push_back({static_cast<std::size_t>(from - base_), length, with});
}

}  // namespace trac0r
