// Writing an output file so that a failure never loses or truncates the
// file that was there: the bytes go to a temporary file beside the target,
// every write, the flush to disk and the close are checked, and only then
// is the temporary file renamed over the target (rename is atomic within a
// file system). Used for every image trac0r writes.
#ifndef TRAC0R_OUTPUT_FILE_H
#define TRAC0R_OUTPUT_FILE_H

#include <cstddef>
#include <string>

namespace trac0r {

// The file a write to path replaces: path itself, or where the links in
// it lead when path names a symbolic link to an existing file.
std::string replacement_target(const std::string& path);

// Why an output file cannot be written at path ("is a directory",
// "is not a regular file", "cannot create a file in DIR: REASON", ...), or
// "" when it can: found by creating (and removing) a temporary file where
// write_file_replacing would, so a directory no file can be made in (such
// as /proc, even for root) is caught before the work that fills the file.
std::string output_file_problem(const std::string& path);

// An output file being written as described above: write() as often as
// needed, then commit() renames it over the target. Every call throws
// std::runtime_error naming the path and the reason (e.g. "No space left
// on device") on failure; the temporary file is removed on failure and by
// a destructor that runs before commit(), and the old file stays as it was.
class ReplacingFile {
  public:
    explicit ReplacingFile(const std::string& path);
    ~ReplacingFile();
    ReplacingFile(const ReplacingFile&) = delete;
    ReplacingFile& operator=(const ReplacingFile&) = delete;

    void write(const void* data, std::size_t size);
    void commit();

  private:
    [[noreturn]] void fail(const char* step, int error);

    std::string path_;       // as the user named it
    std::string target_;     // replacement_target(path_)
    std::string temporary_;  // beside target_
    int fd_ = -1;
};

// The whole of a file at once, through ReplacingFile.
void write_file_replacing(const std::string& path, const void* data, std::size_t size);

}  // namespace trac0r

#endif
