// The OBJ checker (obj_checker.h): the checks that tinyobjloader leaves out.
#include "trac0r/obj_checker.h"

#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/text_encoding.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <vector>

namespace trac0r {

namespace {

// The OBJ checks that tinyobjloader leaves out: it reads "x", "nan" or a
// missing coordinate as 0, "3.5" as the index 3, a face of two vertices as
// nothing, an index past 2^31 as another index, and "0x1p0" as 0. Only v
// and f lines are checked (the only ones the mesh uses); each error is
// "path:line: ...". It accepts what exporters write that tinyobjloader
// does not: a '+' before a coordinate, and a line continued after a '\'. The checker also blanks
// comments out of the text, which tinyobjloader refuses after a face ("zero value for face index"),
// and then hands it the same text. Lines end in \n, \r\n or \r.
class ObjChecker {
  public:
    // mtl: the file is an MTL material library (checked_mtl_text).
    ObjChecker(const std::string& path, bool mtl, ModelDefects* defects = nullptr)
        : path_(path), mtl_(mtl), defects_(defects) {}

    // The usemtl and mtllib statements of the text checked, in order.
    const std::vector<ObjNameRef>& materials() const { return materials_; }
    const std::vector<ObjNameRef>& libraries() const { return libraries_; }

    // The file's text, its comments and unused statements blanked out,
    // once every line is checked.
    std::string checked_text() {
        // Only a regular file within the input size limit (input_file.h).
        std::string text = read_input_file(path_, mtl_ ? "MTL material library" : "OBJ mesh");
        // UTF-16 with a byte-order mark (Windows tools write it; assimp and
        // Blender read it): the same text in UTF-8.
        text = utf8_of_utf16(text);
        // tinyobjloader would read such a file as no statements at all.
        const std::size_t nul = text.find('\0');
        if (nul != std::string::npos) {
            const long line = 1 + std::count(text.begin(), text.begin() + nul, '\n');
            throw std::runtime_error(path_ + ":" + std::to_string(line) +
                                     ": a NUL byte: this is no " + (mtl_ ? "MTL" : "OBJ") +
                                     " text (a binary file, or UTF-16: save it as UTF-8)");
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
        check_referred(vertices_);
        check_referred(normals_);
        check_referred(texcoords_);
        // The rewrites, from the last: earlier offsets stay valid.
        for (auto e = edits_.rbegin(); e != edits_.rend(); ++e) {
            text.replace(e->offset, e->length, e->with);
        }
        return text;
    }

  private:
    struct Word {
        const char* begin;
        const char* end;
        std::string text() const { return std::string(begin, end); }
    };

    static bool is_blank(char c) { return c == ' ' || c == '\t'; }

    // The line `p` (in the statement being checked) is on.
    long line_of(const char* p) const {
        return line_number_ +
               static_cast<long>(std::count_if(breaks_.begin(), breaks_.end(),
                                               [p](const char* b) { return b < p; }));
    }

    [[noreturn]] void fail_at(long line, const std::string& message) const {
        throw std::runtime_error(path_ + ":" + std::to_string(line) + ": " + message);
    }

    // Whether [at, end) (what follows an "s") is one smoothing group as
    // tinyobjloader reads it: "off", or a number of at most 9 digits (0:
    // none). Another is blanked with the statements the mesh does not use
    // (its faces are flat).
    static bool is_smoothing_group(const char* at, const char* end) {
        while (at < end && is_blank(*at)) {
            ++at;
        }
        const char* word_end = at;
        while (word_end < end && !is_blank(*word_end) && *word_end != '\r') {
            ++word_end;
        }
        for (const char* rest = word_end; rest < end; ++rest) {
            if (!is_blank(*rest) && *rest != '\r') {
                return false;
            }
        }
        const std::size_t length = static_cast<std::size_t>(word_end - at);
        if (length == 3 && std::equal(at, word_end, "off")) {
            return true;
        }
        return length >= 1 && length <= 9 &&
               std::all_of(at, word_end, [](char c) { return c >= '0' && c <= '9'; });
    }

    // The line [begin, end), its comment (from '#') blanked out first.
    void check_line(char* begin, char* end) {
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
                if (words_.size() == 1 && !mtl_ && !is_keyword(words_[0], 'v') &&
                    !is_keyword(words_[0], 'f')) {
                    // A statement the mesh does not use: texture and normal
                    // vertices stay (faces may refer to them), everything
                    // else is blanked, so that tinyobjloader cannot refuse
                    // or misread a line, point or curve the mesh never uses.
                    if (is_word(words_[0], "vn") || is_word(words_[0], "vt") ||
                        is_word(words_[0], "usemtl") || is_word(words_[0], "mtllib")) {
                        whole_line_ = true;  // checked as a whole below
                        continue;
                    }
                    if (is_word(words_[0], "s") && is_smoothing_group(at, end)) {
                        return;  // kept as it is
                    }
                    std::fill(begin, end, ' ');
                    return;
                }
            }
        }
        if (words_.empty()) {
            return;
        }
        if (mtl_) {
            check_mtl_statement();
        } else if (whole_line_) {
            whole_line_ = false;
            if (is_word(words_[0], "vn")) {
                check_normal();
            } else if (is_word(words_[0], "vt")) {
                check_texcoord();
            } else {
                check_names();
            }
        } else if (is_keyword(words_[0], 'v')) {
            check_vertex();
        } else if (!check_face()) {
            std::fill(begin, end, ' ');  // a defect passed over: the face skipped
        }
    }

