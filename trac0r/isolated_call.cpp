#include "trac0r/isolated_call.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>

// The sanitizers' runtime (ASan, UBSan, and libFuzzer through it) has it;
// a plain build does not, and the weak reference is then null.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace trac0r {

namespace {

// The child's message: one tag byte, the payload's length (8 bytes, little
// endian), the payload.
const char tag_result = 'R';
const char tag_error = 'E';
const char tag_out_of_memory = 'M';
const char tag_exception = 'X';
const std::size_t header_size = 9;

// Writes all of `data` to fd (short writes and EINTR continue); false on
// an error (the parent is gone: EPIPE).
bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, std::min<std::size_t>(size, 1u << 20));
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            return false;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

// In the child, before the work: the crash signals' default actions (a
// crash kills the child, which the parent reports), no death callback of
// a sanitizer (libFuzzer's would count a report in the child as its own
// crash and write a crash file), no SIGPIPE (a parent gone reads as a
// failed write), nothing blocked, and the child killed with its parent.
void prepare_child() {
    if (__sanitizer_set_death_callback != nullptr) {
        __sanitizer_set_death_callback(nullptr);
    }
    struct sigaction dfl;
    std::memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    for (int s : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS, SIGXCPU, SIGXFSZ,
                  SIGINT, SIGTERM, SIGHUP, SIGALRM, SIGUSR1, SIGUSR2}) {
        sigaction(s, &dfl, nullptr);
    }
    struct sigaction ign = dfl;
    ign.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ign, nullptr);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    // A crash leaves no core file the size of trac0r behind.
    struct rlimit no_core;
    no_core.rlim_cur = 0;
    no_core.rlim_max = 0;
    setrlimit(RLIMIT_CORE, &no_core);
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
}

// Bounds the child's data (heap and private mappings, RLIMIT_DATA) to
// what it has at the fork plus `bytes` (0: no bound), so that a reader a
// file drives to allocate without end meets std::bad_alloc, not the
// machine's memory. What it has is read from /proc/self/status (VmData);
// without it, no bound.
void limit_child_memory(std::uint64_t bytes) {
    if (bytes == 0) {
        return;
    }
    std::FILE* status = std::fopen("/proc/self/status", "r");
    if (status == nullptr) {
        return;
    }
    char line[256];
    unsigned long long kb = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, status) != nullptr) {
        found = std::sscanf(line, "VmData: %llu kB", &kb) == 1;
    }
    std::fclose(status);
    if (!found) {
        return;
    }
    struct rlimit data;
    data.rlim_cur = static_cast<rlim_t>(kb * 1024u + bytes);
    data.rlim_max = data.rlim_cur;
    setrlimit(RLIMIT_DATA, &data);
}

[[noreturn]] void run_child(int fd, pid_t parent, const std::function<std::string()>& work,
                            std::uint64_t memory_limit) {
    prepare_child();
    limit_child_memory(memory_limit);
#ifdef __linux__
    if (getppid() != parent) {
        _exit(1);  // the parent died before PR_SET_PDEATHSIG took effect
    }
#else
    (void)parent;
#endif
    char tag = tag_result;
    std::string payload;
    try {
        payload = work();
    } catch (const std::runtime_error& e) {
        tag = tag_error;
        payload = e.what();
    } catch (const std::bad_alloc&) {
        tag = tag_out_of_memory;
        payload.clear();
    } catch (const std::exception& e) {
        tag = tag_exception;
        payload = e.what();
    } catch (...) {
        tag = tag_exception;
        payload = "an exception of unknown type";
    }
    char header[header_size];
    header[0] = tag;
    const std::uint64_t size = payload.size();
    for (int i = 0; i < 8; ++i) {
        header[1 + i] = static_cast<char>((size >> (8 * i)) & 0xffu);
    }
    const bool sent =
        write_all(fd, header, sizeof header) && write_all(fd, payload.data(), payload.size());
    _exit(sent ? 0 : 1);
}

}  // namespace

std::uint64_t half_machine_memory() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0
               ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2u
               : 0u;
}

std::string signal_name(int signal) {
    switch (signal) {
    case SIGSEGV:
        return "SIGSEGV";
    case SIGBUS:
        return "SIGBUS";
    case SIGILL:
        return "SIGILL";
    case SIGFPE:
        return "SIGFPE";
    case SIGABRT:
        return "SIGABRT";
    case SIGTRAP:
        return "SIGTRAP";
    case SIGSYS:
        return "SIGSYS";
    case SIGKILL:
        return "SIGKILL";
    case SIGTERM:
        return "SIGTERM";
    case SIGINT:
        return "SIGINT";
    case SIGHUP:
        return "SIGHUP";
    case SIGPIPE:
        return "SIGPIPE";
    case SIGXCPU:
        return "SIGXCPU";
    case SIGXFSZ:
        return "SIGXFSZ";
    default:
        return "signal " + std::to_string(signal);
    }
}

namespace {

thread_local bool isolation_on = true;

// work() in this process, its outcome as the child's would be (no limits).
IsolatedOutcome run_here(const std::function<std::string()>& work) {
    IsolatedOutcome out;
    try {
        out.payload = work();
        out.kind = IsolatedOutcome::Kind::result;
    } catch (const std::runtime_error& e) {
        out.kind = IsolatedOutcome::Kind::error;
        out.payload = e.what();
    } catch (const std::bad_alloc&) {
        out.kind = IsolatedOutcome::Kind::out_of_memory;
    } catch (const std::exception& e) {
        out.kind = IsolatedOutcome::Kind::exception;
        out.detail = e.what();
    }
    return out;
}

}  // namespace

