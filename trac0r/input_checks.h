// Checks of what users write, shared by the scene loader, trac0r_viewer
// and the benchmark programs: how a number may be written (command lines,
// OBJ files), and whether an output path can be written before the work
// that fills it starts.
#ifndef TRAC0R_INPUT_CHECKS_H
#define TRAC0R_INPUT_CHECKS_H

#include <string>

namespace trac0r {

// Whether text is a number written in decimal, as the usage texts and OBJ
// files show them: an optional '-', digits with at most one '.', and an optional
// exponent (e or E, an optional sign, digits): "3", "-0.5", ".5", "1e+06".
// Not what strtol and strtod also take: a leading space or '+',
// hexadecimal ("0x10"), "inf", "nan".
bool is_decimal_number(const std::string& text);
// The same for the characters [begin, end).
bool is_decimal_number(const char* begin, const char* end);

// text read as a number written in decimal (is_decimal_number), all of it,
// into *value; false where it is not one, or is out of the type's range
// (for a double also one that underflows: strtod's ERANGE).
bool parse_decimal(const std::string& text, long* value);
bool parse_decimal(const std::string& text, double* value);

// text as a one-line message may quote it: control bytes (C0, DEL, C1)
// written as \xNN, and cut to at most max_length bytes with "..." (a word
// of a file may be a megabyte long, or hold a terminal's escape sequence),
// never inside a UTF-8 character or an escape.
std::string printable(const std::string& text, std::size_t max_length);

// Whether `path` ends in `suffix` (lower case, such as ".png") in any case:
// how a file's kind is told by its extension.
bool has_extension(const std::string& path, const std::string& suffix);

// Why path cannot be written ("is a directory", "directory d does not
// exist", "exists and is not writable", ...), or "" when it can: a
// temporary file is made and removed where the output will be written
// (output_file_problem), so even for root a place no file can be made in
// is found before the work that fills it.
std::string unwritable_reason(const std::string& path);

// Whether path names an existing directory.
bool is_directory(const std::string& path);

// Whether a and b name the same file: the same name, or (where both exist)
// the same device and inode, as a link or another spelling of the path
// gives. For an output that would overwrite an input.
bool same_file(const std::string& a, const std::string& b);

}  // namespace trac0r

#endif
