// The MTL checker (mtl_checker.h): the checks that tinyobjloader leaves
// out of a material library.
#include "trac0r/mtl_checker.h"

#include "trac0r/input_checks.h"
#include "trac0r/obj_checker.h"
#include "trac0r/obj_text_checker.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace trac0r {

namespace {

class MtlChecker : public ObjTextChecker {
  public:
    MtlChecker(const std::string& path, ModelDefects* defects)
        : ObjTextChecker(path, "MTL material library", "MTL", defects) {}

  private:
    void check_statement(char*, char*) override { check_mtl_statement(); }

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
                edit(words_[1].end, 0, " " + v[0] + " " + v[0]);
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
                edit(w.begin, static_cast<std::size_t>(w.end - w.begin), shown_value);
                text = shown_value;
            }
            out.push_back(text);
        }
        return out;
    }

    std::map<std::string, long> newmtl_lines_;  // the material names, their lines
};

}  // namespace

std::string checked_mtl_text(const std::string& path, ModelDefects* defects) {
    return MtlChecker(path, defects).checked_text();
}

}  // namespace trac0r
