// Running work that may crash, hang or corrupt memory (a third-party
// reader given a malformed file: assimp's) in a forked child process, so
// that it cannot take trac0r down. The child runs the work, sends what it
// returns through a pipe and _exits; the parent reads everything (within
// a time limit), then reaps the child and says what became of it.
//
// The fork may happen while other threads run (OpenMP's pool, SDL's): the
// child runs only the work, which must not wait for another thread (a
// lock one held at the fork stays held in the child), and then _exits
// without running destructors or atexit handlers. So the work must not
// use OpenMP either: the child's copy of its thread pool has no threads,
// and a parallel region would wait for them until the time limit. In the child, the
// crash signals take their default action (no sanitizer's or fuzzer's
// handler turns a crash into a report of the whole program; a sanitizer's
// report in the child does not run the fuzzer's death callback), and the
// child dies with its parent (Linux).
#ifndef TRAC0R_ISOLATED_CALL_H
#define TRAC0R_ISOLATED_CALL_H

#include <cstdint>
#include <functional>
#include <string>

namespace trac0r {

struct IsolatedOutcome {
    enum class Kind {
        result,       // the work returned: `payload` is what it returned
        error,        // it threw std::runtime_error: `payload` is its what()
        out_of_memory,  // it threw std::bad_alloc
        exception,    // it threw another exception: `detail` is its what()
        crashed,      // the child died of a signal: `detail` names it ("SIGSEGV")
        exited,       // the child exited with a status other than 0: `detail` says it
        timed_out,    // the child ran past the limit and was killed
        broken,       // what came through the pipe was cut short or malformed: `detail`
        not_started,  // no pipe or no child process: `detail` says why
    };
    Kind kind = Kind::broken;
    std::string payload;
    std::string detail;
};

// Runs work() in a forked child within `time_limit_seconds` (> 0), and
// with `memory_limit_bytes` more data than it has at the fork (0: no
// limit; beyond it allocations fail, and the outcome is out_of_memory).
// Where the calling thread has turned isolation off (ReaderIsolation),
// work() runs in this process, without the limits, its exceptions as the
// child's would be reported.
IsolatedOutcome run_isolated(const std::function<std::string()>& work,
                             double time_limit_seconds, std::uint64_t memory_limit_bytes = 0);

// Whether run_isolated forks on this thread (true unless a ReaderIsolation
// of false is alive on it).
bool readers_isolated();

// For its lifetime, run_isolated on this thread forks (on) or not (off):
// LoadOptions::isolate_readers for one load.
class ReaderIsolation {
  public:
    explicit ReaderIsolation(bool on);
    ~ReaderIsolation();
    ReaderIsolation(const ReaderIsolation&) = delete;
    ReaderIsolation& operator=(const ReaderIsolation&) = delete;

  private:
    bool saved_;
};

// Half the machine's physical memory (0 where it cannot be known): what
// a reader's child may take beyond the program's own (run_isolated's
// memory limit for the mesh and image readers).
std::uint64_t half_machine_memory();

// "SIGSEGV" for SIGSEGV, ...; "signal N" for one it does not know.
std::string signal_name(int signal);

}  // namespace trac0r

#endif
