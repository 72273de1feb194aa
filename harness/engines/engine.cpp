// run_engine: the one way the layers above get a trajectory, from this
// engine, from Box2D, or from any program that speaks the engine protocol
// (docs/engine-protocol.md).
#include "engine.h"

#include "engine_failure.h"
#include "engine_output.h"
#include "engine_process.h"
#include "input_error.h"
#include "interruption.h"
#include "memory_budget.h"
#include "number_format.h"
#include "record.h"
#include "scene_writer.h"
#include "trajectory_columns.h"
#ifdef IMPULSE_WITH_BOX2D
#include "box2d_simulator.h"
#include "single_precision.h"
#endif
#ifdef IMPULSE_WITH_CHIPMUNK
#include "chipmunk_simulator.h"
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

namespace impulse::harness {

namespace {

// The exit code by which an engine refuses a scene it cannot model.
constexpr int unsupported_exit_code = 3;
// An engine's message is its last non-empty line on standard error, cut to this.
constexpr std::size_t message_chars = 300;

// An in-process reference engine's run: `make` builds its simulator from the
// effective scene and throws InputError for a scene the engine cannot
// represent, which the protocol calls unsupported (a skip with the sentence
// naming the JSON path, as an external engine's exit 3).
template <class Make>
[[maybe_unused]] EngineRun run_in_process(const Scene& scene, const Overrides& overrides,
                                          Make&& make) {
    const Scene effective = with_overrides(scene, overrides);
    EngineRun result;
    std::unique_ptr<Simulator> simulator;
    try {
        simulator = make(effective, result);
    } catch (const InputError& refusal) {
        result.outcome = EngineRun::Outcome::unsupported;
        result.message = refusal.what();
        return result;
    }
    result.trajectory = record(*simulator, effective);
    const std::string used = overrides_list(overrides);
    if (!used.empty()) {
        result.trajectory.solver.emplace_back("overrides", used);
    }
    return result;
}

EngineRun run_box2d(const Scene& scene, const Overrides& overrides) {
#ifdef IMPULSE_WITH_BOX2D
    return run_in_process(scene, overrides, [](const Scene& effective, EngineRun& result) {
        // Single precision and a polygon its skin would swallow are what Box2D
        // cannot represent.
        require_single_precision(effective, "Box2D",
                                 effective.dt / static_cast<double>(effective.box2d.substeps));
        return make_box2d_simulator(effective, result.warnings);
    });
#else
    (void)overrides;
    throw InputError(scene.file, "",
                     "engine 'box2d' cannot run it: this build has no Box2D (configured with "
                     "IMPULSE_WITH_BOX2D=OFF); install libbox2d-dev and configure with "
                     "-DIMPULSE_WITH_BOX2D=ON to use it");
#endif
}

EngineRun run_chipmunk(const Scene& scene, const Overrides& overrides) {
#ifdef IMPULSE_WITH_CHIPMUNK
    return run_in_process(scene, overrides, [](const Scene& effective, EngineRun&) {
        // Refused before Chipmunk sees it: what it cannot represent, and what
        // would trip its debug checks (which abort the process).
        return make_chipmunk_simulator(effective);
    });
#else
    (void)overrides;
    throw InputError(scene.file, "",
                     "engine 'chipmunk' cannot run it: this build has no Chipmunk2D (configured "
                     "with IMPULSE_WITH_CHIPMUNK=OFF); install libchipmunk-dev and configure "
                     "with -DIMPULSE_WITH_CHIPMUNK=ON to use it");
#endif
}

// A private folder for the scene the engine reads (mkdtemp: mode 0700, a
// name no one else has), removed with what it holds however the run ends.
class PrivateFolder {
  public:
    PrivateFolder() {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "impulse-engine-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) {
            throw InputError(pattern, "",
                             std::string("cannot create a folder for the engine's scene: ") +
                                 std::strerror(errno));
        }
        path_ = std::filesystem::absolute(pattern);
    }
    ~PrivateFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    PrivateFolder(const PrivateFolder&) = delete;
    PrivateFolder& operator=(const PrivateFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

std::string write_scene_file(const std::filesystem::path& folder, const Scene& scene) {
    const std::string path = (folder / (scene.name + ".json")).string();
    std::ofstream out(path, std::ios::binary);
    out << write_normalized_scene(scene);
    out.close();
    if (!out) {
        throw InputError(path, "",
                         "cannot be written for the engine: " + std::string(std::strerror(errno)));
    }
    return path;
}

// Where the time limit a run ran out of is set: the project file's
// engine entry ("raise time_limit at ./impulse.json: engines[0]"), or, for
// --engine-command, the way to give it one (docs/project-file.md).
std::string time_limit_hint(const EngineSpec& engine) {
    if (engine.origin == "--engine-command") {
        return " (an engine given with --engine-command has 60 s; name it in a project file "
               "with a time_limit to give it longer)";
    }
    if (engine.origin.rfind("the reference ", 0) == 0 || engine.origin.empty()) {
        return "";
    }
    return " (raise its time_limit at " + engine.origin + ")";
}

// How the process ended when it did not end with exit 0 or 3, and its message.
std::string failure_reason(const ProcessResult& process, const EngineSpec& engine) {
    std::string reason;
    if (process.timed_out) {
        reason = "did not finish within " + format_double(engine.time_limit) +
                 " s; its process group was killed" + time_limit_hint(engine);
    } else if (process.overflowed) {
        reason = "wrote more than " + trajectory_limit_text() +
                 " on standard output; its process group was killed";
    } else if (process.signal) {
        reason = "signal " + std::to_string(*process.signal) + " (" +
                 std::string(::strsignal(*process.signal)) + ")";
    } else {
        reason = "exit status " + std::to_string(process.exit_code.value_or(-1));
    }
    const std::string message = last_line(process.error_tail, message_chars);
    return reason + ": " + (message.empty() ? "(nothing on standard error)" : message);
}

// "engine 'mine' failed on drop.json (with dt 0.02, integrator euler)": the
// overrides of the command line or of a sweep's grid point, since the same
// scene may run under many.
std::string failed_label(const EngineSpec& engine, const Scene& scene,
                         const Overrides& overrides = {}) {
    std::string with;
    const auto add = [&with](const std::string& item) {
        with += (with.empty() ? " (with " : ", ") + item;
    };
    if (overrides.dt) {
        add("dt " + format_double(*overrides.dt));
    }
    if (overrides.integrator) {
        add(std::string("integrator ") + integrator_name(*overrides.integrator));
    }
    if (overrides.toi_tolerance) {
        add("toi_tolerance " + format_double(*overrides.toi_tolerance));
    }
    return "engine '" + engine.name + "' failed on " + scene.file +
           (with.empty() ? "" : with + ")");
}

ProcessResult run_command(const EngineSpec& engine, const Scene& received, const Scene& scene) {
    PrivateFolder folder;
    ProcessRequest request;
    request.command = engine.command;
    request.command.push_back(write_scene_file(folder.path(), received));
    // Removed with the folder even if the harness is interrupted meanwhile.
    const InterruptibleFolder interruptible(folder.path().string(), request.command.back());
    request.working_directory = engine.working_directory;
    request.time_limit = engine.time_limit;
    request.output_limit = static_cast<std::size_t>(trajectory_limit_bytes());
    ProcessResult process = run_process(request);
    if (process.not_started) {
        const std::string origin =
            engine.origin.empty() ? "" : " (the command of " + engine.origin + ")";
        throw EngineFailure(failed_label(engine, scene), "", *process.not_started + origin);
    }
    return process;
}

// The protocol fixes an outside engine's frames (steps + 1 rows of 1 + 6 D
// numbers), so the memory they must take is known before it runs: a scene
// whose frames alone pass the limit is refused as run_scene refuses it, not
// after the engine has run, up to its time limit, into the output cap (an
// outside review). Their text is not known (a number may be one character),
// so only their memory is checked here; the text as the output is read.
void require_frames_within_limit(const Scene& scene) {
    const long long steps = step_count(scene);
    std::uint64_t columns = 1;
    for (const SceneBody& body : scene.bodies) {
        columns += body.is_static ? 0 : body_channel_suffixes.size();
    }
    TrajectorySize frames = frames_size_bound(static_cast<std::uint64_t>(steps) + 1, columns);
    frames.text_bytes = 0;
    require_within_trajectory_limit(frames, scene.file, "duration",
                                    "the engine must write " + std::to_string(steps + 1) +
                                        " frames of " + std::to_string(columns) + " numbers (" +
                                        std::to_string(steps) + " steps)");
}

// Tunnelling is not refused here as run_scene does: whether a body passes
// through another is this engine's property, which the gate is there to see.
EngineRun run_external(const EngineSpec& engine, const Scene& scene, const Overrides& overrides) {
    const Scene received = with_overrides(scene, overrides);
    require_frames_within_limit(received);
    const ProcessResult process = run_command(engine, received, scene);
    EngineRun result;
    result.seconds = process.seconds;
    if (process.exit_code == unsupported_exit_code) {
        result.outcome = EngineRun::Outcome::unsupported;
        result.message = last_line(process.error_tail, message_chars);
        if (result.message.empty()) {
            result.message = "(the engine gave no reason on standard error)";
        }
        return result;
    }
    if (process.exit_code != 0) {
        EngineFailure failure(failed_label(engine, scene, overrides), "",
                              failure_reason(process, engine));
        failure.model_stopped =
            process.exit_code == 1 && !process.timed_out && !process.overflowed && !process.signal;
        throw failure;
    }
    EngineOutput output;
    try {
        output = read_engine_output(process.output, OutputContext{engine.name, &scene, &received,
                                                                  overrides_list(overrides)});
    } catch (const InputError& unreadable) {
        throw EngineFailure(unreadable);
    }
    result.trajectory = std::move(output.trajectory);
    result.cost = output.cost;
    return result;
}

} // namespace

EngineSpec impulse_engine() {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::impulse;
    spec.name = "impulse";
    return spec;
}

EngineSpec box2d_engine() {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::box2d;
    spec.name = "box2d";
    return spec;
}

EngineSpec chipmunk_engine() {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::chipmunk;
    spec.name = "chipmunk";
    return spec;
}

void require_startable(const EngineSpec& engine) {
    if (engine.kind != EngineSpec::Kind::external) {
        return;
    }
    const std::optional<std::string> problem =
        start_problem(engine.command, engine.working_directory);
    if (!problem) {
        return;
    }
    const bool declared = !engine.origin.empty() && engine.origin != "--engine-command";
    throw InputError(declared ? engine.origin + ".command[0]" : "--engine-command", "",
                     *problem + " (engine '" + engine.name + "'; no scene was run)");
}

EngineRun run_engine(const EngineSpec& engine, const Scene& scene, const Overrides& overrides) {
    const auto start = std::chrono::steady_clock::now();
    EngineRun result;
    if (std::find(engine.skip.begin(), engine.skip.end(), scene.name) != engine.skip.end()) {
        result.outcome = EngineRun::Outcome::unsupported;
        result.message = "listed in its \"skip\" at " + engine.origin;
        return result;
    }
    switch (engine.kind) {
    case EngineSpec::Kind::impulse:
        result.trajectory = run_scene(scene, overrides);
        break;
    case EngineSpec::Kind::box2d:
        result = run_box2d(scene, overrides);
        break;
    case EngineSpec::Kind::chipmunk:
        result = run_chipmunk(scene, overrides);
        break;
    case EngineSpec::Kind::external:
        // The process's own wall time, measured around it.
        return run_external(engine, scene, overrides);
    }
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

} // namespace impulse::harness
