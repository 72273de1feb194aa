#include "output_path.h"

#include "atomic_file.h"
#include "file_kind.h"
#include "input_error.h"

#include <climits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <unistd.h>
#include <utility>

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

} // namespace

bool same_output_file(const std::string& a, const std::string& b) {
    return !is_standard_output(a) && !is_standard_output(b) &&
           landing_place(a).lexically_normal() == landing_place(b).lexically_normal();
}

namespace {

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

// One top-level string member of a JSON document (its "schema", say), read
// as a stream that stops as soon as it is known (or the document is not an
// object): no tree is built, so any file, however large or deep, costs one
// pass at most.
class TopLevelString : public nlohmann::json_sax<nlohmann::json> {
  public:
    explicit TopLevelString(std::string key) : key_(std::move(key)) {}
    std::optional<std::string> value;
    bool null() override { return scalar(); }
    bool boolean(bool) override { return scalar(); }
    bool number_integer(number_integer_t) override { return scalar(); }
    bool number_unsigned(number_unsigned_t) override { return scalar(); }
    bool number_float(number_float_t, const string_t&) override { return scalar(); }
    bool string(string_t& text) override {
        if (depth_ == 1 && wanted_next_) {
            value = text;
            return false; // found: stop reading
        }
        return scalar();
    }
    bool binary(binary_t&) override { return scalar(); }
    bool start_object(std::size_t) override { return open(); }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return depth_ > 0 && open(); }
    bool end_array() override { return close(); }
    bool key(string_t& name) override {
        wanted_next_ = depth_ == 1 && name == key_;
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

  private:
    std::string key_;
    int depth_ = 0;
    bool wanted_next_ = false;
    bool scalar() {
        wanted_next_ = false;
        return depth_ > 0;
    }
    bool open() {
        wanted_next_ = false;
        ++depth_;
        return true;
    }
    bool close() {
        --depth_;
        return depth_ > 0;
    }
};

// The top-level string member `key` of the JSON file at `path`; nothing when
// the file cannot be read, is not an object or has no such string.
std::optional<std::string> top_level_string(const fs::path& path, const std::string& key) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        return std::nullopt;
    }
    TopLevelString sax(key);
    nlohmann::json::sax_parse(in, &sax, nlohmann::json::input_format_t::json, false);
    return sax.value;
}

// The goldens folder of the project whose file is in `folder`, if one is: its
// "goldens" member, or "goldens" when the file names none or is broken (the
// default; project/ validates the member, this only reads it). So a project's
// goldens are refused as an output from wherever the verb runs, not only from
// inside the project (an outside review: `run --out ../app/goldens/x.json` run
// outside ../app replaced that golden).
std::optional<fs::path> project_goldens(const fs::path& folder) {
    const fs::path file = folder / "impulse.json";
    if (kind_at(file.string()) == FileKind::missing) {
        return std::nullopt;
    }
    std::error_code error;
    std::optional<std::string> named; // a FIFO or device is never opened
    if (fs::is_regular_file(fs::status(file, error))) {
        named = top_level_string(file, "goldens");
    }
    const fs::path goldens = resolved(folder / named.value_or("goldens"));
    // A broken file's "." or "..": protect the default, not the whole project.
    if (goldens == folder || !is_within(goldens, folder)) {
        return resolved(folder / "goldens");
    }
    return goldens;
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
        if (const auto goldens = project_goldens(up)) {
            folders.push_back(*goldens);
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

// A file at an output path that is one impulse reads and never writes: a
// scene or a project file, by the schema it declares. A verb's outputs are
// trajectories, results, reports and pictures, so one written over a scene
// can only destroy the user's work (an outside review: `run pile --out
// scenes/pile.json` and `check --junit scenes/pile.json` replaced the scene,
// exit 0). The families are those of scene.h and project.h, which this
// lowest module cannot include.
void refuse_input_file(const std::string& option, const std::string& path) {
    // Unreadable or without a schema: nothing of the user's to recognise.
    const std::string schema = top_level_string(path, "schema").value_or("");
    const std::pair<const char*, const char*> families[] = {{"impulse/scene@", "a scene"},
                                                            {"impulse/project@", "a project"}};
    for (const auto& [family, what] : families) {
        if (schema.rfind(family, 0) == 0) {
            throw InputError(path, option,
                             "is " + std::string(what) + " file (schema " + schema +
                                 "); impulse never writes over one, so give another path");
        }
    }
}

// A path the system could not create: empty, or a name or whole path longer
// than the file system takes (checked before the work, not found after it).
void refuse_impossible_name(const std::string& option, const std::string& path) {
    if (path.empty()) {
        throw InputError(option, "", "is empty; give a file name (- is standard output)");
    }
    const fs::path p(path);
    const fs::path folder = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    const std::size_t longest = name_max > 0 ? static_cast<std::size_t>(name_max) : NAME_MAX;
    const std::string name = p.filename().string();
    // The temporary file beside it adds ".tmp-XXXXXX" (11 bytes) to the name.
    if (name.size() + 11 > longest) {
        throw InputError(path, option,
                         "has a file name of " + std::to_string(name.size()) +
                             " bytes; with the temporary file's \".tmp-XXXXXX\" it passes the " +
                             std::to_string(longest) + " this file system takes");
    }
    if (path.size() + 11 >= PATH_MAX) {
        throw InputError(path, option,
                         "is " + std::to_string(path.size()) + " bytes long, more than the " +
                             std::to_string(PATH_MAX - 12) + " a path may have here");
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
    refuse_impossible_name(option, path);
    const FileKind kind = kind_at(path);
    if (kind != FileKind::missing && kind != FileKind::regular) {
        throw InputError(path, option,
                         std::string("is ") + kind_words(kind) +
                             "; impulse writes only regular files (- is standard output)");
    }
    refuse_protected(option, path, landing_place(path), protected_folders);
    refuse_missing_folder(option, path);
    if (kind == FileKind::regular) {
        refuse_input_file(option, path);
    }
}

void refuse_input_as_output(const std::string& option, const std::string& path,
                            const std::vector<std::string>& inputs) {
    if (is_standard_output(path)) {
        return;
    }
    for (const std::string& input : inputs) {
        std::error_code error;
        if (fs::equivalent(path, input, error) && !error) {
            throw InputError(path, option,
                             "is " + printable_path(input) +
                                 ", which this command reads; give another path");
        }
    }
}

void check_output_folder(const std::string& option, const std::string& dir,
                         const std::vector<std::string>& protected_folders) {
    if (is_standard_output(dir)) {
        throw InputError(dir, option,
                         "is standard output, which takes one file; this option needs a folder");
    }
    if (dir.empty()) {
        throw InputError(option, "", "is empty; give a folder (. is the current one)");
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
