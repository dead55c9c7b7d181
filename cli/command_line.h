// The command lines of trac0r_viewer, trac0r_mpi and the benchmark
// programs, on CLI11 (Debian's libcli11-dev): options defined once, their
// --help generated from the definitions, and every mistake one line on
// stderr that names the flag and what was expected (UsageError: exit code
// 2; anything else exits 1).
#ifndef TRAC0R_CLI_COMMAND_LINE_H
#define TRAC0R_CLI_COMMAND_LINE_H

#include "cli/parse.h"

#include "trac0r/version.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <functional>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r_cli {

// text's words refilled into lines of at most `width` columns; the first
// line begins at column `first` (already written), the others are indented
// to `indent`. A '\n' in text starts a new line.
inline std::string wrap(const std::string& text, std::size_t width, std::size_t first,
                        std::size_t indent) {
    std::string out;
    std::size_t column = first;
    bool line_start = true;
    std::size_t i = 0;
    while (i < text.size()) {
        if (text[i] == '\n') {
            out += "\n" + std::string(indent, ' ');
            column = indent;
            line_start = true;
            ++i;
            continue;
        }
        if (text[i] == ' ') {
            ++i;
            continue;
        }
        std::size_t end = i;
        while (end < text.size() && text[end] != ' ' && text[end] != '\n') {
            ++end;
        }
        const std::string word = text.substr(i, end - i);
        if (!line_start && column + 1 + word.size() > width) {
            out += "\n" + std::string(indent, ' ');
            column = indent;
            line_start = true;
        }
        if (!line_start) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
        line_start = false;
        i = end;
    }
    return out;
}

// --help: the usage line, the description, then each group of options as
// "  -o, --output FILE  what it does", refilled to 80 columns.
class HelpFormatter : public CLI::Formatter {
  public:
    HelpFormatter(std::string usage, std::size_t column) : usage_(std::move(usage)) {
        column_width(column);
        label("Positionals", "Arguments");
    }

    std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode) const override {
        std::string out = "Usage: " + usage_ + "\n\n";
        out += wrap(app->get_description(), width, 0, 0) + "\n";
        out += make_positionals(app);
        out += option_groups(app);
        const std::string footer = app->get_footer();
        if (!footer.empty()) {
            out += "\n" + footer;
        }
        return out;
    }

    // The groups in the order their first options were defined, but the
    // one of --help last.
    std::string option_groups(const CLI::App* app) const {
        const std::string help_group = app->get_help_ptr()->get_group();
        std::vector<std::string> groups;
        for (const std::string& g : app->get_groups()) {
            if (g != help_group) {
                groups.push_back(g);
            }
        }
        groups.push_back(help_group);
        std::string out;
        for (const std::string& group : groups) {
            const std::vector<const CLI::Option*> opts =
                app->get_options([&group](const CLI::Option* o) {
                    return o->get_group() == group && o->nonpositional();
                });
            if (!group.empty() && !opts.empty()) {
                out += make_group(group, false, opts);
            }
        }
        return out;
    }

    std::string make_option_name(const CLI::Option* opt, bool is_positional) const override {
        if (is_positional) {
            return opt->get_name(true);
        }
        std::string names;
        for (const std::string& s : opt->get_snames()) {
            names += (names.empty() ? "-" : ", -") + s;
        }
        for (const std::string& l : opt->get_lnames()) {
            names += (names.empty() ? "--" : ", --") + l;
        }
        return names;
    }

    std::string make_option_opts(const CLI::Option* opt) const override {
        return opt->get_items_expected_max() == 0 || opt->get_positional()
                   ? std::string()
                   : " " + opt->get_type_name();
    }

    std::string make_option(const CLI::Option* opt, bool is_positional) const override {
        const std::string left =
            "  " + make_option_name(opt, is_positional) + make_option_opts(opt);
        const std::size_t column = get_column_width();
        if (left.size() + 2 > column) {
            return left + "\n" + std::string(column, ' ') +
                   wrap(make_option_desc(opt), width, column, column) + "\n";
        }
        return left + std::string(column - left.size(), ' ') +
               wrap(make_option_desc(opt), width, column, column) + "\n";
    }

    static const std::size_t width = 80;

  private:
    std::string usage_;
};

// A program's command line: a CLI::App whose options parse their values
// with the functions above, and whose errors are UsageErrors.
class CommandLine {
  public:
    enum class Outcome { run, help, version };

