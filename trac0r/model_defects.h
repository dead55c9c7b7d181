// Defects of a model file that leave it renderable (a face of two
// vertices, a usemtl naming no material, a texture that is not there):
// loaded leniently, as Blender's importer and assimp do, each kind is one
// warning line with a count; loaded strictly (--strict), each is the error
// it always was.
#ifndef TRAC0R_MODEL_DEFECTS_H
#define TRAC0R_MODEL_DEFECTS_H

#include <string>
#include <vector>

namespace trac0r {

class ModelDefects {
  public:
    explicit ModelDefects(bool strict) : strict_(strict) {}

    bool strict() const { return strict_; }

    // A defect of `file` (at `line`, 0 where no line applies): `what` is
    // wrong, `done` what lenient loading does about it ("skipped", "its
    // colour factor instead"). Strict: throws std::runtime_error
    // "file[:line]: what". Lenient: counted with the others of the same
    // file and `what`, their first line kept; `times` defects at once.
    void report(const std::string& file, long line, const std::string& what,
                const std::string& done, long times = 1);

    // A defect that a reader reported as its error `message` ("file: ...",
    // as it is thrown when strict): counted as report() does, `file:`
    // taken off its front. Lenient only (the caller rethrows when strict).
    void report_message(const std::string& file, const std::string& message,
                        const std::string& done);

    // Warning lines made elsewhere (a reader's child process), kept as
    // they are, after this one's own.
    void add_lines(const std::vector<std::string>& lines);

    // One line per kind, in the order first met: "file:line: warning:
    // what; done (N times; the first here)" ("... done" alone where there
    // is one; "(N times)" where no line applies).
    std::vector<std::string> lines() const;

  private:
    void count(const std::string& file, long line, const std::string& what, const std::string& done,
               long times = 1);

    struct Kind {
        std::string file;
        long line;
        std::string what;
        std::string done;
        long count;
    };
    bool strict_;
    std::vector<Kind> kinds_;
    std::vector<std::string> added_;
};

}  // namespace trac0r

#endif
