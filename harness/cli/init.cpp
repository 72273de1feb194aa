// `impulse init [DIR]`: a starter project, DIR/impulse.json and one example
// scene with an exact answer, so check and bless work there from the start.
#include "atomic_file.h"
#include "cli.h"
#include "command_words.h"
#include "input_error.h"
#include "project.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

namespace impulse::harness::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* init_help =
    R"(usage: impulse init [DIR] [--engine NAME] [--engine-command 'PROGRAM ARGS']

Starts a project in DIR (default: the current folder): writes DIR/impulse.json
(the project file: scenes in DIR/scenes, goldens in DIR/goldens, one engine
whose command is a placeholder for yours) and DIR/scenes/drop.json (a disc
dropped on the ground, with the exact answer every run is checked against),
then prints the next steps. Refuses, writing nothing, when either file exists.
See docs/project-file.md and docs/engine-protocol.md.

  --engine NAME      the engine's name in impulse.json (default my-engine)
  --engine-command 'PROGRAM ARGS'
                     your engine's command (split into words as a shell would,
                     nothing expanded; run in DIR with the scene's path
                     appended), instead of the placeholder

Exit: 0 written, 2 a file exists or cannot be written.
)";

// The project file, with the engine the user named or a placeholder whose
// command cannot explain itself in JSON (no comments): the next steps
// printed on standard output do.
std::string starter_project(const std::string& name, const std::vector<std::string>& command) {
    // nlohmann::json writes each string with JSON's escapes; the layout is ours.
    std::string words;
    for (const std::string& word : command) {
        words += (words.empty() ? "" : ", ") + nlohmann::json(word).dump();
    }
    return "{\n"
           "  \"schema\": \"impulse/project@1\",\n"
           "  \"scenes\": [\"scenes\"],\n"
           "  \"goldens\": \"goldens\",\n"
           "  \"engines\": [\n"
           "    {\"name\": " +
           nlohmann::json(name).dump() + ", \"command\": [" + words +
           "], \"time_limit\": 60}\n"
           "  ],\n"
           "  \"regen\": \"impulse regen\"\n"
           "}\n";
}

// A drop has an exact answer (docs/physics.md): every impact time and the
// speed after it follow from g, the gap and e alone, so a correct engine
// passes it whatever its own choices.
//
// Its box2d block (`impulse box2d`, `impulse compare`) bounds how far Box2D
// 2.4.1 may be from the engine under study. Box2D errs to first order in dt
// (physics.md, "Box2D, the second reference": it finds the contact one to
// two steps late and bounces after that step's gravity kick), so these are
// the tolerances of the canonical drop-circle, the same drop at dt = 1/30 s,
// times 0.3 for dt = 0.01 s: impact time 2 dt = 0.02 s; rebound speed about
// 3.6 g dt = 0.36 m/s (e times the late step's extra fall and kick, plus
// symplectic Euler's loss of g dt per flight on the engine's side); apexes,
// read from those speeds, 0.099 m, and their ratios 0.057.
constexpr const char* starter_scene = R"({
  "schema": "impulse/scene@1",
  "name": "drop",
  "description": "A disc of radius 0.5 dropped from a 2 m gap onto the ground, e = 0.7: each impact's time and speed have an exact answer",
  "gravity": [0, -9.81],
  "restitution": 0.7,
  "dt": 0.01,
  "duration": 3.0,
  "solver": {"integrator": "rk4"},
  "bodies": [
    {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
    {"name": "ball", "shape": {"circle": 0.5}, "density": 2, "position": [0, 2.5]}
  ],
  "expectations": [
    {"kind": "drop", "body": "ball", "impacts": 3, "rtol": 1e-09, "atol": 1e-12}
  ],
  "box2d": {
    "observables": [
      {"kind": "impact-times", "body": "ball", "count": 1, "atol": 0.02},
      {"kind": "post-impact-velocity", "body": "ball", "impact": 1, "atol": 0.36},
      {"kind": "apex-heights", "body": "ball", "count": 2, "atol": 0.099},
      {"kind": "apex-ratios", "body": "ball", "count": 2, "atol": 0.057}
    ]
  }
}
)";

bool entry_exists(const fs::path& path) {
    std::error_code error;
    return fs::symlink_status(path, error).type() != fs::file_type::not_found;
}

