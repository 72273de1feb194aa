// The golden gate (docs/design.md, "Comparing and the golden workflow"): canonical
// scenes are simulated again and compared with the goldens blessed earlier.
#pragma once

#include "scene_check.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// Where scenes and goldens live: ROOT/harness/scenes/NAME.json, ROOT/goldens/NAME.json.
struct GateRoot {
    std::string root = ".";
    std::string scenes_dir() const;
    std::string goldens_dir() const;
    std::string golden_path(const std::string& scene_name) const;
};

// CI mode: the CI environment variable set to anything but empty, "0" or "false".
bool ci_mode();

// Canonical scene files under the root, sorted by name: every NAME.json entry,
// readable or not (a dangling symlink is a scene that fails to load). Throws
// InputError when the folder is missing or two names differ only in case.
std::vector<std::string> canonical_scenes(const GateRoot& root);
// A scene argument is a path when it names an existing file or ends in .json,
// otherwise the name of a canonical scene.
std::string resolve_scene(const GateRoot& root, const std::string& argument);
// The scene files a verb works on: every canonical scene when no argument
// names one, otherwise each argument resolved as above. Throws InputError
// naming both files when two names differ only in case.
std::vector<std::string> scenes_named(const GateRoot& root,
                                      const std::vector<std::string>& arguments);
// Goldens with no canonical scene of their name, even ignoring case.
std::vector<std::string> unreferenced_goldens(const GateRoot& root);

// Keeps the scenes of shard k of n (1-based): a scene's shard depends on its
// name alone, so adding a scene never moves the others between machines.
std::vector<std::string> shard(const std::vector<std::string>& scene_paths, int k, int n);

struct CheckOptions {
    bool tolerance_mode = false;
    // Command-line tolerance specs (--atol/--rtol/--ulp), applied over each scene's own.
    std::optional<std::string> atol, rtol, ulp;
    int jobs = 1;
    // Called (from any worker thread) when a scene starts and when it is done;
    // for a progress bar, never for results.
    std::function<void(const std::string& scene_path)> on_start;
    std::function<void()> on_done;
};

SceneCheck check_scene(const GateRoot& root, const std::string& scene_path,
                       const CheckOptions& options);
// Checks every scene on `jobs` threads; results in the order given, identical for any jobs.
std::vector<SceneCheck> check_scenes(const GateRoot& root, const std::vector<std::string>& paths,
                                     const CheckOptions& options);

// What bless did to one golden.
struct Blessing {
    // unwritten: the golden could not be written (read-only folder, disk
    // full); summary holds the sentence naming it.
    enum class Outcome { created, changed, unchanged, refused, unwritten };
    std::string name;
    std::string golden_file;
    Outcome outcome = Outcome::unchanged;
    std::string summary; // changed: what moved and by how much; refused: why
};

// Runs the scene and writes its golden (atomically, only when the bytes change).
// A scene that fails its own expectations or does not run is refused.
Blessing bless_scene(const GateRoot& root, const std::string& scene_path);

} // namespace impulse::harness
