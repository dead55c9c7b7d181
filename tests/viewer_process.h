// Running trac0r_viewer (or a benchmark program) as a child process, for
// the tests of what a user sees of it: its exit code, its stdout and its
// stderr, kept apart.
#ifndef TRAC0R_TESTS_VIEWER_PROCESS_H
#define TRAC0R_TESTS_VIEWER_PROCESS_H

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace trac0r_test {

struct ViewerRun {
    int exit_code;  // -1: killed by a signal (a crash, or the time limit)
    std::string out;
    std::string err;
};

inline std::string read_text_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// `prefix` goes before the program (e.g. "cd dir &&" or "env -u DISPLAY");
// a program that hangs is killed after `seconds`, and reads as exit code 124.
inline ViewerRun run_process(const std::string& program, const std::string& args,
                             const std::string& prefix = "", int seconds = 120) {
    // Absolute: the prefix may change directory.
    char cwd[4096];
    const std::string err_path = std::string(getcwd(cwd, sizeof cwd) ? cwd : ".") +
                                 "/viewer_process_stderr_" + std::to_string(getpid()) + ".txt";
    const std::string command = prefix + " timeout " + std::to_string(seconds) + " " + program +
                                " " + args + " 2>" + err_path;
    FILE* pipe = popen(command.c_str(), "r");
    ViewerRun run{-1, "", ""};
    if (!pipe) {
        run.err = "popen failed: " + command;
        return run;
    }
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) {
        run.out += buffer;
    }
    const int status = pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.err = read_text_file(err_path);
    std::remove(err_path.c_str());
    return run;
}

inline ViewerRun run_viewer_process(const std::string& args, const std::string& prefix = "",
                                    int seconds = 120) {
    return run_process(TRAC0R_VIEWER, args, prefix, seconds);
}

}  // namespace trac0r_test

#endif