void print_next_steps(const std::string& project_file, bool placeholder, std::ostream& out) {
    out << "next steps:\n";
    if (placeholder) {
        out << "  1. Put your engine behind the gate: in " << project_file
            << ", engines[0].command\n"
            << "     [\"./my-engine\"] is a placeholder. Make it the program that runs your "
               "engine;\n"
            << "     it is given a scene file's path and writes the trajectory to standard output\n"
            << "     (docs/engine-protocol.md). To try the gate with impulse's own engine first,\n"
            << "     make the engine {\"name\": \"impulse\", \"builtin\": \"impulse\"}.\n";
    } else {
        out << "  1. impulse conform  scores your engine on the shipped scenes' exact answers\n";
    }
    out << "  2. impulse bless    runs the scenes and writes goldens/drop.json; its drop\n"
        << "                      expectation wants each impact's exact time to 1e-9, which\n"
        << "                      an engine that finds impact times meets: for one that\n"
        << "                      steps through them, loosen rtol and atol in\n"
        << "                      scenes/drop.json to what it promises (e.g. 0.05 and\n"
        << "                      |g| dt, 0.1: a step of time, of speed and of apex height)\n"
        << "  3. impulse check    the gate: exit 0 while nothing moved, 1 naming the scene,\n"
        << "                      body, channel and time when something did\n"
        << "  4. impulse regen    accepts an intended change (rewrites the goldens)\n";
}

} // namespace

int init_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream&) {
    const Arguments a = parse_arguments(args, {"--engine", "--engine-command"}, {"--help"});
    if (a.has_flag("--help")) {
        out << init_help;
        return exit_ok;
    }
    if (a.positional.size() > 1) {
        throw UsageError("takes at most one DIR, got " + std::to_string(a.positional.size()));
    }
    if (!a.positional.empty() && a.positional.front().empty()) {
        throw UsageError("DIR is empty; give a folder (. is the current one)");
    }
    const fs::path dir = a.positional.empty() ? fs::path(".") : fs::path(a.positional.front());
    const fs::path project_file = dir / project_file_name;
    const fs::path scene_file = dir / "scenes" / "drop.json";
    // Both are checked before either is written: a refusal writes nothing.
    for (const fs::path& file : {project_file, scene_file}) {
        if (entry_exists(file)) {
            throw InputError(file.string(), "",
                             "already exists; impulse init writes a new project and never "
                             "overwrites one (edit the file, or init another folder)");
        }
    }
    std::vector<std::string> command{"./my-engine"};
    if (const auto given = a.option("--engine-command")) {
        command = command_words(*given);
    }
    // The folders init makes, outermost first, so that a refusal can take
    // back every one of them (an outside review's `init a/b --engine "bad
    // name"` left a/ and a/b/scenes/ behind).
    std::vector<fs::path> made;
    for (fs::path folder = dir / "scenes"; !folder.empty() && !entry_exists(folder);
         folder = folder.parent_path()) {
        made.insert(made.begin(), folder);
    }
    std::error_code error;
    const auto take_back = [&] {
        fs::remove(scene_file, error);
        fs::remove(project_file, error);
        for (auto folder = made.rbegin(); folder != made.rend(); ++folder) {
            fs::remove(*folder, error); // only when empty: nothing of the user's goes
        }
    };
    fs::create_directories(dir / "scenes", error);
    std::error_code looked;
    if (error || !fs::is_directory(dir / "scenes", looked)) {
        // A link that leads nowhere is in the way without an error of its own.
        const std::string why =
            fs::is_symlink(fs::symlink_status(dir / "scenes", looked))
                ? "a symbolic link to a folder that does not exist is in the way"
                : error.message();
        take_back();
        throw InputError((dir / "scenes").string(), "", "cannot be made (" + why + ")");
    }
    const std::string name = a.option("--engine").value_or("my-engine");
    try {
        write_file_atomically(scene_file.string(), starter_scene);
        write_file_atomically(project_file.string(), starter_project(name, command));
        // The file is read back as every verb will read it: a name the
        // project file refuses is refused here, with nothing left behind.
        load_project(project_file.string());
    } catch (const InputError&) {
        take_back(); // all or nothing
        throw;
    }
    out << "wrote " << printable_path(project_file.string()) << " and "
        << printable_path(scene_file.string()) << "\n\n";
    print_next_steps(printable_path(project_file.string()), !a.option("--engine-command"), out);
    return exit_ok;
}

} // namespace impulse::harness::cli
