#include "output_path.h"

#include "atomic_file.h"
#include "file_kind.h"
#include "input_error.h"

#include <filesystem>
#include <iterator>
#include <ostream>
#include <unistd.h>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

// Symbolic links followed and ".." removed as far as the path exists; the
// rest kept as written. Lexically normal when even that fails.
fs::path resolved(const fs::path& path) {
    std::error_code error;
    fs::path absolute = fs::absolute(path, error);
    if (error) {
        absolute = path;
    }
    fs::path canonical = fs::weakly_canonical(absolute, error);
    return error ? absolute.lexically_normal() : canonical;
}

// Where a write to `path` lands: its folder resolved, its last name as
// written (rename() replaces a final symbolic link, it does not follow it).
fs::path landing_place(const std::string& path) {
    const fs::path p(path);
    const fs::path name = p.filename();
    if (name.empty() || name == "." || name == "..") {
        return resolved(p);
    }
    return resolved(p.parent_path().empty() ? fs::path(".") : p.parent_path()) / name;
}

// `inner` is `folder` or lies inside it, component by component.
bool is_within(const fs::path& inner, const fs::path& folder) {
    auto i = inner.begin();
    for (auto f = folder.begin(); f != folder.end(); ++f, ++i) {
        if (f->empty() && std::next(f) == folder.end()) {
            break; // a trailing separator
        }
        if (i == inner.end() || *i != *f) {
            return false;
        }
    }
    return true;
}

// A folder named goldens beside a harness/scenes folder is a repository's
// goldens folder, whatever --root and the current directory say.
bool is_goldens_of_a_root(const fs::path& folder) {
    std::error_code error;
    return folder.filename() == "goldens" &&
           fs::is_directory(folder.parent_path() / "harness" / "scenes", error);
}

void refuse_protected(const std::string& option, const std::string& path, const fs::path& place,
                      const std::vector<std::string>& protected_folders) {
    std::vector<fs::path> folders;
    for (const std::string& folder : protected_folders) {
        folders.push_back(resolved(folder));
    }
    for (fs::path up = place; up.has_relative_path(); up = up.parent_path()) {
        if (is_goldens_of_a_root(up)) {
            folders.push_back(up);
        }
    }
    for (const fs::path& goldens : folders) {
        if (is_within(place, goldens)) {
            throw InputError(path, option,
                             "is in the goldens folder " + printable_path(goldens.string()) +
                                 "; only impulse bless writes there");
        }
    }
}

// The folder a file is written into must exist, be a folder and take new
// files (the atomic write makes its temporary file there): checked with the
// other outputs before the work, so a second output that cannot be written
// never leaves the first one replaced (run --out and --json).
void refuse_missing_folder(const std::string& option, const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    const fs::path folder = parent.empty() ? fs::path(".") : parent;
    std::error_code error;
    const fs::file_status status = fs::status(folder, error);
    if (!fs::exists(status)) {
        throw InputError(path, option,
                         "cannot be written: its folder " + printable_path(folder.string()) +
                             " does not exist");
    }
    if (!fs::is_directory(status)) {
        throw InputError(path, option,
                         "cannot be written: " + printable_path(folder.string()) +
                             " is not a folder");
    }
    if (::access(folder.c_str(), W_OK | X_OK) != 0) {
        throw InputError(path, option,
                         "cannot be written: the folder " + printable_path(folder.string()) +
                             " does not let this user create files in it");
    }
}

} // namespace

bool is_standard_output(const std::string& path) {
    return path == standard_output;
}

std::vector<std::string> goldens_folders(const std::string& root) {
    std::vector<std::string> folders = {(fs::path(root) / "goldens").string()};
    if (resolved(folders.front()) != resolved("goldens")) {
        folders.push_back("goldens");
    }
    return folders;
}

void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& protected_folders) {
    if (is_standard_output(path)) {
        return;
    }
    const FileKind kind = kind_at(path);
    if (kind != FileKind::missing && kind != FileKind::regular) {
        throw InputError(path, option,
                         std::string("is ") + kind_words(kind) +
                             "; impulse writes only regular files (- is standard output)");
    }
    refuse_protected(option, path, landing_place(path), protected_folders);
    refuse_missing_folder(option, path);
}

void check_output_folder(const std::string& option, const std::string& dir,
                         const std::vector<std::string>& protected_folders) {
    if (is_standard_output(dir)) {
        throw InputError(dir, option,
                         "is standard output, which takes one file; this option needs a folder");
    }
    // The files go inside, so a symbolic link to a folder is followed.
    std::error_code error;
    const fs::file_status status = fs::status(dir, error);
    if (!error && fs::exists(status) && !fs::is_directory(status)) {
        throw InputError(dir, option, "is not a folder; this option needs one");
    }
    refuse_protected(option, dir, resolved(dir), protected_folders);
}

void write_output_file(const std::string& option, const std::string& path,
                       const std::string& content,
                       const std::vector<std::string>& protected_folders,
                       std::ostream& standard_out) {
    check_output_file(option, path, protected_folders);
    if (is_standard_output(path)) {
        standard_out << content << std::flush;
        return;
    }
    write_file_atomically(path, content);
}

} // namespace impulse::harness
