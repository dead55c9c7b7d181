// The JSON diagnostics layer under the scene loader: reading nlohmann::json
// values with one message per mistake, "ORIGIN: /json/pointer: expected
// ..., got ...", and parsing JSON text with the position of a syntax error
// and no key given twice. Each error is a JsonError; it knows nothing of
// scenes.
#ifndef TRAC0R_JSON_DIAGNOSTICS_H
#define TRAC0R_JSON_DIAGNOSTICS_H

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace trac0r {
namespace json_diagnostics {

using nlohmann::json;

// One message: "ORIGIN: /json/path: what was expected (got ...)", or
// "ORIGIN:LINE:COLUMN: JSON syntax error: ..." for the text itself.
class JsonError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// ---- Locations and messages ------------------------------------------------

// Where a value sits: the text's origin (a file name) and a JSON pointer.
struct Location {
    std::string origin;
    std::string pointer;  // "" for the whole document

    Location key(const std::string& name) const;
    Location index(std::size_t i) const;
};

// Throws JsonError("ORIGIN: POINTER: message"), each key of the pointer cut
// short and its control bytes escaped.
[[noreturn]] void fail(const Location& at, const std::string& message);

// JSON text of a value as a person would write it ("[1, -2]"), cut short to
// 80 characters.
std::string describe(const json& value);

// fail(at, "expected EXPECTED, got DESCRIBE(found)NOTE").
[[noreturn]] void fail_expected(const Location& at, const std::string& expected, const json& found,
                                const std::string& note = "");

// "a, b, c", each word between `quote`s.
std::string join(const std::vector<std::string>& words, const std::string& quote = "");

// "an emissive", "a plane".
std::string with_article(const std::string& word);

// ---- Numbers, strings, objects ---------------------------------------------

enum class NumberRule { finite, positive, non_negative, unit_interval, non_zero };

// "a finite positive number" or, for count > 0, "an array of 3 finite
// positive numbers".
std::string expectation(NumberRule rule, int count = 0);

// Whether x satisfies `rule` (finite: always; the caller checks finiteness).
bool satisfies(NumberRule rule, float x);

// Whether a JSON number fits a float (finite, at most FLT_MAX).
bool fits_float(const json& value);

// A number that fits a float and satisfies `rule`.
float read_float(const json& value, const Location& at, NumberRule rule);
// An array of 3 (2) such numbers; the message shows the whole array.
glm::vec3 read_vec3(const json& value, const Location& at, NumberRule rule);
// read_vec3's checks, and the numbers as the file wrote them, in double.
glm::dvec3 read_dvec3(const json& value, const Location& at, NumberRule rule);
glm::vec2 read_vec2(const json& value, const Location& at, NumberRule rule);
// An integer in [lowest, highest]; 800.0 is accepted as 800, 800.5 is not.
int read_int(const json& value, const Location& at, int lowest, int highest);
// A string among `choices`.
std::string read_choice(const json& value, const Location& at,
                        const std::vector<std::string>& choices);

// A JSON object being read: lookups of its keys, with their locations.
class ObjectReader {
  public:
    ObjectReader(const json& value, Location at, const std::string& expected)
        : value_(value), at_(std::move(at)) {
        if (!value_.is_object()) {
            fail_expected(at_, expected, value_);
        }
    }

    // Every key must be one of `allowed`; `owner` names the object in the
    // message ("a diffuse material").
    void allow_only(const std::vector<std::string>& allowed, const std::string& owner) const {
        for (auto it = value_.begin(); it != value_.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
                fail(at(it.key()),
                     "unknown key in " + owner + " (allowed keys: " + join(allowed) + ")");
            }
        }
    }

    bool has(const std::string& key) const { return value_.contains(key); }
    const json& operator[](const std::string& key) const { return value_.at(key); }
    Location at(const std::string& key) const { return at_.key(key); }

    // The value of a key that must be present; `expected` tells what to
    // write when it is missing.
    const json& required(const std::string& key, const std::string& expected) const {
        if (!has(key)) {
            fail(at(key), "required key is missing (expected " + expected + ")");
        }
        return value_.at(key);
    }

    float required_float(const std::string& key, NumberRule rule) const {
        return read_float(required(key, expectation(rule)), at(key), rule);
    }
    float optional_float(const std::string& key, NumberRule rule, float fallback) const {
        return has(key) ? read_float(value_.at(key), at(key), rule) : fallback;
    }
    glm::vec3 required_vec3(const std::string& key, NumberRule rule) const {
        return read_vec3(required(key, expectation(rule, 3)), at(key), rule);
    }
    glm::vec3 optional_vec3(const std::string& key, NumberRule rule, glm::vec3 fallback) const {
        return has(key) ? read_vec3(value_.at(key), at(key), rule) : fallback;
    }
    glm::dvec3 optional_dvec3(const std::string& key, NumberRule rule, glm::dvec3 fallback) const {
        return has(key) ? read_dvec3(value_.at(key), at(key), rule) : fallback;
    }
    int optional_int(const std::string& key, int lowest, int highest, int fallback) const {
        return has(key) ? read_int(value_.at(key), at(key), lowest, highest) : fallback;
    }
    bool optional_bool(const std::string& key, bool fallback) const {
        if (!has(key)) {
            return fallback;
        }
        const json& v = value_.at(key);
        if (!v.is_boolean()) {
            fail_expected(at(key), "true or false", v);
        }
        return v.get<bool>();
    }

  private:
    const json& value_;
    Location at_;
};

// ---- Parsing ----------------------------------------------------------------

// The JSON text `text`, named `origin` in messages; a syntax error, a
// number beyond double's range and a key given twice in one object are
// JsonErrors with their line and column (or JSON pointer).
json parse_json(const std::string& text, const std::string& origin);

}  // namespace json_diagnostics
}  // namespace trac0r

#endif
