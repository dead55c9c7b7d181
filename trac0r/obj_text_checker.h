// What the OBJ and MTL checkers (obj_checker.cpp, mtl_checker.cpp) share:
// reading the file's text (UTF-8, or UTF-16 with a mark), splitting it into
// statements (lines, continued after a '\\'), comments blanked out, words,
// decimal numbers finite in float, messages "path:line: ...", defects
// reported or refused, and the rewrites made for tinyobjloader.
#ifndef TRAC0R_OBJ_TEXT_CHECKER_H
#define TRAC0R_OBJ_TEXT_CHECKER_H

#include "trac0r/model_defects.h"

#include <cstddef>
#include <string>
#include <vector>

namespace trac0r {

class ObjTextChecker {
  public:
    // `kind`: what the file is, for messages ("OBJ mesh", "MTL material
    // library"); `format`: its format's name ("OBJ", "MTL").
    ObjTextChecker(const std::string& path, const char* kind, const char* format,
                   ModelDefects* defects)
        : path_(path), defects_(defects), kind_(kind), format_(format) {}
    virtual ~ObjTextChecker() = default;

    // The file's text, its comments (and what check_statement blanks)
    // blanked out and the rewrites made, once every statement is checked.
    std::string checked_text();

  protected:
    struct Word {
        const char* begin;
        const char* end;
        std::string text() const { return std::string(begin, end); }
    };

    // One statement, [begin, end) with its comment blanked out, split into
    // words_ (at least one).
    virtual void check_statement(char* begin, char* end) = 0;
    // After the last statement.
    virtual void finish() {}

    static bool is_blank(char c) { return c == ' ' || c == '\t'; }
    static bool is_keyword(const Word& w, char keyword) {
        return w.end - w.begin == 1 && *w.begin == keyword;
    }
    static bool is_word(const Word& w, const char* text);
    // The word as the message shows it: cut short, control bytes escaped.
    static std::string shown(const Word& w);
    static bool finite_in_float(const Word& w);

    // The line `p` (in the statement being checked) is on.
    long line_of(const char* p) const;
    [[noreturn]] void fail_at(long line, const std::string& message) const;
    // A defect at `line`: reported (lenient), else the error it names.
    void report_or_fail(long line, const std::string& what, const std::string& done);
    // Each word after the first a decimal number finite in float; `what`
    // names one in the message.
    void check_numbers(const std::string& what);
    // The name after the statement's keyword (see obj_text_checker.cpp).
    std::string name_after_keyword();
    // [from, to) of the text replaced by " " + name.
    void rename(const char* from, const char* to, char name);
    // [from, from + length) of the text replaced by `with`.
    void edit(const char* from, std::size_t length, const std::string& with);

    std::string path_;
    ModelDefects* defects_;
    long line_number_ = 0;
    std::vector<Word> words_;
    const char* statement_end_ = nullptr;  // the end of the statement being checked

  private:
    // The line [begin, end): its comment (from '#') blanked out, its words
    // split, then check_statement.
    void check_line(char* begin, char* end);

    const char* kind_;
    const char* format_;
    // Rewrites of the checked text (where tinyobjloader would misread a
    // statement), in order, applied once every line is checked.
    struct Edit {
        std::size_t offset;
        std::size_t length;
        std::string with;
    };
    std::vector<Edit> edits_;
    const char* base_ = nullptr;       // the text's first byte
    std::vector<const char*> breaks_;  // the statement's continuations, in order
};

}  // namespace trac0r

#endif
