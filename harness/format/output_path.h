// Where a verb's output may go (docs/reliability.md, "Output paths and input
// files"): only a regular file or a missing one, never a symbolic link, FIFO,
// device, socket or directory, and never into a goldens folder, which only
// `impulse bless` writes. "-" is standard output for an output that is one file.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace impulse::harness {

// The path that means standard output.
inline constexpr const char* standard_output = "-";
bool is_standard_output(const std::string& path);

// The goldens folders a verb other than bless must not write into: ROOT/goldens
// and, since a path is often given relative to it, ./goldens.
std::vector<std::string> goldens_folders(const std::string& root);

// Throws InputError naming the path and `option` (e.g. "--out") unless the
// path may be written: missing or a regular file (a final symbolic link is
// not followed), and not in any of `protected_folders` once its folder is
// resolved (symbolic links followed, ".." removed), nor in any folder named
// goldens that has a harness/scenes folder beside it. "-" always may.
// Verbs call it before their work, so a bad path costs nothing.
void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& protected_folders);

// Throws InputError naming the path and `option` when it is the same file as
// one of the verb's `inputs` (render TRAJECTORY --out TRAJECTORY): an output
// never replaces what the verb reads. Scenes and project files are refused
// as outputs anyway (check_output_file); this catches the rest.
void refuse_input_as_output(const std::string& option, const std::string& path,
                            const std::vector<std::string>& inputs);

// Whether two output paths land on the same file (neither "-"): their
// folders resolved, so "a.json", "./a.json" and "sub/../a.json" are one file.
bool same_output_file(const std::string& a, const std::string& b);

// The same for a folder that receives several files (check --report, box2d
// --out): it must not be, or be inside, a protected or goldens folder, must be a folder
// if it exists, and cannot be "-".
void check_output_folder(const std::string& option, const std::string& dir,
                         const std::vector<std::string>& protected_folders);

// check_output_file again, then the content to `standard_out` for "-" or to
// the file, atomically (write_file_atomically).
void write_output_file(const std::string& option, const std::string& path,
                       const std::string& content,
                       const std::vector<std::string>& protected_folders,
                       std::ostream& standard_out);

} // namespace impulse::harness
