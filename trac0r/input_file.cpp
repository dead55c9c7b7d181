#include "trac0r/input_file.h"

#include "trac0r/input_checks.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace trac0r {

namespace {

std::uint64_t limit_bytes = 4000000000u;  // 4,000 MB

std::string size_text(std::uint64_t bytes) {
    if (bytes < 1000000) {
        return std::to_string(bytes) + " bytes";
    }
    char text[64];
    std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
    return text;
}

// Closes the descriptor on every way out.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) {
            close(fd);
        }
    }
};

}  // namespace

std::uint64_t input_size_limit() { return limit_bytes; }
void set_input_size_limit(std::uint64_t bytes) { limit_bytes = bytes; }

std::string read_input_file(const std::string& path, const std::string& what) {
    const std::string where = path + ": cannot read " + what + ": ";
    if (path.find('\0') != std::string::npos) {
        // The system would read the name only up to it: another file.
        throw std::runtime_error(printable(path, 200) + ": cannot read " + what +
                                 ": the path holds a NUL byte");
    }
    // Non-blocking, so that opening a FIFO with no writer does not wait;
    // what is opened is checked by its descriptor, not its name.
    const Descriptor file{open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) {
        throw std::runtime_error(path + ": cannot open " + what + ": " + std::strerror(errno));
    }
    struct stat info;
    if (fstat(file.fd, &info) != 0) {
        throw std::runtime_error(where + std::strerror(errno));
    }
    if (S_ISDIR(info.st_mode)) {
        throw std::runtime_error(where + "it is a directory");
    }
    if (!S_ISREG(info.st_mode)) {
        throw std::runtime_error(where + "it is a device, FIFO or socket, not a regular file");
    }
    const std::uint64_t size = static_cast<std::uint64_t>(info.st_size);
    if (size > limit_bytes) {
        throw std::runtime_error(where + "it is " + size_text(size) +
                                 ", over the input size limit of " + size_text(limit_bytes) +
                                 " (--max-input-mb raises it)");
    }
    std::string text(static_cast<std::size_t>(size), '\0');
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = read(file.fd, &text[done], text.size() - done);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0) {
            throw std::runtime_error(where + std::strerror(errno));
        }
        if (n == 0) {
            break;  // the file shrank while being read: what is there
        }
        done += static_cast<std::size_t>(n);
    }
    text.resize(done);
    return text;
}

std::string resolve_path(const std::string& base_dir, const std::string& file) {
    if (base_dir.empty() || file.empty() || file.front() == '/') {
        return file;
    }
    return base_dir.back() == '/' ? base_dir + file : base_dir + "/" + file;
}

}  // namespace trac0r
