// The registry of reference engines (reference_engines.h): what each is,
// how it runs, and whether this machine has what it needs.
#include "reference_engines.h"

#include "input_error.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

// What every missing reference is installed with: scripts/setup installs the
// Debian packages (libbox2d-dev, libchipmunk-dev, nodejs, npm) and runs npm ci
// in references/ from its committed package-lock.json.
constexpr const char* setup_command = "scripts/setup";
constexpr const char* rebuild = " then rebuild (cmake --preset default && cmake --build "
                                "--preset default)";

bool is_folder(const fs::path& path) {
    std::error_code error;
    return fs::is_directory(path, error);
}

bool is_file(const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error);
}

// The first of `names` that is an executable file in a folder of PATH; empty
// when none is (the engine process searches PATH the same way, but a missing
// program is to be reported before a run, with the command that installs it).
std::string on_path(const std::vector<std::string>& names) {
    const char* path = std::getenv("PATH");
    std::string folders = path != nullptr ? path : "";
    std::size_t start = 0;
    while (start <= folders.size()) {
        const std::size_t end = std::min(folders.find(':', start), folders.size());
        const std::string folder = folders.substr(start, end - start);
        for (const std::string& name : names) {
            const fs::path candidate = fs::path(folder.empty() ? "." : folder) / name;
            if (is_file(candidate) && ::access(candidate.c_str(), X_OK) == 0) {
                return candidate.string();
            }
        }
        start = end + 1;
    }
    return "";
}

fs::path installed_references_dir() {
    std::error_code error;
    const fs::path exe = fs::read_symlink("/proc/self/exe", error);
    if (error || exe.empty()) {
        return {};
    }
    return exe.parent_path().parent_path() / "share" / "impulse" / "references";
}

ReferenceEngine built_in(const std::string& name, const std::string& title, EngineSpec spec) {
    ReferenceEngine r;
    r.name = name;
    r.title = title;
    r.spec = std::move(spec);
    r.spec.name = name;
    r.available = true;
    return r;
}

// Unused in a build with every built-in reference.
[[maybe_unused]] ReferenceEngine not_built(ReferenceEngine r, const std::string& option) {
    r.available = false;
    r.missing = "this build has no " + r.title + " (configured with " + option + "=OFF)";
    r.install = std::string(setup_command) + "," + rebuild;
    return r;
}

// A Node program of the npm project in `dir`: `node DIR/SCRIPT SCENE`, run
// in `dir`, available when node is on PATH, the script is there and npm ci
// has installed its package.
ReferenceEngine node_reference(const std::string& name, const std::string& title,
                               const fs::path& dir, const std::string& script,
                               const std::string& package, const std::string& node) {
    ReferenceEngine r;
    r.name = name;
    r.title = title;
    r.spec.kind = EngineSpec::Kind::external;
    r.spec.name = name;
    r.spec.working_directory = dir.string();
    r.spec.command = {node.empty() ? "node" : node, (dir / script).string()};
    r.spec.origin = "the reference " + name;
    r.install = setup_command;
    if (node.empty()) {
        r.missing = "node is not on PATH";
    } else if (!is_file(dir / script)) {
        r.missing = (dir / script).string() + " is missing";
    } else if (!is_file(dir / "node_modules" / package / "package.json")) {
        r.missing =
            "npm package " + package + " is not installed in " + (dir / "node_modules").string();
    } else {
        r.available = true;
        r.install.clear();
    }
    return r;
}

} // namespace

std::string references_dir() {
    const char* set = std::getenv("IMPULSE_REFERENCES_DIR");
    if (set != nullptr && *set != '\0') {
        if (!is_folder(set)) {
            throw InputError(set, "",
                             "IMPULSE_REFERENCES_DIR names this, which is not a folder of "
                             "reference engines");
        }
        return set;
    }
    const fs::path installed = installed_references_dir();
    if (!installed.empty() && is_folder(installed)) {
        return installed.lexically_normal().string();
    }
    return (fs::path(IMPULSE_SOURCE_DIR) / "references").string();
}

std::vector<ReferenceEngine> reference_engines() {
    std::vector<ReferenceEngine> all;
    ReferenceEngine box2d = built_in("box2d-2.4", "Box2D 2.4.1", box2d_engine());
#ifndef IMPULSE_WITH_BOX2D
    box2d = not_built(box2d, "IMPULSE_WITH_BOX2D");
#endif
    all.push_back(box2d);
    const fs::path dir = references_dir();
    const std::string node = on_path({"node", "nodejs"});
    all.push_back(node_reference("box2d-3", "Box2D v3 (npm box2d3-wasm 5.2.0)", dir,
                                 "box2d-v3/engine.mjs", "box2d3-wasm", node));
    ReferenceEngine chipmunk = built_in("chipmunk", "Chipmunk2D 7.0.3", chipmunk_engine());
#ifndef IMPULSE_WITH_CHIPMUNK
    chipmunk = not_built(chipmunk, "IMPULSE_WITH_CHIPMUNK");
#endif
    all.push_back(chipmunk);
    all.push_back(
        node_reference("rapier", "Rapier2D (npm @dimforge/rapier2d-deterministic-compat 0.20.0)",
                       dir, "rapier/engine.mjs", "@dimforge/rapier2d-deterministic-compat", node));
    return all;
}

std::vector<std::string> reference_names() {
    return {"box2d-2.4", "box2d-3", "chipmunk", "rapier"};
}

std::string unavailable_sentence(const ReferenceEngine& reference) {
    return "reference '" + reference.name + "' (" + reference.title + ") is not available (" +
           reference.missing + "); install it with: " + reference.install;
}

} // namespace impulse::harness