    // usage: the line after "Usage: ", e.g. "tonemap IN.pfm OUT.png [EXPOSURE]".
    CommandLine(const std::string& program, const std::string& usage,
                const std::string& description, std::size_t column = 25)
        : app_(description, program), program_(program) {
        app_.formatter(std::make_shared<HelpFormatter>(usage, column));
        app_.allow_extras();  // refused by parse(), with our message
        app_.set_help_flag("-h,--help", "this text");
        app_.set_version_flag("--version", program + " " + trac0r::version_line(),
                              "the version and whether OpenCL is built in");
    }

    CLI::App& app() { return app_; }

    // The group the options added next are listed under in --help.
    void group(const std::string& name) { group_ = name; }
    // Moves -h, --help and --version into group `name`.
    void help_group(const std::string& name) {
        app_.get_help_ptr()->group(name);
        app_.get_option("--version")->group(name);
    }

    // An option with one value, given at most once: set(value). A value
    // that is an option's spelling ("--spp") is refused: the value was
    // forgotten.
    CLI::Option* value(const std::string& names, const std::string& type, const std::string& help,
                       std::function<void(const std::string&)> set) {
        CLI::Option* opt = app_.add_option_function<std::string>(
            names, [names, set](const std::string& v) { set(checked(name_of(names), v)); }, help);
        return opt->type_name(type)->group(group_);
    }

    // As value, but the option may be repeated: set for each value in turn.
    CLI::Option* repeated(const std::string& names, const std::string& type,
                          const std::string& help, std::function<void(const std::string&)> set) {
        CLI::Option* opt = app_.add_option_function<std::vector<std::string>>(
            names,
            [names, set](const std::vector<std::string>& values) {
                for (const std::string& v : values) {
                    set(checked(name_of(names), v));
                }
            },
            help);
        opt->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
        return opt->type_name(type)->group(group_);
    }

    template <typename Int>
    CLI::Option* integer(const std::string& names, Int* target, long lo, long hi,
                         const std::string& help, const std::string& type = "N") {
        const std::string flag = name_of(names);
        return value(names, type, help, [=](const std::string& v) {
            *target = static_cast<Int>(parse_long(flag, v, lo, hi));
        });
    }

    template <typename Real>
    CLI::Option* number(const std::string& names, Real* target, double lo, double hi,
                        const std::string& help, const std::string& type = "X") {
        const std::string flag = name_of(names);
        return value(names, type, help, [=](const std::string& v) {
            *target = static_cast<Real>(parse_number(flag, v, lo, hi));
        });
    }

    template <typename Real>
    CLI::Option* positive(const std::string& names, Real* target, const std::string& help,
                          const std::string& type = "X") {
        const std::string flag = name_of(names);
        return value(names, type, help, [=](const std::string& v) {
            *target = static_cast<Real>(parse_positive(flag, v));
        });
    }

    // One of choices ("a|b|c"), listed as the value's type in --help.
    CLI::Option* choice(const std::string& names, std::string* target, const std::string& choices,
                        const std::string& help) {
        const std::string flag = name_of(names);
        return value(names, choices, help,
                     [=](const std::string& v) { *target = parse_choice(flag, v, choices); });
    }

    CLI::Option* text(const std::string& names, std::string* target, const std::string& help,
                      const std::string& type = "FILE") {
        return value(names, type, help, [=](const std::string& v) { *target = v; });
    }

    // Two integers in [1, max] after the flag: `--size W H`.
    CLI::Option* size(const std::string& names, int* width, int* height, long max,
                      const std::string& help) {
        const std::string flag = name_of(names);
        CLI::Option* opt = app_.add_option_function<std::vector<std::string>>(
            names,
            [=](const std::vector<std::string>& v) {
                *width = static_cast<int>(parse_long(flag + " W", v.at(0), 1, max));
                *height = static_cast<int>(parse_long(flag + " H", v.at(1), 1, max));
            },
            help);
        opt->expected(2)->multi_option_policy(CLI::MultiOptionPolicy::Throw);
        return opt->type_name("W H")->group(group_);
    }

    CLI::Option* flag(const std::string& names, bool* target, const std::string& help) {
        CLI::Option* opt = app_.add_flag(names, *target, help);
        return opt->multi_option_policy(CLI::MultiOptionPolicy::Throw)->group(group_);
    }

