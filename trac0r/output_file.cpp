#include "trac0r/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace trac0r {

namespace {

std::string directory_of(const std::string& path) {
    const std::string::size_type slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

std::string base_name_of(const std::string& path) {
    const std::string::size_type slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// A temporary file beside target, open for writing; its name goes to
// *name. -1 with errno set where none can be made.
int create_temporary_beside(const std::string& target, std::string* name) {
    std::string pattern = directory_of(target) + "/." + base_name_of(target) + ".tmp-XXXXXX";
    const int fd = mkstemp(&pattern[0]);
    *name = pattern;
    return fd;
}

// Creates a file of target's kind: the old file's permissions where there
// is one, else those a new file gets (0666 less the umask).
void copy_permissions(int fd, const std::string& target) {
    struct stat old;
    mode_t mode;
    if (stat(target.c_str(), &old) == 0) {
        mode = old.st_mode & 07777;
    } else {
        const mode_t mask = umask(0);
        umask(mask);
        mode = 0666 & ~mask;
    }
    (void)fchmod(fd, mode);  // a file system without modes keeps the default
}

bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = write(fd, data, size);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            if (n == 0) {
                errno = EIO;
            }
            return false;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

}  // namespace

std::string replacement_target(const std::string& path) {
    struct stat link;
    if (lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
        char resolved[PATH_MAX];
        if (realpath(path.c_str(), resolved)) {
            return resolved;
        }
    }
    return path;
}

namespace {

// What output_file_problem finds without making a file: the target's kind
// and its directory.
std::string target_problem(const std::string& path, const std::string& target) {
    if (path.empty()) {
        return "the path is empty";
    }
    struct stat info;
    if (stat(target.c_str(), &info) == 0) {
        if (S_ISDIR(info.st_mode)) {
            return "is a directory";
        }
        if (!S_ISREG(info.st_mode)) {
            return target == path
                       ? "is a device, FIFO or socket, not a regular file"
                       : "leads to " + target + ", a device, FIFO or socket, not a regular file";
        }
    }
    const std::string dir = directory_of(target);
    if (stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
        return "directory " + dir + " does not exist";
    }
    return "";
}

std::string cannot_create_in(const std::string& target, int error) {
    return "cannot create a file in " + directory_of(target) + ": " + std::strerror(error);
}

}  // namespace

std::string output_file_problem(const std::string& path) {
    const std::string target = replacement_target(path);
    const std::string problem = target_problem(path, target);
    if (!problem.empty()) {
        return problem;
    }
    std::string temporary;
    const int fd = create_temporary_beside(target, &temporary);
    if (fd < 0) {
        return cannot_create_in(target, errno);
    }
    close(fd);
    unlink(temporary.c_str());
    return "";
}

// The temporary file itself is the test that one can be made: no probe
// first, as output_file_problem makes for a check before the work.
ReplacingFile::ReplacingFile(const std::string& path)
    : path_(path), target_(replacement_target(path)) {
    std::string problem = target_problem(path, target_);
    if (problem.empty()) {
        fd_ = create_temporary_beside(target_, &temporary_);
        if (fd_ < 0) {
            problem = cannot_create_in(target_, errno);
        }
    }
    if (!problem.empty()) {
        throw std::runtime_error(path + ": cannot be written: " + problem);
    }
    copy_permissions(fd_, target_);
}

ReplacingFile::~ReplacingFile() {
    if (fd_ >= 0) {
        close(fd_);
        unlink(temporary_.c_str());
    }
}

void ReplacingFile::fail(const char* step, int error) {
    if (fd_ >= 0) {
        close(fd_);
        fd_ = -1;
    }
    unlink(temporary_.c_str());
    throw std::runtime_error(path_ + ": " + step + ": " + std::strerror(error) +
                             " (the file that was there, if any, is unchanged)");
}

void ReplacingFile::write(const void* data, std::size_t size) {
    if (!write_all(fd_, static_cast<const char*>(data), size)) {
        fail("write failed", errno);
    }
}

void ReplacingFile::commit() {
    if (fsync(fd_) != 0) {
        fail("flush to disk failed", errno);
    }
    const int fd = fd_;
    fd_ = -1;
    if (close(fd) != 0) {
        fail("close failed", errno);
    }
    if (rename(temporary_.c_str(), target_.c_str()) != 0) {
        fail("rename over it failed", errno);
    }
}

void write_file_replacing(const std::string& path, const void* data, std::size_t size) {
    ReplacingFile file(path);
    file.write(data, size);
    file.commit();
}

}  // namespace trac0r