bool readers_isolated() { return isolation_on; }

ReaderIsolation::ReaderIsolation(bool on) : saved_(isolation_on) { isolation_on = on; }

ReaderIsolation::~ReaderIsolation() { isolation_on = saved_; }

IsolatedOutcome run_isolated(const std::function<std::string()>& work, double time_limit_seconds,
                             std::uint64_t memory_limit_bytes) {
    if (!isolation_on) {
        return run_here(work);
    }
    IsolatedOutcome out;
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        out.kind = IsolatedOutcome::Kind::not_started;
        out.detail = std::string("pipe: ") + std::strerror(errno);
        return out;
    }
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        out.kind = IsolatedOutcome::Kind::not_started;
        out.detail = std::string("fork: ") + std::strerror(errno);
        ::close(fds[0]);
        ::close(fds[1]);
        return out;
    }
    if (pid == 0) {
        ::close(fds[0]);
        run_child(fds[1], parent, work, memory_limit_bytes);
    }
    ::close(fds[1]);
    // Everything the child sends, until it closes the pipe (or dies), or
    // the time is up.
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(time_limit_seconds));
    std::string data;
    bool timed_out = false;
    bool out_of_memory = false;  // the parent could not hold what the child sent
    std::string read_error;
    // Nothing may throw past here before the child is reaped: a result too
    // large to hold ends the reading, and the child is killed.
    try {
        std::string buffer(1u << 20, '\0');
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                                  deadline - std::chrono::steady_clock::now())
                                  .count();
            if (left <= 0) {
                timed_out = true;
                break;
            }
            pollfd p;
            p.fd = fds[0];
            p.events = POLLIN;
            p.revents = 0;
            const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, INT_MAX)));
            if (ready < 0) {
                if (errno == EINTR) {
                    continue;
                }
                read_error = std::string("poll: ") + std::strerror(errno);
                break;
            }
            if (ready == 0) {
                continue;  // the deadline decides
            }
            const ssize_t n = ::read(fds[0], &buffer[0], buffer.size());
            if (n < 0) {
                if (errno == EINTR || errno == EAGAIN) {
                    continue;
                }
                read_error = std::string("read: ") + std::strerror(errno);
                break;
            }
            if (n == 0) {
                break;  // end of file: the child closed the pipe or died
            }
            data.append(buffer.data(), static_cast<std::size_t>(n));
        }
    } catch (const std::bad_alloc&) {
        out_of_memory = true;
        read_error = "out of memory";
        data = std::string();
    }
    ::close(fds[0]);
    if (timed_out || !read_error.empty()) {
        ::kill(pid, SIGKILL);
    }
    int status = 0;
    pid_t reaped;
    do {
        reaped = ::waitpid(pid, &status, 0);
    } while (reaped < 0 && errno == EINTR);
    if (timed_out) {
        out.kind = IsolatedOutcome::Kind::timed_out;
        return out;
    }
    if (out_of_memory) {
        out.kind = IsolatedOutcome::Kind::out_of_memory;
        return out;
    }
    if (!read_error.empty()) {
        out.kind = IsolatedOutcome::Kind::broken;
        out.detail = read_error;
        return out;
    }
    if (reaped < 0) {
        out.kind = IsolatedOutcome::Kind::broken;
        out.detail = std::string("waitpid: ") + std::strerror(errno);
        return out;
    }
    if (WIFSIGNALED(status)) {
        out.kind = IsolatedOutcome::Kind::crashed;
        out.detail = signal_name(WTERMSIG(status));
        return out;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        out.kind = IsolatedOutcome::Kind::exited;
        out.detail = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                       : "status " + std::to_string(status);
        return out;
    }
    // An orderly exit: the message must be whole.
    if (data.size() < header_size) {
        out.kind = IsolatedOutcome::Kind::broken;
        out.detail = "a message of " + std::to_string(data.size()) + " bytes, under its header's " +
                     std::to_string(header_size);
        return out;
    }
    std::uint64_t size = 0;
    for (int i = 0; i < 8; ++i) {
        size |= static_cast<std::uint64_t>(static_cast<unsigned char>(data[1 + i])) << (8 * i);
    }
    if (size != data.size() - header_size) {
        out.kind = IsolatedOutcome::Kind::broken;
        out.detail = "a message of " + std::to_string(data.size() - header_size) +
                     " bytes where its header says " + std::to_string(size);
        return out;
    }
    const char tag = data[0];
    data.erase(0, header_size);
    if (tag == tag_result) {
        out.kind = IsolatedOutcome::Kind::result;
        out.payload = std::move(data);
    } else if (tag == tag_error) {
        out.kind = IsolatedOutcome::Kind::error;
        out.payload = std::move(data);
    } else if (tag == tag_out_of_memory) {
        out.kind = IsolatedOutcome::Kind::out_of_memory;
    } else if (tag == tag_exception) {
        out.kind = IsolatedOutcome::Kind::exception;
        out.detail = std::move(data);
    } else {
        out.kind = IsolatedOutcome::Kind::broken;
        out.detail = "a message of unknown kind " + std::to_string(static_cast<unsigned char>(tag));
    }
    return out;
}

}  // namespace trac0r
