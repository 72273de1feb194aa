// The golden gate (docs/design.md, "Comparing and the golden workflow"): a
// project's scenes are run again in its engines and compared with the
// goldens blessed earlier.
#pragma once

#include "project.h"
#include "scene_check.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// The implicit project at `root` (ROOT/harness/scenes, ROOT/goldens, the
// impulse engine), for callers that have not moved to Project yet.
struct GateRoot {
    std::string root = ".";
    std::string scenes_dir() const;
    std::string goldens_dir() const;
    std::string golden_path(const std::string& scene_name) const;
};
Project project_of(const GateRoot& root);

// CI mode: the CI environment variable set to anything but empty, "0" or "false".
bool ci_mode();

// The project's scene files (project_scenes), refusing two whose names differ
// only in case (InputError naming both).
std::vector<std::string> canonical_scenes(const Project& project);
// A scene argument is a path when it names an existing file, ends in .json or
// has a '/'; otherwise the name of a project scene (looked for in the first
// scenes folder when no scene has that name, so the error names that file).
std::string resolve_scene(const Project& project, const std::string& argument);
// A scene argument as a verb takes it: resolve_scene, refusing a name that
// no scene has with one sentence naming the scenes folder (or the project
// file) and the closest name, instead of a file that cannot be read.
std::string scene_argument(const Project& project, const std::string& argument);
// The scene files a verb works on: every project scene when no argument
// names one, otherwise each argument resolved as above. Throws InputError
// naming both files when two names differ only in case.
std::vector<std::string> scenes_named(const Project& project,
                                      const std::vector<std::string>& arguments);
// Goldens with no project scene of their name, even ignoring case, in each
// engine's golden folder (and, with several engines, GOLDENS/*.json).
std::vector<std::string> unreferenced_goldens(const Project& project);
// Why such a golden is unreferenced, for the sentence after its path: "no
// scene of that name", or, for a golden left in GOLDENS/ itself once the
// project has several engines, that each engine's goldens now live in
// GOLDENS/ENGINE/ (an outside review added a second engine and was told
// that scenes which exist had no scene of their name).
std::string unreferenced_reason(const Project& project, const std::string& golden);
// Throws InputError unless `scene_path` is one of the project's scenes: the
// golden of any other scene would be unreferenced (and pruned).
void require_project_scene(const Project& project, const std::string& scene_path);
// The project a file lies in: the first folder from the file's own folder
// upwards that has an impulse.json (loaded as find_project would) or a
// harness/scenes folder (the implicit project there). Empty when there is
// none or its impulse.json is refused: a file outside any project is normal.
std::optional<Project> project_around(const std::string& file);

std::vector<std::string> canonical_scenes(const GateRoot& root);
std::string resolve_scene(const GateRoot& root, const std::string& argument);
std::vector<std::string> scenes_named(const GateRoot& root,
                                      const std::vector<std::string>& arguments);
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

// Runs the scene in `engine` (run_engine) and compares it with the engine's
// golden. An engine's refusal is a skipped row, its failure an error row.
SceneCheck check_scene(const Project& project, const EngineSpec& engine,
                       const std::string& scene_path, const CheckOptions& options);
// Every (engine, scene) pair, engine by engine, each engine's scenes on
// `jobs` threads; results in that order, identical for any jobs.
std::vector<SceneCheck> check_scenes(const Project& project, const std::vector<EngineSpec>& engines,
                                     const std::vector<std::string>& paths,
                                     const CheckOptions& options);
SceneCheck check_scene(const GateRoot& root, const std::string& scene_path,
                       const CheckOptions& options);
std::vector<SceneCheck> check_scenes(const GateRoot& root, const std::vector<std::string>& paths,
                                     const CheckOptions& options);

// What bless did to one golden.
struct Blessing {
    // unwritten: the golden could not be written (read-only folder, disk
    // full); summary holds the sentence naming it. skipped: the engine
    // refused the scene's settings; summary holds its sentence.
    enum class Outcome { created, changed, unchanged, refused, unwritten, skipped };
    std::string name;
    std::string golden_file;
    Outcome outcome = Outcome::unchanged;
    std::string summary; // changed: what moved and by how much; refused: why
    std::string golden_folder;
    std::vector<std::string> warnings; // the scene's, each naming its file (a polygon recentred)
    // created / changed, between prepare_blessing and write_blessing: the
    // golden's new bytes.
    std::string text;
};

// Runs the scene in `engine` and writes its golden (atomically, only when the
// bytes change). A scene that fails its own expectations is refused; one
// that does not load, lies outside the project or fails in the engine throws
// InputError.
Blessing bless_scene(const Project& project, const EngineSpec& engine,
                     const std::string& scene_path);
Blessing bless_scene(const GateRoot& root, const std::string& scene_path);
// bless_scene in two halves, so that several scenes are written all or
// nothing: prepare_blessing runs the scene and decides (the golden's bytes
// kept in `text`), write_blessing writes a created or changed golden (or
// makes it unwritten) and does nothing for any other outcome.
Blessing prepare_blessing(const Project& project, const EngineSpec& engine,
                          const std::string& scene_path);
void write_blessing(Blessing& blessing);
// Throws InputError naming the golden when write_blessing could not write it
// (something other than a regular file there, a folder on its way that is a
// file, or one that takes no new files), without writing anything: bless
// checks every golden it would write first, so the folder is all new or all old.
void check_golden_writable(const Blessing& blessing);

} // namespace impulse::harness
