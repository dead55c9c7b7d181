// The OBJ checker (obj_checker.h): the checks that tinyobjloader leaves out.
#include "trac0r/obj_checker.h"

#include "trac0r/obj_text_checker.h"

#include <algorithm>
#include <string>
#include <vector>

namespace trac0r {

namespace {

// The OBJ checks that tinyobjloader leaves out: it reads "x", "nan" or a
// missing coordinate as 0, "3.5" as the index 3, a face of two vertices as
// nothing, an index past 2^31 as another index, and "0x1p0" as 0. Only the
// statements the mesh uses are checked (v, vn, vt, f, usemtl, mtllib, s);
// the others are blanked, so that tinyobjloader cannot refuse or misread a
// line, point or curve the mesh never uses. Each error is "path:line: ...".
// It accepts what exporters write that tinyobjloader does not: a '+' before
// a coordinate, and a line continued after a '\' (ObjTextChecker).
class ObjChecker : public ObjTextChecker {
  public:
    ObjChecker(const std::string& path, ModelDefects* defects)
        : ObjTextChecker(path, "OBJ mesh", "OBJ", defects) {}

    // The usemtl and mtllib statements of the text checked, in order.
    const std::vector<ObjNameRef>& materials() const { return materials_; }
    const std::vector<ObjNameRef>& libraries() const { return libraries_; }

  private:
    void check_statement(char* begin, char* end) override {
        const Word& key = words_[0];
        if (is_keyword(key, 'v')) {
            check_vertex();
        } else if (is_keyword(key, 'f')) {
            if (!check_face()) {
                std::fill(begin, end, ' ');  // a defect passed over: the face skipped
            }
        } else if (is_word(key, "vn")) {
            check_normal();
        } else if (is_word(key, "vt")) {
            check_texcoord();
        } else if (is_word(key, "usemtl") || is_word(key, "mtllib")) {
            check_names();
        } else if (!(is_word(key, "s") && is_smoothing_group(key.end, end))) {
            // A statement the mesh does not use (a smoothing group is
            // kept as it is).
            std::fill(begin, end, ' ');
        }
    }

    void finish() override {
        check_referred(vertices_);
        check_referred(normals_);
        check_referred(texcoords_);
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

    Referred vertices_{"vertex", "vertices"};
    Referred normals_{"normal", "normals"};
    Referred texcoords_{"texture coordinate", "texture coordinates (vt)"};
    std::vector<ObjNameRef> materials_;
    std::vector<ObjNameRef> libraries_;
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
    ObjChecker checker(path, defects);
    CheckedObj out;
    out.text = checker.checked_text();
    out.materials = checker.materials();
    out.libraries = checker.libraries();
    return out;
}

}  // namespace trac0r
