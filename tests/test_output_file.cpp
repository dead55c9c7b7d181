// Output files (trac0r/output_file.h, issue 33 point 1): a write that
// fails leaves the old file as it was and says why; nothing half-written
// or temporary is left behind; what cannot be written is found before a
// render starts. A full disk is played by a file-size limit (RLIMIT_FSIZE,
// with SIGXFSZ ignored): the write then fails with EFBIG, as it fails with
// ENOSPC on a full disk, through the same checks.
#include "trac0r/image_io.h"
#include "trac0r/input_checks.h"
#include "trac0r/output_file.h"
#include "viewer_process.h"

#include <catch2/catch.hpp>

#include <dirent.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using trac0r_test::read_text_file;

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// A fresh, empty directory for one test.
std::string fresh_directory(const std::string& name) {
    REQUIRE(system(("rm -rf " + name + " && mkdir " + name).c_str()) == 0);
    return name;
}

std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> names;
    DIR* d = opendir(dir.c_str());
    REQUIRE(d != nullptr);
    while (dirent* e = readdir(d)) {
        const std::string n = e->d_name;
        if (n != "." && n != "..") {
            names.push_back(n);
        }
    }
    closedir(d);
    return names;
}

// Files larger than `bytes` cannot be written while one lives.
struct FileSizeLimit {
    rlimit saved;
    void (*saved_handler)(int);
    explicit FileSizeLimit(rlim_t bytes) {
        REQUIRE(getrlimit(RLIMIT_FSIZE, &saved) == 0);
        saved_handler = std::signal(SIGXFSZ, SIG_IGN);
        rlimit limit = saved;
        limit.rlim_cur = bytes;
        REQUIRE(setrlimit(RLIMIT_FSIZE, &limit) == 0);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &saved);
        std::signal(SIGXFSZ, saved_handler);
    }
};

trac0r::Image grey_image(int width, int height) {
    trac0r::Image image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height, glm::vec3(0.25f));
    return image;
}

}  // namespace

TEST_CASE("an output file is written whole, with nothing left beside it", "[output]") {
    const std::string dir = fresh_directory("out_whole");
    write_text(dir + "/a.txt", "old");
    REQUIRE(chmod((dir + "/a.txt").c_str(), 0640) == 0);
    trac0r::write_file_replacing(dir + "/a.txt", "new bytes", 9);
    CHECK(read_text_file(dir + "/a.txt") == "new bytes");
    CHECK(entries(dir) == std::vector<std::string>{"a.txt"});
    struct stat info;
    REQUIRE(stat((dir + "/a.txt").c_str(), &info) == 0);
    CHECK((info.st_mode & 07777) == 0640);  // the old file's permissions kept

    // Through a link, the file it leads to is replaced; the link stays.
    REQUIRE(symlink("a.txt", (dir + "/link.txt").c_str()) == 0);
    trac0r::write_file_replacing(dir + "/link.txt", "via link", 8);
    CHECK(read_text_file(dir + "/a.txt") == "via link");
    struct stat link;
    REQUIRE(lstat((dir + "/link.txt").c_str(), &link) == 0);
    CHECK(S_ISLNK(link.st_mode));
}

TEST_CASE("a write that fails leaves the old file as it was", "[output]") {
    const std::string dir = fresh_directory("out_full");
    const std::string pfm = dir + "/old.pfm";
    const std::string png = dir + "/old.png";
    write_text(pfm, "the old PFM");
    write_text(png, "the old PNG");
    // A 64 x 64 grey PNG is a few hundred bytes, its PFM 48 KB: a noisy PNG
    // of 256 x 256 is tens of kilobytes.
    trac0r::Image noisy = grey_image(256, 256);
    for (std::size_t i = 0; i < noisy.pixels.size(); ++i) {
        noisy.pixels[i] = glm::vec3(static_cast<float>((i * 2654435761u) % 1000) / 1000.0f);
    }
    {
        const FileSizeLimit limit(4096);
        for (const std::string& path : {pfm, png}) {
            INFO(path);
            try {
                trac0r::write_image(path, noisy);
                FAIL("no error over the file-size limit");
            } catch (const std::runtime_error& e) {
                const std::string message = e.what();
                CHECK(message.find(path + ": write failed: File too large") == 0);
                CHECK(message.find("unchanged") != std::string::npos);
            }
        }
    }
    CHECK(read_text_file(pfm) == "the old PFM");
    CHECK(read_text_file(png) == "the old PNG");
    CHECK(entries(dir).size() == 2);  // no temporary file left
}

TEST_CASE("what cannot hold an output is found before writing", "[output]") {
    const std::string dir = fresh_directory("out_bad");
    REQUIRE(symlink("/dev/full", (dir + "/full.png").c_str()) == 0);
    CHECK(trac0r::output_file_problem(dir + "/full.png") ==
          "leads to /dev/full, a device, FIFO or socket, not a regular file");
    CHECK(trac0r::output_file_problem("/dev/null") ==
          "is a device, FIFO or socket, not a regular file");
    CHECK(trac0r::output_file_problem(dir) == "is a directory");
    CHECK(trac0r::output_file_problem(dir + "/none/x.png") ==
          "directory " + dir + "/none does not exist");
    // /proc exists and root may "write" it by access(), but no file can be
    // made there.
    CHECK(trac0r::unwritable_reason("/proc/version.png").find("cannot create a file in /proc") ==
          0);
    CHECK_THROWS_WITH(trac0r::write_image(dir + "/full.png", grey_image(4, 4)),
                      Catch::Contains("full.png: cannot be written: leads to /dev/full"));
    CHECK(trac0r::output_file_problem(dir + "/fine.png").empty());
    CHECK(entries(dir) == std::vector<std::string>{"full.png"});
}

TEST_CASE("the viewer on a full disk says so, exits 1 and keeps the old image", "[output]") {
    const std::string dir = fresh_directory("out_viewer");
    write_text(dir + "/x.pfm", "old image");
    // `ulimit -f 8`: at most 8 blocks of 512 bytes (dash) or 1 KiB (bash);
    // the 200 x 150 PFM is 360 KB.
    const trac0r_test::ViewerRun r = trac0r_test::run_viewer_process(
        "--headless --width 200 --height 150 --spp 1 --output " + dir + "/x.pfm", "ulimit -f 8;");
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(dir + "/x.pfm: write failed: File too large") != std::string::npos);
    CHECK(r.err.find("wrote") == std::string::npos);
    CHECK(read_text_file(dir + "/x.pfm") == "old image");
    CHECK(entries(dir).size() == 1);

    // A link to /dev/full is refused before the render, with exit 2.
    REQUIRE(symlink("/dev/full", (dir + "/full.png").c_str()) == 0);
    const trac0r_test::ViewerRun f = trac0r_test::run_viewer_process(
        "--headless --width 8 --height 6 --spp 1 --output " + dir + "/full.png");
    CHECK(f.exit_code == 2);
    CHECK(f.err == "trac0r_viewer: --output " + dir +
                       "/full.png: cannot be written (leads to /dev/full, a device, FIFO or "
                       "socket, not a regular file)\n");
}
