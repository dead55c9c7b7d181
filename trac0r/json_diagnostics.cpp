// The JSON diagnostics layer under the scene loader (json_diagnostics.h):
// values read out of nlohmann::json with one message per mistake that says
// where it is, what was expected and what was found, and JSON text parsed
// with the line and column of a syntax error and no key given twice.
#include "trac0r/json_diagnostics.h"

#include "trac0r/input_checks.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <set>
#include <utility>

namespace trac0r {
namespace json_diagnostics {

namespace {

// RFC 6901 escaping, so that a name containing '/' still gives a pointer
// that names exactly one value.
std::string escape_pointer_token(const std::string& token) {
    std::string escaped;
    for (char c : token) {
        if (c == '~') {
            escaped += "~0";
        } else if (c == '/') {
            escaped += "~1";
        } else {
            escaped += c;
        }
    }
    return escaped;
}

// JSON text of a value as a person would write it ("[1, -2]"), cut short so
// that a whole misplaced object does not flood the message: appended to
// out until out is longer than limit, so the text of a value nested ten
// thousand deep, or of a huge array, is never built in full (nor recursed
// through: each level adds a character, so the depth stays below limit).
void append_description(const json& value, std::size_t limit, std::string& out) {
    if (out.size() > limit) {
        return;
    }
    if (value.is_array()) {
        out += '[';
        for (std::size_t i = 0; i < value.size() && out.size() <= limit; ++i) {
            out += i == 0 ? "" : ", ";
            append_description(value[i], limit, out);
        }
        out += ']';
    } else if (value.is_object()) {
        out += '{';
        for (auto it = value.begin(); it != value.end() && out.size() <= limit; ++it) {
            out += it == value.begin() ? "" : ", ";
            out += json(it.key()).dump() + ": ";
            append_description(it.value(), limit, out);
        }
        out += '}';
    } else {
        out += value.dump();
    }
}


const char* const not_finite_note = " (not finite as a 32-bit float)";

// The whole array is shown when one element is wrong: "got [1, -2]" reads
// better than a pointer to the element.
std::vector<float> read_floats(const json& value, const Location& at, int count, NumberRule rule) {
    const std::string expected = expectation(rule, count);
    if (!value.is_array() || value.size() != static_cast<std::size_t>(count)) {
        fail_expected(at, expected, value);
    }
    std::vector<float> xs;
    for (const json& element : value) {
        if (!element.is_number()) {
            fail_expected(at, expected, value);
        }
        if (!fits_float(element)) {
            fail_expected(at, expected, value, not_finite_note);
        }
        xs.push_back(element.get<float>());
        if (!satisfies(rule, xs.back())) {
            fail_expected(at, expected, value);
        }
    }
    return xs;
}

}  // namespace

// ---- Locations and messages ------------------------------------------------

Location Location::key(const std::string& name) const {
    return {origin, pointer + "/" + escape_pointer_token(name)};
}

Location Location::index(std::size_t i) const {
    return {origin, pointer + "/" + std::to_string(i)};
}

[[noreturn]] void fail(const Location& at, const std::string& message) {
    // A key may be any string, 100,000 characters or a terminal's escape
    // sequence: each is cut short, as a value is (describe), its control
    // bytes escaped, and the path keeps every key (the last names the field).
    std::string where = at.pointer.empty() ? "(top level)" : "";
    for (std::size_t start = 0; start < at.pointer.size();) {
        const std::size_t slash = std::min(at.pointer.find('/', start + 1), at.pointer.size());
        where += printable(at.pointer.substr(start, slash - start), 40);
        start = slash;
    }
    throw JsonError(at.origin + ": " + where + ": " + message);
}

std::string describe(const json& value) {
    const std::size_t max_length = 80;
    std::string text;
    append_description(value, max_length, text);
    return text.size() <= max_length ? text : text.substr(0, max_length - 3) + "...";
}

[[noreturn]] void fail_expected(const Location& at, const std::string& expected, const json& found,
                                const std::string& note) {
    fail(at, "expected " + expected + ", got " + describe(found) + note);
}

std::string join(const std::vector<std::string>& words, const std::string& quote) {
    std::string text;
    for (const std::string& w : words) {
        text += (text.empty() ? "" : ", ") + quote + w + quote;
    }
    return text;
}

std::string with_article(const std::string& word) {
    const bool vowel = !word.empty() && std::strchr("aeiou", word.front()) != nullptr;
    return (vowel ? "an " : "a ") + word;
}

// ---- Numbers, strings, objects ---------------------------------------------

std::string expectation(NumberRule rule, int count) {
    std::string adjectives = "finite";
    std::string suffix;
    switch (rule) {
    case NumberRule::finite:
        break;
    case NumberRule::positive:
        adjectives = "finite positive";
        break;
    case NumberRule::non_negative:
        suffix = " >= 0";
        break;
    case NumberRule::unit_interval:
        adjectives = "";
        suffix = " in [0, 1]";
        break;
    case NumberRule::non_zero:
        adjectives = "finite non-zero";
        break;
    }
    const std::string lead = adjectives.empty() ? "" : adjectives + " ";
    if (count == 0) {
        return "a " + lead + "number" + suffix;
    }
    return "an array of " + std::to_string(count) + " " + lead + "numbers" + suffix;
}

bool satisfies(NumberRule rule, float x) {
    switch (rule) {
    case NumberRule::finite:
        return true;
    case NumberRule::positive:
        return x > 0.0f;
    case NumberRule::non_negative:
        return x >= 0.0f;
    case NumberRule::unit_interval:
        return x >= 0.0f && x <= 1.0f;
    case NumberRule::non_zero:
        return x != 0.0f;
    }
    return false;
}

// Whether a JSON number fits a float; the double-to-float conversion of a
// larger value is undefined behaviour, and infinity is no scene value.
bool fits_float(const json& value) {
    const double d = value.get<double>();
    return std::isfinite(d) && std::fabs(d) <= static_cast<double>(FLT_MAX);
}

float read_float(const json& value, const Location& at, NumberRule rule) {
    if (!value.is_number()) {
        fail_expected(at, expectation(rule), value);
    }
    if (!fits_float(value)) {
        fail_expected(at, expectation(rule), value, not_finite_note);
    }
    const float x = value.get<float>();
    if (!satisfies(rule, x)) {
        fail_expected(at, expectation(rule), value);
    }
    return x;
}

glm::vec3 read_vec3(const json& value, const Location& at, NumberRule rule) {
    const std::vector<float> xs = read_floats(value, at, 3, rule);
    return glm::vec3(xs[0], xs[1], xs[2]);
}

glm::dvec3 read_dvec3(const json& value, const Location& at, NumberRule rule) {
    read_vec3(value, at, rule);  // the same checks and messages
    return glm::dvec3(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
}

glm::vec2 read_vec2(const json& value, const Location& at, NumberRule rule) {
    const std::vector<float> xs = read_floats(value, at, 2, rule);
    return glm::vec2(xs[0], xs[1]);
}

// JSON has one number type, so 800.0 is accepted as 800; 800.5 is not.
int read_int(const json& value, const Location& at, int lowest, int highest) {
    const std::string expected =
        "an integer in [" + std::to_string(lowest) + ", " + std::to_string(highest) + "]";
    if (!value.is_number()) {
        fail_expected(at, expected, value);
    }
    const double d = value.get<double>();
    if (!(d >= lowest && d <= highest && std::floor(d) == d)) {
        fail_expected(at, expected, value);
    }
    return static_cast<int>(d);
}

std::string read_choice(const json& value, const Location& at,
                        const std::vector<std::string>& choices) {
    const std::string expected = "one of " + join(choices, "\"");
    if (!value.is_string()) {
        fail_expected(at, expected, value);
    }
    const std::string text = value.get<std::string>();
    if (std::find(choices.begin(), choices.end(), text) == choices.end()) {
        fail_expected(at, expected, value);
    }
    return text;
}

// ---- Parsing ----------------------------------------------------------------

namespace {

// nlohmann keeps the last of two equal keys in an object without a word;
// a copied material that keeps its old name would then vanish. This SAX
// handler follows the path being parsed and rejects a repeated key; it
// builds nothing, so it costs a pass over the text. (As a callback of the
// DOM parser the same check took 42 s for a 37 MB scene, against 0.56 s
// for the parse without it: that parser copies what it hands over.)
class DuplicateKeyCheck : public json::json_sax_t {
  public:
    explicit DuplicateKeyCheck(const std::string& origin) : origin_(origin) {}

    bool null() override { return element_done(); }
    bool boolean(bool) override { return element_done(); }
    bool number_integer(json::number_integer_t) override { return element_done(); }
    bool number_unsigned(json::number_unsigned_t) override { return element_done(); }
    bool number_float(json::number_float_t, const json::string_t&) override {
        return element_done();
    }
    bool string(json::string_t&) override { return element_done(); }
    bool binary(json::binary_t&) override { return element_done(); }
    bool start_object(std::size_t) override { return start(false); }
    bool start_array(std::size_t) override { return start(true); }
    bool end_object() override { return end(); }
    bool end_array() override { return end(); }
    bool key(json::string_t& key) override {
        Frame& object = frames_.back();
        object.key = key;
        if (!object.keys.insert(key).second) {
            fail(location(), "duplicate key (a JSON object names each key once)");
        }
        return true;
    }
    // A syntax error ends the check quietly: the DOM parser that runs next
    // reports it, with its position.
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

  private:
    struct Frame {
        bool is_array;
        std::size_t index;           // arrays: the element being parsed
        std::string key;             // objects: the key being parsed
        std::set<std::string> keys;  // objects: the keys seen so far
    };

    bool start(bool is_array) {
        frames_.push_back(Frame{is_array, 0, "", {}});
        return true;
    }
    bool end() {
        frames_.pop_back();
        return element_done();
    }
    bool element_done() {
        if (!frames_.empty() && frames_.back().is_array) {
            ++frames_.back().index;
        }
        return true;
    }

    Location location() const {
        Location at{origin_, ""};
        for (const Frame& f : frames_) {
            at = f.is_array ? at.index(f.index) : at.key(f.key);
        }
        return at;
    }

    std::string origin_;
    std::vector<Frame> frames_;
};

// "FILE:LINE:COL" of the byte nlohmann's parse_error reports (1-based: the
// last byte it read, which is the offending one).
std::string text_position(const std::string& text, std::size_t byte) {
    const std::size_t offending = std::min(byte == 0 ? 0 : byte - 1, text.size());
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + offending, '\n'));
    const std::size_t line_start =
        offending == 0 ? 0 : text.find_last_of('\n', offending - 1) + 1;  // npos + 1 == 0
    return std::to_string(line) + ":" + std::to_string(offending - line_start + 1);
}

// nlohmann's what() is "[json.exception.parse_error.101] parse error at line
// L, column C: syntax error while parsing value - unexpected '}'; ...": keep
// only what went wrong, as we state the position ourselves.
std::string syntax_error_detail(const std::string& what) {
    std::string detail = what;
    const std::size_t column = detail.find(", column ");
    if (column != std::string::npos && detail.find(": ", column) != std::string::npos) {
        detail = detail.substr(detail.find(": ", column) + 2);
    }
    const std::size_t dash = detail.find(" - ");
    if (detail.compare(0, 12, "syntax error") == 0 && dash != std::string::npos) {
        detail = detail.substr(dash + 3);
    }
    return detail;
}

// "[json.exception.out_of_range.406] number overflow ..." without the id.
std::string without_exception_id(const std::string& what) {
    const std::size_t end = what.find("] ");
    return what.compare(0, 1, "[") == 0 && end != std::string::npos ? what.substr(end + 2) : what;
}

// The byte offset (0-based) of the first number in JSON text, outside
// strings, that is beyond double's range, or npos: where nlohmann's number
// overflow is, which it does not say.
std::size_t overflowing_number_offset(const std::string& text) {
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') {
                ++i;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '-' || (c >= '0' && c <= '9')) {
            const std::size_t end = text.find_first_of(",]} \t\r\n", i);
            const std::string number = text.substr(i, end == std::string::npos ? end : end - i);
            if (std::isinf(std::strtod(number.c_str(), nullptr))) {
                return i;
            }
            i += number.size() - 1;
        }
    }
    return std::string::npos;
}

}  // namespace

json parse_json(const std::string& text, const std::string& origin) {
    // Two linear passes: the duplicate-key check, then the DOM.
    DuplicateKeyCheck duplicate_keys(origin);
    try {
        json::sax_parse(text, &duplicate_keys);
        return json::parse(text);
    } catch (const json::parse_error& e) {
        throw JsonError(origin + ":" + text_position(text, e.byte) +
                        ": JSON syntax error: " + syntax_error_detail(e.what()));
    } catch (const json::out_of_range& e) {
        // A number beyond double range ("1e400"); nlohmann gives no position.
        const std::size_t at = overflowing_number_offset(text);
        const std::string where = at == std::string::npos ? "" : ":" + text_position(text, at + 1);
        throw JsonError(origin + where +
                        ": JSON number is not finite: " + without_exception_id(e.what()));
    }
}

}  // namespace json_diagnostics
}  // namespace trac0r
