// A PLY header checked against its file before assimp reads it
// (trac0r/ply_header.h): counts that the file cannot hold are refused at
// once, with what they promise.
#include "test_support.h"

#include "trac0r/ply_header.h"

using namespace trac0r;
using Catch::Matchers::Contains;

namespace {

std::string ply_error(const std::string& text) {
    try {
        check_ply_header("m.ply", text);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

const std::string ascii_header =
    "ply\nformat ascii 1.0\ncomment made by hand\n"
    "element vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n";

}  // namespace

TEST_CASE("a PLY header whose elements fit the file passes", "[ply]") {
    CHECK(ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").empty());
    // The least ascii data: two characters a property.
    CHECK(ply_error(ascii_header + std::string(3 * 6 + 2, ' ')).empty());
    std::string crlf = ascii_header;
    for (std::size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2)) {
        crlf.replace(at, 1, "\r\n");
    }
    CHECK(ply_error(crlf + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").empty());
    // Binary: 3 x 12 bytes of vertices, then a face of 1 + 3 x 4.
    const std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n";
    CHECK(ply_error(binary + std::string(36 + 13, '\0')).empty());
    // A list's items are not counted (a face may have none).
    CHECK(ply_error(binary + std::string(36 + 1, '\0')).empty());
}

TEST_CASE("a PLY header that promises more than the file holds is refused", "[ply]") {
    // The reproducer's header: 10^9 vertices in a 343-byte file.
    const std::string huge =
        "ply\nformat ascii 1.0\nelement vertex 1000000000\n"
        "property float x\nproperty float y\nproperty float z\n"
        "end_header\n0 0 0\n";
    CHECK(ply_error(huge) ==
          "m.ply: cannot read mesh: the PLY header promises 1000000000 'vertex' elements, "
          "which need at least 6000000000 bytes, but the file has 6 after its header");
    std::string too_many = ascii_header;
    too_many.replace(too_many.find("vertex 3"), 8, "vertex 100000000000000000000");
    CHECK(ply_error(too_many) ==
          "m.ply: cannot read mesh: the PLY element 'vertex' has the count "
          "'100000000000000000000': expected a whole number below 2^32");
    CHECK(ply_error("ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty double x\n"
                    "end_header\n" +
                    std::string(15, '\0')) ==
          "m.ply: cannot read mesh: the PLY header promises 2 'vertex' elements, which need at "
          "least 16 bytes, but the file has 15 after its header");
    CHECK_THAT(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"),
               Contains("the PLY header has no end_header line"));
    CHECK_THAT(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                         "end_header0\n1 \n"),
               Contains("the PLY header has no end_header line"));
    CHECK_THAT(ply_error("ply\nformat binary_middle_endian 1.0\nend_header\n"),
               Contains("the PLY format 'binary_middle_endian': expected ascii"));
    CHECK_THAT(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\n"
                         "end_header\n1 \n"),
               Contains("a PLY property of type 'half'"));
    CHECK_THAT(ply_error("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n"),
               Contains("has the count '-1': expected a whole number below 2^32"));
}

TEST_CASE("the reproducers' PLY files end at once with what their headers promise", "[ply][mesh]") {
    // Through the scene loader, in well under a second (assimp took them
    // past 8 GB).
    TempDir dir;
    dir.write("huge.ply",
              "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
              "property float x\nproperty float y\nproperty float z\n"
              "element face 12\nproperty list uchar int vertex_indices\n"
              "end_header\n" +
                  std::string(252, '\0'));
    const std::string json =
        dir.write("s.json", R"({"materials": {"w": {"type": "diffuse", "color": [1, 1, 1]}},
                      "shapes": [{"type": "mesh", "file": "huge.ply", "material": "w"}]})");
    try {
        load_scene_file(json);
        FAIL("huge.ply loaded");
    } catch (const SceneError& e) {
        CHECK_THAT(e.what(), Contains("huge.ply: cannot read mesh: the PLY header promises "
                                      "1000000000 'vertex' elements"));
    }
}