    // A positional argument (shown in --help under "Arguments").
    CLI::Option* positional(const std::string& name, std::string* target, const std::string& help) {
        return app_.add_option(name, *target, help);
    }

    // What happens to a positional argument that no positional took
    // (default: refused as unexpected).
    void on_extra(std::function<void(const std::string&)> extra) { extra_ = std::move(extra); }

    // Parses the command line: help or version when asked for (printed by
    // the caller: help() and version()), else run. Throws a UsageError.
    Outcome parse(int argc, const char* const* argv) {
        refuse_bad_equals(argc, argv);
        try {
            app_.parse(argc, argv);
        } catch (const CLI::CallForHelp&) {
            return Outcome::help;
        } catch (const CLI::CallForVersion&) {
            return Outcome::version;
        } catch (const CLI::ParseError& e) {
            throw UsageError(message(e));
        }
        for (const std::string& a : app_.remaining()) {
            if (a.size() > 1 && a[0] == '-') {
                throw UsageError(a.substr(0, a.find('=')) + ": unknown option (see --help)");
            }
            if (extra_) {
                extra_(a);
            } else {
                throw UsageError("unexpected argument '" + a + "' (see --help)");
            }
        }
        return Outcome::run;
    }

    // For the programs that print help and version themselves: false
    // after printing them, true to run.
    bool parse_or_print(int argc, const char* const* argv) {
        const Outcome o = parse(argc, argv);
        if (o == Outcome::help) {
            std::fputs(help().c_str(), stdout);
        } else if (o == Outcome::version) {
            std::printf("%s\n", version().c_str());
        }
        return o == Outcome::run;
    }

    std::string help() const { return app_.help(); }
    std::string version() const { return program_ + " " + trac0r::version_line(); }

    // The options given ("--output", "--help" for -h), and whether one was.
    std::set<std::string> given() const {
        std::set<std::string> names;
        for (const CLI::Option* o : app_.get_options()) {
            if (o->count() > 0 && o->nonpositional()) {
                names.insert(o->get_name());
            }
        }
        return names;
    }
    bool given(const std::string& name) const { return app_.count(name) > 0; }

  private:
    // "-o,--output" as messages name it: "--output".
    static std::string name_of(const std::string& names) {
        const std::size_t comma = names.rfind(',');
        return comma == std::string::npos ? names : names.substr(comma + 1);
    }

    static std::string checked(const std::string& flag, const std::string& v) {
        if (v.size() > 2 && v.compare(0, 2, "--") == 0) {
            throw UsageError(flag + ": expected a value after it, got the option " + v);
        }
        return v;
    }

    // CLI11 reads --flag=yes as a true flag, and --spp= followed by an
    // argument as --spp with that argument: both are mistakes here.
    void refuse_bad_equals(int argc, const char* const* argv) const {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if (a == "--") {
                return;
            }
            const std::size_t eq = a.find('=');
            if (a.compare(0, 2, "--") != 0 || eq == std::string::npos) {
                continue;
            }
            const std::string name = a.substr(0, eq);
            const CLI::Option* opt = app_.get_option_no_throw(name);
            if (opt == nullptr) {
                continue;
            }
            if (opt->get_items_expected_max() == 0) {
                throw UsageError(name + ": takes no value, got '" + a.substr(eq + 1) + "'");
            }
            if (eq + 1 == a.size()) {
                throw UsageError(name + ": expected a value after '='");
            }
        }
    }

    // CLI11's own errors, in our words: "NAME: N required TYPE missing" and
    // "NAME: At least N required but received M" (the values ran out), and
    // "NAME: At Most N required but received M" (given twice).
    std::string message(const CLI::ParseError& e) const {
        const std::string what = e.what();
        const std::string name = what.substr(0, what.find(':'));
        const CLI::Option* opt = app_.get_option_no_throw(name);
        if (opt != nullptr && (what.find(" missing") != std::string::npos ||
                               what.find(": At least ") != std::string::npos)) {
            return name + (opt->get_items_expected_min() == 2
                               ? ": expected two values, " + opt->get_type_name()
                               : ": expected a value after it");
        }
        if (opt != nullptr && what.find(": At Most ") != std::string::npos) {
            return name + ": given more than once";
        }
        return what;
    }

    CLI::App app_;
    std::string program_;
    std::string group_ = "Options";
    std::function<void(const std::string&)> extra_;
};

}  // namespace trac0r_cli

#endif