    // Whether a decimal number is finite as a float, and as tinyobjloader
    // reads it (mantissa times 5^exponent times 2^exponent in double: 0e500
    // is 0 times infinity, NaN; 400 digits before the point overflow the
    // mantissa): at most 39 significant digits before the point and an
    // exponent within +-300, then finite when converted. Only numbers with
    // an exponent or 39 significant digits are converted (FLT_MAX is 3.4e38).
    static bool finite_in_float(const Word& w) {
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

    static bool is_keyword(const Word& w, char keyword) {
        return w.end - w.begin == 1 && *w.begin == keyword;
    }

    static bool is_word(const Word& w, const char* text) {
        return static_cast<std::size_t>(w.end - w.begin) == std::strlen(text) &&
               std::equal(w.begin, w.end, text);
    }

    // The word as the message shows it: cut short, control bytes escaped.
    static std::string shown(const Word& w) { return printable(w.text(), 40); }

    // x y z, and optionally w, a colour (r g b), or both, each a decimal
    // number finite in float (one below float's smallest reads as 0,
    // which is fine).
    void check_vertex() {
        const std::size_t values = words_.size() - 1;
        if (values != 3 && values != 4 && values != 6 && values != 7) {
            fail_at(line_number_,
                    "expected a vertex as 'v x y z' (with an optional w, r g b, or both), got " +
                        std::to_string(values) + " values");
        }
        check_numbers("a vertex coordinate");
        ++vertices_.count;
    }

    // A vertex normal, 'vn x y z', each a decimal number finite in float.
    void check_normal() {
        const std::size_t values = words_.size() - 1;
        if (values != 3) {
            fail_at(line_number_,
                    "expected a normal as 'vn x y z', got " + std::to_string(values) + " values");
        }
        check_numbers("a normal component");
        ++normals_.count;
    }

    // vt u [v [w]]: finite numbers (w is not used).
    void check_texcoord() {
        const std::size_t values = words_.size() - 1;
        if (values < 1 || values > 3) {
            fail_at(line_number_, "expected a texture coordinate as 'vt u [v [w]]', got " +
                                      std::to_string(values) + " values");
        }
        check_numbers("a texture coordinate");
        ++texcoords_.count;
    }

    // usemtl NAME, or mtllib FILE...: each name recorded with its line.
    void check_names() {
        const bool library = is_word(words_[0], "mtllib");
        if (library && words_.size() < 2) {
            fail_at(line_number_, "expected 'mtllib FILE.mtl ...', got no file name");
        }
        if (!library) {
            // usemtl NAME: the rest of the line, trimmed, as Blender and
            // assimp read it (blanks and all; none: no material).
            if (words_.size() < 2) {
                if (defects_ == nullptr || defects_->strict()) {
                    fail_at(line_number_, "expected 'usemtl NAME', got no name");
                }
                defects_->report(path_, line_number_, "usemtl without a name",
                                 "its faces take the shape's material");
                rename(words_[0].end, words_.back().end, no_material_mark);
                return;
            }
            const long line = line_of(words_[1].begin);
            materials_.push_back({name_after_keyword(), line});
            return;
        }
        for (std::size_t k = 1; k < words_.size(); ++k) {
            (library ? libraries_ : materials_)
                .push_back({words_[k].text(), line_of(words_[k].begin)});
        }
    }

    // The name after the statement's keyword: the rest of the statement,
    // trimmed, as the file wrote it. In the text, its blanks become
    // material_name_mark, so that tinyobjloader reads it as one word
    // (decode_material_name turns them back), and what follows the
    // keyword becomes one blank and the name (tinyobjloader's newmtl takes
    // all that follows its keyword and one blank, blanks and all).
    std::string name_after_keyword() {
        std::string name(words_[1].begin, words_.back().end);
        std::string marked = name;
        std::replace_if(
            marked.begin(), marked.end(), [](char c) { return is_blank(c); }, material_name_mark);
        edits_.push_back({static_cast<std::size_t>(words_[0].end - base_),
                          static_cast<std::size_t>(statement_end_ - words_[0].end), " " + marked});
        std::replace(name.begin(), name.end(), '\t', ' ');
        return name;
    }

    // [from, to) of the text replaced by " " + name.
    void rename(const char* from, const char* to, char name) {
        edits_.push_back({static_cast<std::size_t>(from - base_),
                          static_cast<std::size_t>(to - from), std::string(" ") + name});
    }

    // In an MTL file: the colours (Ka, Kd, Ks, Ke, Tf: r g b) and the numbers (Ns, Ni, d, Tr,
    // illum) a material of the renderer is made from; other statements (newmtl, maps) are
    // tinyobjloader's.
    void check_mtl_statement() {
        static const char* const colours[] = {"Ka", "Kd", "Ks", "Ke", "Tf"};
        static const char* const numbers[] = {"Ns", "Ni", "d", "Tr", "illum"};
        const Word& key = words_[0];
        const auto is_one_of = [&](const char* const* list, std::size_t n) {
            return std::any_of(list, list + n, [&](const char* w) { return is_word(key, w); });
        };
        const std::size_t values = words_.size() - 1;
        if (is_word(key, "newmtl")) {
            // The name: the rest of the line, trimmed (tinyobjloader's
            // newmtl keeps its blanks, its usemtl only the first word).
            if (values == 0) {
                if (defects_ == nullptr || defects_->strict()) {
                    fail_at(line_number_, "expected 'newmtl NAME', got no name");
                }
                defects_->report(path_, line_number_, "newmtl without a name",
                                 "no usemtl can name it");
                rename(key.end, key.end, material_name_mark);
            } else {
                const long line = line_of(words_[1].begin);
                const std::string name = name_after_keyword();
                const auto first = newmtl_lines_.emplace(name, line);
                if (!first.second) {
                    // tinyobjloader's usemtl finds the first of the name.
                    report_or_fail(line,
                                   "newmtl '" + printable(name, 60) + "' again (first on line " +
                                       std::to_string(first.first->second) + ")",
                                   "the first is used");
                }
            }
            return;
        }
        if (is_one_of(colours, 5)) {
            // Three, or one for all three, as the MTL format allows
            // (tinyobjloader reads "Kd 0.5" as (0.5, 0, 0)).
            if (values != 3 && values != 1) {
                fail_at(line_number_, "expected '" + key.text() + " r g b', three numbers, got " +
                                          std::to_string(values) + " values");
            }
            check_numbers("a " + key.text() + " value");
            // Reflectances and transmission in [0, 1]; emission >= 0.
            const std::vector<std::string> v =
                ranged_values(0.0, is_word(key, "Ke") ? 1e30 : 1.0, false);
            if (values == 1) {
                edits_.push_back(
                    {static_cast<std::size_t>(words_[1].end - base_), 0, " " + v[0] + " " + v[0]});
            }
        } else if (is_one_of(numbers, 5)) {
            if (values != 1) {
                fail_at(line_number_, "expected '" + key.text() + " N', one number, got " +
                                          std::to_string(values) + " values");
            }
            check_numbers("a " + key.text() + " value");
            if (is_word(key, "d") || is_word(key, "Tr")) {
                ranged_values(0.0, 1.0, false);
            } else if (is_word(key, "Ns")) {
                ranged_values(0.0, 1000.0, false);  // the MTL format's range, as Blender clamps
            } else if (is_word(key, "illum")) {
                ranged_values(0.0, 10.0, true);
            }
        }
    }

    // A defect at `line`: reported (lenient), else the error it names.
    void report_or_fail(long line, const std::string& what, const std::string& done) {
        if (defects_ == nullptr) {
            fail_at(line, what);
        }
        defects_->report(path_, line, what, done);  // throws when strict
    }

    // The statement's values (checked numbers) within [lo, hi] (whole
    // numbers where `whole`): one outside is a defect, taken as the
    // nearest value within (its text rewritten for tinyobjloader; a
    // fraction of a whole number cut off, as tinyobjloader reads it).
    // Returns the values' texts as tinyobjloader will read them.
    std::vector<std::string> ranged_values(double lo, double hi, bool whole) {
        std::vector<std::string> out;
        for (std::size_t k = 1; k < words_.size(); ++k) {
            const Word& w = words_[k];
            std::string text = w.text();
            const double value = std::strtod(text.c_str(), nullptr);
            double taken = std::min(hi, std::max(lo, value));
            if (whole) {
                taken = std::trunc(taken);
            }
            if (taken != value) {
                char shown_value[32];
                std::snprintf(shown_value, sizeof shown_value, "%g", taken);
                char range[64];
                std::snprintf(range, sizeof range,
                              whole ? "a whole number from %g to %g" : "a number in [%g, %g]", lo,
                              hi);
                report_or_fail(line_of(w.begin),
                               words_[0].text() + " " + shown(w) + ": expected " + range,
                               std::string("taken as ") + shown_value);
                edits_.push_back({static_cast<std::size_t>(w.begin - base_),
                                  static_cast<std::size_t>(w.end - w.begin), shown_value});
                text = shown_value;
            }
            out.push_back(text);
        }
        return out;
    }

    // Each word after the first a decimal number finite in float; `what`
    // names one in the message.
    void check_numbers(const std::string& what) {
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

    // At least three vertex references v, v/vt, v//vn or v/vt/vn; v is an
    // integer, from 1 up or (relative) from -1 down, of a vertex the file
    // has.
    // Returns false for a face lenient loading skips (fewer than 3
    // distinct vertices, model_defects.h).
    bool check_face() {
        const std::size_t vertices = words_.size() - 1;
        if (vertices < 3 && defects_ != nullptr && !defects_->strict()) {
            defects_->report(path_, line_number_,
                             "a face of " + std::to_string(vertices) + " vertices", "skipped");
            return false;
        }
        if (vertices < 3 || vertices > max_face_vertices) {
            fail_at(line_number_, "expected a face of 3 to " + std::to_string(max_face_vertices) +
                                      " vertices, got " + std::to_string(vertices));
        }
        std::vector<long> corners;
        for (std::size_t k = 1; k < words_.size(); ++k) {
            const Word& w = words_[k];
            // v, v/vt, v//vn or v/vt/vn: each index present a non-zero
            // integer.
            const char* const slash1 = std::find(w.begin, w.end, '/');
            const char* const slash2 = slash1 == w.end ? w.end : std::find(slash1 + 1, w.end, '/');
            long index = 0;
            long normal = 0;    // 0: none
            long texcoord = 0;  // 0: none
            bool valid = parse_index(w.begin, slash1, &index);
            if (slash1 != w.end) {
                const bool has_vt = slash2 > slash1 + 1;
                valid = valid && (!has_vt || parse_index(slash1 + 1, slash2, &texcoord)) &&
                        (slash2 != w.end || has_vt) &&
                        (slash2 == w.end || parse_index(slash2 + 1, w.end, &normal));
            }
            if (!valid) {
                fail_at(line_of(w.begin),
                        "expected a face vertex as v, v/vt, v//vn or v/vt/vn, each "
                        "a non-zero integer, got '" +
                            shown(w) + "'");
            }
            refer(vertices_, index, w);
            refer(normals_, normal, w);
            refer(texcoords_, texcoord, w);
            corners.push_back(index < 0 ? vertices_.count + 1 + index : index);
        }
        std::sort(corners.begin(), corners.end());
        if (std::unique(corners.begin(), corners.end()) - corners.begin() < 3 &&
            defects_ != nullptr) {
            defects_->report(path_, line_number_, "a face of fewer than 3 distinct vertices",
                             "skipped");
            return false;
        }
        return true;
    }

    // What faces refer to by index (from 1, or counted back from -1):
    // vertices or normals, how many came so far, and the largest index a
    // face named, with its line (one may come after: checked at the end).
    struct Referred {
        const char* one;   // "vertex"
        const char* many;  // "vertices"
        long count = 0;
        long largest = 0;
        long largest_line = 0;
    };

    // A face's reference `index` (0: none) to one of `r`, in word w.
    void refer(Referred& r, long index, const Word& w) {
        if (index < 0 && -index > r.count) {
            fail_at(line_of(w.begin), std::string("face refers to ") + r.one + " " +
                                          std::to_string(index) + " (counted back from the " +
                                          std::to_string(r.count) + " " + r.many +
                                          " before it), before the first");
        }
        if (index > r.largest) {
            r.largest = index;
            r.largest_line = line_of(w.begin);
        }
    }

    // Every index a face named forward is one the file has.
    void check_referred(const Referred& r) const {
        if (r.largest > r.count) {
            fail_at(r.largest_line, std::string("face refers to ") + r.one + " " +
                                        std::to_string(r.largest) + ", but the file has " +
                                        std::to_string(r.count) + " " + r.many);
        }
    }

    // The non-zero integer in [begin, end) (a '-' and at most 10 digits,
    // within 32 bits), or false.
    static bool parse_index(const char* begin, const char* end, long* index) {
        const bool negative = begin < end && *begin == '-';
        const char* digits = negative ? begin + 1 : begin;
        if (digits == end || end - digits > 10) {
            return false;
        }
        long value = 0;
        for (const char* c = digits; c < end; ++c) {
            if (*c < '0' || *c > '9') {
                return false;
            }
            value = value * 10 + (*c - '0');
        }
        *index = negative ? -value : value;
        return value != 0 && value <= 2147483647L;
    }

    // tinyobjloader triangulates a face in time that grows with the square
    // of its size: 10,000 vertices take about 0.2 s, 100,000 took 18 s.
    static constexpr std::size_t max_face_vertices = 10000;

    std::string path_;
    long line_number_ = 0;
    Referred vertices_{"vertex", "vertices"};
    Referred normals_{"normal", "normals"};
    Referred texcoords_{"texture coordinate", "texture coordinates (vt)"};
    bool mtl_ = false;
    ModelDefects* defects_;
    bool whole_line_ = false;  // the line being split is a vn, usemtl or mtllib statement
    std::vector<ObjNameRef> materials_;
    std::vector<ObjNameRef> libraries_;
    std::vector<Word> words_;
    // Rewrites of the checked text (where tinyobjloader would misread a
    // statement), in order, applied once every line is checked.
    struct Edit {
        std::size_t offset;
        std::size_t length;
        std::string with;
    };
    std::vector<Edit> edits_;
    const char* base_ = nullptr;                // the text's first byte
    const char* statement_end_ = nullptr;       // the end of the statement being checked
    std::map<std::string, long> newmtl_lines_;  // an MTL's material names, their lines
    std::vector<const char*> breaks_;           // the statement's continuations, in order
};

}  // namespace

std::string checked_obj_text(const std::string& path) { return check_obj(path).text; }

std::string decode_material_name(std::string name) {
    if (name == std::string(1, material_name_mark)) {
        return "";  // a newmtl without a name
    }
    std::replace(name.begin(), name.end(), material_name_mark, ' ');
    return name;
}

CheckedObj check_obj(const std::string& path, ModelDefects* defects) {
    ObjChecker checker(path, false, defects);
    CheckedObj out;
    out.text = checker.checked_text();
    out.materials = checker.materials();
    out.libraries = checker.libraries();
    return out;
}

std::string checked_mtl_text(const std::string& path, ModelDefects* defects) {
    return ObjChecker(path, true, defects).checked_text();
}

}  // namespace trac0r
