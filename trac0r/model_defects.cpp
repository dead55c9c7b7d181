#include "trac0r/model_defects.h"

#include <stdexcept>

namespace trac0r {

namespace {

std::string located(const std::string& file, long line) {
    return line > 0 ? file + ":" + std::to_string(line) : file;
}

}  // namespace

void ModelDefects::report(const std::string& file, long line, const std::string& what,
                          const std::string& done, long times) {
    if (strict_) {
        throw std::runtime_error(located(file, line) + ": " + what);
    }
    count(file, line, what, done, times);
}

void ModelDefects::count(const std::string& file, long line, const std::string& what,
                         const std::string& done, long times) {
    for (Kind& k : kinds_) {
        if (k.file == file && k.what == what) {
            k.count += times;
            return;
        }
    }
    kinds_.push_back({file, line, what, done, times});
}

void ModelDefects::report_message(const std::string& file, const std::string& message,
                                  const std::string& done) {
    const std::string prefix = file + ": ";
    const bool prefixed = message.compare(0, prefix.size(), prefix) == 0;
    count(file, 0, prefixed ? message.substr(prefix.size()) : message, done);
}

void ModelDefects::add_lines(const std::vector<std::string>& lines) {
    added_.insert(added_.end(), lines.begin(), lines.end());
}

std::vector<std::string> ModelDefects::lines() const {
    std::vector<std::string> out;
    for (const Kind& k : kinds_) {
        std::string line = located(k.file, k.line) + ": warning: " + k.what + "; " + k.done;
        if (k.count > 1) {
            // "here": the line given, where the file has lines.
            line += " (" + std::to_string(k.count) +
                    (k.line > 0 ? " times; the first here)" : " times)");
        }
        out.push_back(line + " (--strict refuses it)");
    }
    out.insert(out.end(), added_.begin(), added_.end());
    return out;
}

}  // namespace trac0r
