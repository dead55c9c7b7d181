#include "trac0r/ply_header.h"

#include "trac0r/input_checks.h"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace trac0r {

namespace {

// Where the data begins: just after the end_header line (LF or CR LF),
// within the first megabyte; std::string::npos where there is none.
std::size_t data_start(const std::string& text) {
    const std::size_t limit = std::min<std::size_t>(text.size(), 1u << 20);
    for (std::size_t at = text.find("\nend_header"); at != std::string::npos && at < limit;
         at = text.find("\nend_header", at + 1)) {
        const std::size_t after = at + 11;
        if (after < text.size() && text[after] == '\n') {
            return after + 1;
        }
        if (after + 1 < text.size() && text[after] == '\r' && text[after + 1] == '\n') {
            return after + 2;
        }
    }
    return std::string::npos;
}

// The bytes of a PLY scalar type in binary; 0 for a name PLY does not have.
std::uint64_t type_bytes(const std::string& type) {
    static const struct {
        const char* name;
        std::uint64_t bytes;
    } types[] = {{"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},
                 {"short", 2}, {"ushort", 2},  {"int16", 2},  {"uint16", 2},
                 {"int", 4},   {"uint", 4},    {"int32", 4},  {"uint32", 4},
                 {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (const auto& t : types) {
        if (type == t.name) {
            return t.bytes;
        }
    }
    return 0;
}

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t binary_bytes = 0;  // the least one takes in binary
    std::uint64_t properties = 0;
};

}  // namespace

void check_ply_header(const std::string& path, const std::string& text) {
    const auto fail = [&](const std::string& why) {
        throw std::runtime_error(path + ": cannot read mesh: " + why);
    };
    const std::size_t start = data_start(text);
    if (start == std::string::npos) {
        fail("the PLY header has no end_header line (a line of its own)");
    }
    std::istringstream header(text.substr(0, start));
    std::string line;
    bool ascii = true;
    std::vector<Element> elements;
    while (std::getline(header, line)) {
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key == "format") {
            std::string format;
            words >> format;
            if (format != "ascii" && format != "binary_little_endian" &&
                format != "binary_big_endian") {
                fail("the PLY format '" + printable(format, 40) +
                     "': expected ascii, binary_little_endian or binary_big_endian");
            }
            ascii = format == "ascii";
        } else if (key == "element") {
            Element e;
            std::string count;
            words >> e.name >> count;
            if (count.empty() || count.size() > 10 ||
                !std::all_of(count.begin(), count.end(),
                             [](char c) { return c >= '0' && c <= '9'; }) ||
                std::stoull(count) > 0xffffffffull) {
                fail("the PLY element '" + printable(e.name, 40) + "' has the count '" +
                     printable(count, 40) + "': expected a whole number below 2^32");
            }
            e.count = std::stoull(count);
            elements.push_back(e);
        } else if (key == "property" && !elements.empty()) {
            std::string type;
            words >> type;
            std::uint64_t bytes = 0;
            if (type == "list") {
                std::string count_type;
                std::string item_type;
                words >> count_type >> item_type;
                bytes = type_bytes(count_type);
                if (bytes == 0 || type_bytes(item_type) == 0) {
                    fail("a PLY list property of types '" + printable(count_type, 20) + "' and '" +
                         printable(item_type, 20) + "': expected PLY's scalar types");
                }
            } else {
                bytes = type_bytes(type);
                if (bytes == 0) {
                    fail("a PLY property of type '" + printable(type, 20) +
                         "': expected one of PLY's scalar types");
                }
            }
            elements.back().binary_bytes += bytes;
            ++elements.back().properties;
        }
    }
    const std::uint64_t available = text.size() - start;
    std::uint64_t needed = 0;
    for (const Element& e : elements) {
        // At most 2^32 x 2^20 properties x 8 bytes: no overflow in 64 bits.
        const std::uint64_t each = ascii ? 2 * e.properties : e.binary_bytes;
        needed += e.count * each;
        if (needed > available) {
            fail("the PLY header promises " + std::to_string(e.count) + " '" +
                 printable(e.name, 40) + "' elements, which need at least " +
                 std::to_string(e.count * each) + " bytes, but the file has " +
                 std::to_string(available) + " after its header");
        }
    }
}

}  // namespace trac0r
