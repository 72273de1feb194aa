// Throwaway roots in the gate's layout (ROOT/harness/scenes, ROOT/goldens)
// built from copies of the canonical scenes and goldens, for the tests that
// run the gate on a root of their own.
#pragma once

#include "files.h"

#include <filesystem>
#include <string>
#include <vector>

namespace impulse::test {

enum class Goldens { none, copied };

// DIR/root holding copies of the canonical scenes named (all of them when
// `names` is empty) and, with Goldens::copied, of their goldens. A name that
// is not a canonical scene fails the test with the copy's exception.
inline std::filesystem::path make_root(const TempDir& dir, const std::vector<std::string>& names,
                                       Goldens goldens) {
    namespace fs = std::filesystem;
    const fs::path root = dir.dir / "root";
    const fs::path source = IMPULSE_SOURCE_DIR;
    fs::create_directories(root / "harness" / "scenes");
    if (goldens == Goldens::copied) {
        fs::create_directories(root / "goldens");
    }
    std::vector<std::string> copied = names;
    if (copied.empty()) {
        for (const fs::directory_entry& e : fs::directory_iterator(source / "harness" / "scenes")) {
            if (e.is_regular_file() && e.path().extension() == ".json") {
                copied.push_back(e.path().stem().string());
            }
        }
    }
    for (const std::string& name : copied) {
        const fs::path file = name + ".json";
        fs::copy_file(source / "harness" / "scenes" / file, root / "harness" / "scenes" / file);
        if (goldens == Goldens::copied) {
            fs::copy_file(source / "goldens" / file, root / "goldens" / file);
        }
    }
    return root;
}

} // namespace impulse::test
