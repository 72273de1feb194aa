// Fuzz target: the CLI's output paths, write_output_file() (docs/reliability.md,
// "Output paths and input files").
//
// The input is KIND, NAME_LENGTH, NAME, CONTENT. In a fresh temporary folder
// the target path is made to be of KIND: missing, a regular file, a symbolic
// link to a file, a dangling link, a FIFO, a folder, a path in a protected
// goldens folder (missing or an existing golden, directly, through "..", or
// through a linked folder), in a goldens folder found by its harness/scenes
// sibling, under a missing folder, a link to /dev/null, or "-". NAME (any bytes
// but '/' and NUL) is the file's name, CONTENT what is written.
//
// The invariant: either a regular file holding CONTENT is at the path (or, for
// "-", CONTENT went to the stream), or InputError was thrown and nothing at
// the path changed (same kind, same bytes, same link target), its message is
// valid UTF-8, and no temporary file is left beside it. The kinds that must be
// refused are refused; the ones that must be written are written. /dev/null
// and the file a link points to are never touched.
#include "fuzz_support.h"
#include "input_error.h"
#include "output_path.h"
// The tests' own record of what is at a path, so that both judge "untouched" alike.
#include "../tests/support/path_state.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using impulse::fuzz::finding;
using impulse::test::spit;
using impulse::test::state_of;

enum Kind {
    missing,
    regular,
    link_to_file,
    dangling_link,
    fifo,
    folder,
    in_goldens,
    existing_golden,
    goldens_via_dotdot,
    goldens_via_linked_folder,
    goldens_beside_scenes,
    missing_parent,
    link_to_dev_null,
    standard_output,
    kind_count
};

bool must_be_written(Kind kind) {
    return kind == missing || kind == regular || kind == standard_output;
}

// Valid UTF-8 without control characters: exactly the text printable_path()
// leaves as it is.
bool printable(const std::string& text) {
    return impulse::harness::printable_path(text) == text;
}

// Makes the target of `kind` in `dir` and returns its path.
fs::path make_target(Kind kind, const fs::path& dir, const std::string& name) {
    fs::create_directories(dir / "goldens");
    spit(dir / "outside", "outside\n");
    switch (kind) {
    case regular:
        spit(dir / name, "old\n");
        return dir / name;
    case link_to_file:
        fs::create_symlink(dir / "outside", dir / name);
        return dir / name;
    case dangling_link:
        fs::create_symlink(dir / "nowhere", dir / name);
        return dir / name;
    case fifo:
        if (::mkfifo((dir / name).c_str(), 0600) != 0) {
            finding("mkfifo failed");
        }
        return dir / name;
    case folder:
        fs::create_directories(dir / name / "inside");
        return dir / name;
    case in_goldens:
        return dir / "goldens" / name;
    case existing_golden:
        spit(dir / "goldens" / name, "golden\n");
        return dir / "goldens" / name;
    case goldens_via_dotdot:
        fs::create_directories(dir / "elsewhere");
        return dir / "elsewhere" / ".." / "goldens" / name;
    case goldens_via_linked_folder:
        fs::create_directory_symlink(dir / "goldens", dir / "linked");
        return dir / "linked" / name;
    case goldens_beside_scenes:
        fs::create_directories(dir / "repo" / "harness" / "scenes");
        fs::create_directories(dir / "repo" / "goldens");
        return dir / "repo" / "goldens" / name;
    case missing_parent:
        return dir / "no-such-folder" / name;
    case link_to_dev_null:
        fs::create_symlink("/dev/null", dir / name);
        return dir / name;
    case missing:
    case standard_output:
    case kind_count:
        break;
    }
    return dir / name;
}

bool temporary_file_left(const fs::path& folder) {
    std::error_code error;
    for (fs::recursive_directory_iterator it(folder, error), end; !error && it != end;
         it.increment(error)) {
        if (it->path().filename().string().find(".tmp-") != std::string::npos) {
            return true;
        }
    }
    return false;
}

std::string dev_null_state() {
    struct stat info {};
    if (::lstat("/dev/null", &info) != 0) {
        return "missing";
    }
    return std::to_string(info.st_mode) + " " + std::to_string(info.st_rdev);
}

void check_once(Kind kind, const fs::path& dir, const std::string& name,
                const std::string& content) {
    const fs::path target = make_target(kind, dir, name);
    const std::string path = kind == standard_output ? "-" : target.string();
    const std::string before = state_of(path), outside = state_of(dir / "outside");
    const std::string dev_null = dev_null_state();
    std::ostringstream stream;
    bool refused = false;
    try {
        impulse::harness::write_output_file("--out", path, content, {(dir / "goldens").string()},
                                            stream);
    } catch (const impulse::harness::InputError& e) {
        refused = true;
        if (!printable(e.what())) {
            finding(std::string("a refusal's message is not printable UTF-8: ") + e.what());
        }
    }
    if (dev_null_state() != dev_null || state_of(dir / "outside") != outside) {
        finding("/dev/null or the file a link points to changed");
    }
    if (temporary_file_left(dir)) {
        finding("a temporary file was left behind");
    }
    if (refused) {
        if (must_be_written(kind)) {
            finding("a path that may be written was refused: kind " + std::to_string(kind));
        }
        if (state_of(path) != before) {
            finding("a refused path changed: kind " + std::to_string(kind));
        }
        return;
    }
    if (!must_be_written(kind)) {
        finding("a path that must be refused was written: kind " + std::to_string(kind));
    }
    const bool whole = kind == standard_output ? stream.str() == content && state_of(path) == before
                                               : state_of(path) == "file " + content;
    if (!whole) {
        finding("the output is not the content, whole: kind " + std::to_string(kind));
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 2) {
        return 0;
    }
    const auto kind = static_cast<Kind>(data[0] % kind_count);
    const std::size_t length = std::min<std::size_t>(1 + data[1] % 48, size - 2);
    std::string name = impulse::fuzz::text_of(data + 2, length);
    for (char& c : name) {
        if (c == '/' || c == '\0') {
            c = '_';
        }
    }
    if (name.empty() || name == "." || name == ".." || name == "goldens" || name == "outside" ||
        name == "nowhere" || name == "elsewhere" || name == "linked" || name == "repo" ||
        name.find(".tmp-") != std::string::npos) {
        name = "out.json"; // the names the set-up itself uses, or one that looks left over
    }
    const std::string content = impulse::fuzz::text_of(data + 2 + length, size - 2 - length);

    std::string pattern = (fs::temp_directory_path() / "impulse-fuzz-output-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
        finding("mkdtemp failed");
    }
    const fs::path dir = pattern;
    check_once(kind, dir, name, content);
    std::error_code ignored;
    fs::remove_all(dir, ignored);
    return 0;
}
