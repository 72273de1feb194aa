// The engine protocol (docs/engine-protocol.md) behind run_engine: the
// normalized scene an engine receives reads back to the same scene bit for
// bit; a correct engine's trajectory comes back canonical; and every way an
// engine can fail (crash, hang, garbage, wrong columns, NaN, refusal, too
// much output, a command that does not start) is one sentence naming the
// engine, the scene and the engine's own message, with nothing left running.
#include "engine.h"
#include "engine_process.h"
#include "input_error.h"
#include "run.h"
#include "scene.h"
#include "scene_writer.h"
#include "support/files.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <sys/stat.h>
#include <vector>

using namespace impulse;
using namespace impulse::harness;
using impulse::test::slurp;
using impulse::test::spit;
using impulse::test::TempDir;
namespace fs = std::filesystem;

namespace {

const fs::path source_dir = IMPULSE_SOURCE_DIR;
const std::string engines_dir = IMPULSE_TEST_ENGINES_DIR;
const std::string fake_engine = engines_dir + "/fake_engine.py";
const std::string engine_name = "fake-engine";

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_bits(Vec2 a, Vec2 b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y);
}

bool same_shape(const Shape& a, const Shape& b) {
    if (a.type != b.type || !same_bits(a.radius, b.radius) || a.polygon.count != b.polygon.count) {
        return false;
    }
    for (std::size_t i = 0; i < static_cast<std::size_t>(a.polygon.count); ++i) {
        if (!same_bits(a.polygon.vertices[i], b.polygon.vertices[i]) ||
            !same_bits(a.polygon.normals[i], b.polygon.normals[i])) {
            return false;
        }
    }
    return true;
}

// Everything the engine's physics depends on, bit for bit.
void require_same_physics(const Scene& a, const Scene& b) {
    CHECK(a.name == b.name);
    CHECK(same_bits(a.gravity, b.gravity));
    CHECK(same_bits(a.restitution, b.restitution));
    CHECK(same_bits(a.dt, b.dt));
    CHECK(same_bits(a.duration, b.duration));
    CHECK(step_count(a) == step_count(b));
    CHECK(a.solver.integrator == b.solver.integrator);
    CHECK(a.solver.toi == b.solver.toi);
    CHECK(same_bits(a.solver.toi_tolerance, b.solver.toi_tolerance));
    CHECK(same_bits(a.solver.contact_tolerance, b.solver.contact_tolerance));
    CHECK(a.solver.contacts == b.solver.contacts);
    CHECK(a.solver.stepping == b.solver.stepping);
    CHECK(a.solver.vertex_normal == b.solver.vertex_normal);
    CHECK(a.solver.ccd == b.solver.ccd);
    CHECK(a.solver.resting == b.solver.resting);
    REQUIRE(a.bodies.size() == b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        const SceneBody& x = a.bodies[i];
        const SceneBody& y = b.bodies[i];
        INFO("bodies[" << i << "] " << x.name);
        const bool same = x.name == y.name && x.is_static == y.is_static &&
                          same_shape(x.shape, y.shape) && same_bits(x.position, y.position) &&
                          same_bits(x.angle, y.angle) && same_bits(x.velocity, y.velocity) &&
                          same_bits(x.angular_velocity, y.angular_velocity) &&
                          same_bits(x.mass, y.mass) && same_bits(x.inertia, y.inertia) &&
                          x.rotation == y.rotation;
        REQUIRE(same);
    }
}

Scene round_trip(const Scene& scene) {
    return parse_scene(write_normalized_scene(scene), "normalized " + scene.file);
}

// A scene with one dynamic body and nothing it reaches: 10 steps of 0.01 s.
const std::string fall_scene_text = R"({"schema": "impulse/scene@1", "name": "fall",
  "dt": 0.01, "duration": 0.1,
  "bodies": [{"name": "ball", "shape": {"circle": 0.5}, "position": [0, 10], "velocity": [1, 0]},
             {"name": "floor", "static": true, "shape": {"box": [5, 1]}, "position": [0, -100]}]})";

EngineSpec fake(const std::vector<std::string>& args, double time_limit = 30.0) {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::external;
    spec.name = engine_name;
    spec.command = {"python3", fake_engine};
    spec.command.insert(spec.command.end(), args.begin(), args.end());
    spec.time_limit = time_limit;
    return spec;
}

// The sentence run_engine refuses with.
std::string refusal(const EngineSpec& engine, const Scene& scene, const Overrides& overrides = {}) {
    try {
        run_engine(engine, scene, overrides);
    } catch (const InputError& error) {
        return error.what();
    }
    FAIL("run_engine did not refuse");
    return "";
}

// A trajectory as an engine would write it: the harness's own fields left out.
std::string engine_text(const Trajectory& trajectory, const std::vector<std::string>& drop) {
    const std::string text = write_trajectory(trajectory);
    std::string kept;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = text.find('\n', start) + 1;
        const std::string line = text.substr(start, end - start);
        bool dropped = false;
        for (const std::string& key : drop) {
            dropped = dropped || line.rfind("  \"" + key + "\":", 0) == 0;
        }
        kept += dropped ? "" : line;
        start = end;
    }
    return kept;
}

// Whether the process is gone (reaped, not a zombie).
bool process_gone(const std::string& pid_text) {
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    return ::kill(pid, 0) == -1 && errno == ESRCH;
}

// IMPULSE_MAX_TRAJECTORY_MIB for one scope, removed however the scope ends.
struct LimitMib {
    explicit LimitMib(const char* mib) { ::setenv("IMPULSE_MAX_TRAJECTORY_MIB", mib, 1); }
    ~LimitMib() { ::unsetenv("IMPULSE_MAX_TRAJECTORY_MIB"); }
    LimitMib(const LimitMib&) = delete;
    LimitMib& operator=(const LimitMib&) = delete;
};

struct Fixture {
    TempDir temp;
    Scene fall;
    Fixture() {
        spit(temp.dir / "fall.json", fall_scene_text);
        fall = load_scene((temp.dir / "fall.json").string());
    }
    // An engine that writes `text` as its trajectory.
    EngineSpec replaying(const std::string& text) const {
        spit(temp.dir / "replay.json", text);
        return fake({"replay", (temp.dir / "replay.json").string()});
    }
    // The sentence for a trajectory of the fall scene edited by `edit`.
    std::string refusal_of(const std::function<void(Trajectory&)>& edit) const {
        Trajectory trajectory = run_scene(fall);
        edit(trajectory);
        return refusal(replaying(engine_text(trajectory, {"digest", "scene_sha256"})), fall);
    }
};

// The impulse engine's run of `scene` with other events (kept in time order by the caller).
Trajectory trajectory_with_events(const Scene& scene, std::vector<TrajectoryEvent> events) {
    Trajectory trajectory = run_scene(scene);
    trajectory.events = std::move(events);
    return trajectory;
}

} // namespace

TEST_CASE("the normalized scene reads back to the same scene, bit for bit", "[engine-protocol]") {
    std::vector<fs::path> files;
    for (const fs::path& folder :
         {source_dir / "harness/scenes", source_dir / "harness/scenes/scale"}) {
        for (const auto& entry : fs::directory_iterator(folder)) {
            if (entry.path().extension() == ".json") {
                files.push_back(entry.path());
            }
        }
    }
    REQUIRE(files.size() > 30);
    for (const fs::path& file : files) {
        INFO(file.string());
        const Scene scene = load_scene(file.string());
        const std::string text = write_normalized_scene(scene);
        CHECK(text.find("\"gas\"") == std::string::npos);
        CHECK(text.find("\"expectations\"") == std::string::npos);
        CHECK(text.find("\"box2d\"") == std::string::npos);
        require_same_physics(scene, parse_scene(text, "normalized"));
    }
}

TEST_CASE("the normalized scene writes every key and keeps odd bodies", "[engine-protocol]") {
    // A static body, a body that does not turn, a recentred polygon, density
    // instead of mass, and -0.0: each must come back as loaded.
    const Scene scene = parse_scene(R"({"schema": "impulse/scene@1", "name": "odd",
      "description": "left out", "dt": 0.01, "duration": 0.5, "restitution": 0.5,
      "solver": {"stepping": "local", "vertex_normal": "bisector"},
      "bodies": [
        {"name": "floor", "static": true, "shape": {"box": [4, 0.5]}, "position": [0, -0.5]},
        {"name": "slider", "shape": {"box": [0.5, 0.25]}, "position": [-2, 1], "rotation": false,
         "velocity": [-0.0, 1]},
        {"name": "wedge", "shape": {"polygon": [[0, 0], [1, 0], [0, 1]]}, "position": [2, 1],
         "angle": 0.3, "density": 2.5},
        {"name": "tilted", "shape": {"polygon": [[-0.5, -0.2], [0.5, -0.2], [0.5, 0.2], [-0.5, 0.2]]},
         "position": [0, 3], "angle": -0.0, "mass": 3, "inertia": 0.7}]})",
                                    "odd.json");
    const std::string text = write_normalized_scene(scene);
    const Scene back = round_trip(scene);
    require_same_physics(scene, back);
    CHECK(!back.bodies[1].rotation);
    CHECK(text.find("\"description\"") == std::string::npos);
    CHECK(text.find(R"({"name": "floor", "static": true, "shape": {"box": [4, 0.5]})") !=
          std::string::npos);
    // The recentred triangle is written where the loader moved it: no second warning.
    CHECK(scene.warnings.size() == 1);
    CHECK(back.warnings.empty());
    CHECK(text.find("\"rotation\": false") != std::string::npos);
    CHECK(text.find("\"velocity\": [-0.0, 1]") != std::string::npos);
    CHECK(text.find("\"vertex_normal\": \"bisector\"") != std::string::npos);
}

TEST_CASE("a correct engine's trajectory comes back canonical", "[engine-protocol]") {
    const Scene scene = load_scene((source_dir / "harness/scenes/drop-box.json").string());
    const Trajectory impulse = run_scene(scene);
    REQUIRE(!impulse.events.empty());
    const std::string golden = slurp(source_dir / "goldens/drop-box.json");
    REQUIRE(write_trajectory(impulse) == golden);
    TempDir temp;
    const auto replay = [&](const std::string& text) {
        spit(temp.dir / "replay.json", text);
        return run_engine(fake({"replay", (temp.dir / "replay.json").string()}), scene);
    };

    SECTION("the engine's engine and solver kept: the golden's bytes") {
        const EngineRun run = replay(engine_text(impulse, {"digest", "scene_sha256", "scene"}));
        CHECK(run.outcome == EngineRun::Outcome::ran);
        CHECK(write_trajectory(run.trajectory) == golden);
        CHECK(!run.cost);
        CHECK(run.seconds > 0.0);
    }
    SECTION("only the required keys: same numbers, the spec's name, an empty solver") {
        const EngineRun run =
            replay(engine_text(impulse, {"digest", "scene_sha256", "scene", "engine", "solver"}));
        const Trajectory& back = run.trajectory;
        CHECK(back.scene == "drop-box");
        CHECK(back.scene_sha256 == scene.sha256);
        CHECK(back.engine == engine_name);
        CHECK(back.solver.empty());
        CHECK(back.columns == impulse.columns);
        CHECK(digest_of(back) == digest_of(impulse));
        REQUIRE(back.frames.size() == impulse.frames.size());
        REQUIRE(back.events.size() == impulse.events.size());
        Trajectory same_header = back;
        same_header.engine = impulse.engine;
        same_header.solver = impulse.solver;
        CHECK(write_trajectory(same_header) == golden);
    }
    SECTION("a wrong digest and fingerprint from the engine are not trusted") {
        std::string text = engine_text(impulse, {"digest", "scene_sha256"});
        text.insert(text.find("\n") + 1, "  \"digest\": \"0000000000000000\",\n"
                                         "  \"scene_sha256\": \"not-even-hex\",\n");
        CHECK(write_trajectory(replay(text).trajectory) == golden);
    }
}

TEST_CASE("an engine that computes the scene it is given", "[engine-protocol]") {
    Fixture f;
    SECTION("overrides arrive as the modified scene and are recorded") {
        const std::string copy = (f.temp.dir / "received.json").string();
        const std::string where = (f.temp.dir / "where.txt").string();
        Overrides overrides;
        overrides.dt = 0.02;
        overrides.integrator = Integrator::rk4;
        const EngineRun run = run_engine(fake({"save-and-fall", copy, where}), f.fall, overrides);
        const Scene received = load_scene(copy);
        CHECK(received.dt == 0.02);
        CHECK(received.solver.integrator == Integrator::rk4);
        CHECK(run.trajectory.frames.size() == 6);            // 0.1 s in steps of 0.02 s, and t = 0
        CHECK(run.trajectory.scene_sha256 == f.fall.sha256); // the scene before overrides
        REQUIRE(!run.trajectory.solver.empty());
        CHECK(run.trajectory.solver.back() ==
              std::pair<std::string, std::string>{"overrides", R"(["dt", "integrator"])"});
        // The private folder the scene was written to is gone.
        CHECK(!fs::exists(fs::path(slurp(where)).parent_path()));
    }
    SECTION("its own cost is kept") {
        const EngineRun run = run_engine(fake({"cost"}), f.fall);
        REQUIRE(run.cost);
        CHECK(run.cost->seconds == 0.25);
        CHECK(run.cost->steps == 10);
    }
    SECTION("a child left holding standard output open does not hang the run") {
        const std::string pid_file = (f.temp.dir / "child.pid").string();
        spit(f.temp.dir / "replay.json", engine_text(run_scene(f.fall), {"digest"}));
        EngineSpec engine = fake({});
        engine.command = {"sh", engines_dir + "/leave_child.sh", pid_file,
                          (f.temp.dir / "replay.json").string()};
        const EngineRun run = run_engine(engine, f.fall);
        CHECK(run.trajectory.frames.size() == 11);
        CHECK(process_gone(slurp(pid_file)));
    }
}

TEST_CASE("an engine that fails is one sentence naming engine, scene and message",
          "[engine-protocol]") {
    Fixture f;
    const std::string failed = "engine 'fake-engine' failed on " + f.fall.file + ": ";
    SECTION("crash by a signal") {
        const std::string why = refusal(fake({"crash"}), f.fall);
        CHECK(why == failed + "signal 11 (" + ::strsignal(SIGSEGV) + "): about to crash");
    }
    SECTION("exit 1 with a message after other lines") {
        CHECK(refusal(fake({"fail", "cannot\tparse the scene"}), f.fall) ==
              failed + "exit status 1: cannot?parse the scene");
    }
    SECTION("exit 3 is a refusal, not a failure, with the engine's sentence") {
        const EngineRun run = run_engine(fake({"refuse", "polygons are not supported"}), f.fall);
        CHECK(run.outcome == EngineRun::Outcome::unsupported);
        CHECK(run.message == "polygons are not supported");
        CHECK(run.trajectory.frames.empty());
    }
    SECTION("a hang is killed at the time limit with its whole process group") {
        const std::string pid_file = (f.temp.dir / "grandchild.pid").string();
        EngineSpec engine = fake({}, 1.0);
        engine.command = {"sh", engines_dir + "/hang.sh", pid_file};
        CHECK(refusal(engine, f.fall) ==
              failed + "did not finish within 1 s; its process group was killed: (nothing on "
                       "standard error)");
        CHECK(process_gone(slurp(pid_file)));
    }
    SECTION("more output than the trajectory limit") {
        const LimitMib one_mib("1");
        const std::string why = refusal(fake({"flood", "2"}), f.fall);
        CHECK(why.rfind(failed + "wrote more than 1 MiB", 0) == 0);
        CHECK(why.find("its process group was killed") != std::string::npos);
    }
    SECTION("frames that alone pass the trajectory limit: refused before the engine starts") {
        const LimitMib one_mib("1");
        // One body: 7 numbers a frame, 8 bytes each and 64 for the row, so
        // 100,001 frames take 12,000,120 bytes, more than 1 MiB.
        Scene longer = f.fall;
        longer.dt = 1e-4;
        longer.duration = 10.0;
        EngineSpec engine = fake({});
        engine.command = {"/nonexistent/engine"}; // never started: no "cannot start"
        CHECK(refusal(engine, longer) ==
              f.fall.file + ": duration: the engine must write 100001 frames of 7 numbers "
                            "(100000 steps): 11.4 MiB in memory (700007 numbers), more than the "
                            "limit of 1 MiB (set IMPULSE_MAX_TRAJECTORY_MIB to a number of MiB "
                            "to change it)");
    }
    SECTION("a program that does not exist") {
        EngineSpec engine = fake({});
        engine.command = {"/nonexistent/engine"};
        engine.origin = "impulse.json: engines[0]";
        CHECK(refusal(engine, f.fall) ==
              failed + "cannot start '/nonexistent/engine': No such file or directory (the "
                       "command of impulse.json: engines[0])");
    }
    SECTION("a whole command line in one word: the words of an array are named") {
        EngineSpec engine = fake({});
        engine.command = {"build/engine --fast"};
        engine.origin = "impulse.json: engines[0]";
        CHECK(refusal(engine, f.fall) ==
              failed + "cannot start 'build/engine --fast': No such file or directory; the word "
                       "holds a space, and a command is one word per element, as "
                       "[\"build/engine\", \"--fast\"] (the command of impulse.json: "
                       "engines[0])");
    }
    SECTION("a bare name not in PATH: PATH is named") {
        EngineSpec engine = fake({});
        engine.command = {"no-such-engine-anywhere"};
        CHECK(refusal(engine, f.fall) ==
              failed + "cannot start 'no-such-engine-anywhere': No such file or directory; a "
                       "word without a '/' is looked up in PATH (write ./no-such-engine-anywhere "
                       "for a file in the working directory)");
    }
    SECTION("a file that is not executable") {
        spit(f.temp.dir / "engine.sh", "#!/bin/sh\necho {}\n");
        ::chmod((f.temp.dir / "engine.sh").c_str(), 0644);
        EngineSpec engine = fake({});
        engine.command = {"./engine.sh"};
        engine.working_directory = f.temp.dir.string();
        CHECK(refusal(engine, f.fall) == failed + "cannot start './engine.sh': Permission denied");
    }
}

TEST_CASE("whether a command can start is found as posix_spawnp finds it, without running it",
          "[engine-protocol]") {
    // start_problem is the preflight of every verb (one sentence before any
    // scene runs): for each command it must say exactly what starting it
    // says, in the same working folder.
    TempDir temp;
    spit(temp.dir / "engine.sh", "#!/bin/sh\nexit 0\n");
    ::chmod((temp.dir / "engine.sh").c_str(), 0755);
    spit(temp.dir / "plain.sh", "#!/bin/sh\nexit 0\n");
    ::chmod((temp.dir / "plain.sh").c_str(), 0644);
    std::filesystem::create_directories(temp.dir / "folder");
    const std::string here = temp.dir.string();
    const std::vector<std::vector<std::string>> commands = {
        {"sh", "-c", "exit 0"},  {"./engine.sh"},
        {"./plain.sh"},          {"./folder"},
        {"./no-such-engine"},    {"/nonexistent/engine"},
        {"build/engine --fast"}, {"no-such-engine-anywhere"},
        {here + "/engine.sh"}};
    for (const std::vector<std::string>& command : commands) {
        INFO(command.front());
        ProcessRequest request;
        request.command = command;
        request.working_directory = here;
        request.time_limit = 10.0;
        request.output_limit = 1024;
        CHECK(start_problem(command, here) == run_process(request).not_started);
    }
    CHECK_FALSE(start_problem({"./engine.sh"}, here));
    CHECK(start_problem({"./plain.sh"}, here) == "cannot start './plain.sh': Permission denied");
    // Relative to the engine's folder, not the harness's.
    CHECK(start_problem({"./engine.sh"}, (temp.dir / "folder").string()));
}

TEST_CASE("an engine's output is read as strictly as a scene", "[engine-protocol]") {
    Fixture f;
    const std::string output = "engine 'fake-engine' on " + f.fall.file + ": output";
    SECTION("a Python NaN and -Infinity name the JSON path") {
        CHECK(refusal(fake({"nan"}), f.fall)
                  .rfind(output + " frames[3][2]: NaN is not a finite number", 0) == 0);
        CHECK(refusal(fake({"infinity"}), f.fall)
                  .rfind(output + " frames[1][5]: -Infinity is not a finite number", 0) == 0);
    }
    SECTION("garbage and nothing") {
        CHECK(refusal(fake({"garbage"}), f.fall).rfind(output + ": begins with \"", 0) == 0);
        CHECK(refusal(fake({"empty"}), f.fall).rfind(output + ": is empty", 0) == 0);
        CHECK(refusal(f.replaying(" [1, 2]"), f.fall) ==
              output + ": the top level must be a JSON object (a trajectory), got an array");
        CHECK(refusal(f.replaying("42"), f.fall) ==
              output + ": the top level must be a JSON object (a trajectory), got 42");
    }
    SECTION("text before or after the trajectory: standard output holds the trajectory alone") {
        const std::string trajectory =
            engine_text(run_scene(f.fall), {"digest", "scene_sha256", "scene"});
        CHECK(refusal(f.replaying("DEBUG: step 1\n" + trajectory), f.fall) ==
              output + ": begins with \"DEBUG: step 1\", not with a trajectory's \"{\" "
                       "(standard output must hold only the trajectory; write anything else to "
                       "standard error)");
        const std::string after = refusal(f.replaying(trajectory + "\ndone.\n"), f.fall);
        CHECK(after.rfind(output + ": not valid JSON: ", 0) == 0);
        CHECK(after.find("(text follows the trajectory: standard output must hold only the "
                         "trajectory; write anything else to standard error)") !=
              std::string::npos);
        // Cut short is not followed by text: it is said as what it is.
        const std::string cut =
            refusal(f.replaying(trajectory.substr(0, trajectory.size() / 2)), f.fall);
        CHECK(cut.rfind(output + ": not valid JSON: ", 0) == 0);
        CHECK(cut.find("the output stops inside the trajectory") != std::string::npos);
        CHECK(cut.find("text follows") == std::string::npos);
        // Cut inside a number (after its sign or its point) or inside
        // a key: the parser names what it last read, not the end of input.
        const std::size_t frames = trajectory.find("\"frames\"");
        REQUIRE(frames != std::string::npos);
        for (const std::string& inside : std::vector<std::string>{".", "-", "\"t"}) {
            const std::size_t at = trajectory.find(inside, inside == "\"t" ? 0 : frames);
            REQUIRE(at != std::string::npos);
            const std::string cut_inside =
                refusal(f.replaying(trajectory.substr(0, at + inside.size())), f.fall);
            INFO("cut after '" << inside << "': " << cut_inside);
            CHECK(cut_inside.find("the output stops inside the trajectory") != std::string::npos);
        }
    }
    SECTION("a wrong, a missing and an extra column") {
        const auto columns = [&](std::vector<std::string> names) {
            return f.refusal_of([&](Trajectory& t) {
                t.columns = names;
                for (auto& frame : t.frames) {
                    frame.resize(names.size());
                }
            });
        };
        const std::vector<std::string> right = {"t",       "ball.x",  "ball.y",    "ball.angle",
                                                "ball.vx", "ball.vy", "ball.omega"};
        std::vector<std::string> wrong = right;
        wrong[4] = "ball.vz";
        CHECK(columns(wrong).rfind(output + " columns[4]: must be \"ball.vx\", got \"ball.vz\"",
                                   0) == 0);
        CHECK(columns({right.begin(), right.end() - 1}) ==
              output + " columns: column \"ball.omega\" is missing (6 of 7 columns given)");
        std::vector<std::string> extra = right;
        extra.push_back("ball.spin");
        CHECK(columns(extra).rfind(output + " columns[7]: \"ball.spin\" is one column too many",
                                   0) == 0);
    }
    SECTION("a frame too few, and a frame at the wrong time") {
        CHECK(f.refusal_of([](Trajectory& t) { t.frames.pop_back(); }) ==
              output + " frames: has 10 frames; the scene's 10 steps (duration 0.1 s, dt 0.01 "
                       "s) make 11");
        CHECK(f.refusal_of([](Trajectory& t) { t.frames[2][0] = 0.021; }) ==
              output + " frames[2][0]: t must be 0.02 (frame 2 is the state at k dt, within "
                       "1e-6 dt), got 0.021");
    }
    SECTION("an unknown key, and an event naming a body the scene does not have") {
        const std::string text =
            engine_text(run_scene(f.fall), {"digest", "scene_sha256", "scene"});
        const std::string with_key = text.substr(0, text.find('\n') + 1) +
                                     "  \"colour\": \"red\",\n" + text.substr(text.find('\n') + 1);
        CHECK(refusal(f.replaying(with_key), f.fall)
                  .rfind(output + " colour: unknown key; the keys allowed here are", 0) == 0);
        TrajectoryEvent ghost;
        ghost.a = "ball";
        ghost.b = "ghost";
        ghost.normal[1] = 1.0;
        CHECK(f.refusal_of([&](Trajectory& t) { t.events = {ghost}; }) ==
              output + " events[0].b: no body of the scene is named \"ghost\"");
        ghost.b = "ball";
        CHECK(f.refusal_of([&](Trajectory& t) { t.events = {ghost}; }) ==
              output + " events[0].b: is the same body as a; an event is between two");
    }
}

TEST_CASE("an engine's events and optional keys are checked against the scene",
          "[engine-protocol]") {
    Fixture f;
    const std::string output = "engine 'fake-engine' on " + f.fall.file + ": output";
    TrajectoryEvent hit;
    hit.t = 0.05;
    hit.a = "ball";
    hit.b = "floor";
    hit.normal[1] = 1.0;
    hit.impulse = 2.0;
    const auto with_events = [&](std::vector<TrajectoryEvent> events) {
        return f.refusal_of([&](Trajectory& t) { t.events = events; });
    };
    TrajectoryEvent bad = hit;
    bad.normal[0] = 0.1; // length sqrt(1.01)
    CHECK(with_events({bad}).rfind(output + " events[0].normal: must be a unit vector", 0) == 0);
    bad = hit;
    bad.impulse = -1e-9;
    CHECK(with_events({bad}) == output + " events[0].impulse: is the normal impulse's magnitude, "
                                         "must be >= 0, got -1e-09");
    bad = hit;
    bad.t = 0.2;
    CHECK(with_events({bad}) == output + " events[0].t: must lie in the run, from 0 to 0.1 s, "
                                         "got 0.2");
    bad.t = 0.04;
    CHECK(with_events({hit, bad}) == output + " events[1].t: is before the previous event's "
                                              "(0.05); events are in time order");
    // The same two events in order are a valid run.
    bad.t = 0.05;
    EngineRun run = run_engine(
        f.replaying(engine_text(trajectory_with_events(f.fall, {hit, bad}), {"digest"})), f.fall);
    CHECK(run.trajectory.events.size() == 2);

    const Trajectory plain = run_scene(f.fall);
    const auto with_line = [&](const std::string& line) {
        std::string text = engine_text(plain, {"digest", "scene_sha256", "scene", "solver"});
        text.insert(text.find('\n') + 1, "  " + line + ",\n");
        return refusal(f.replaying(text), f.fall);
    };
    CHECK(with_line(R"("scene": "drop")") ==
          output + " scene: must be the scene's name \"fall\", got \"drop\"");
    CHECK(with_line(R"("solver": {"overrides": ["dt"]})")
              .rfind(output + " solver.overrides: is the harness's key", 0) == 0);
    CHECK(with_line(R"("solver": {"substeps": [1]})") ==
          output + " solver.substeps: must be a string, a number or a boolean, got an array");
    CHECK(with_line(R"("cost": {"seconds": -1})") ==
          output + " cost.seconds: must be >= 0, got -1");
    CHECK(with_line(R"("cost": {"seconds": 1, "steps": 1.5})") ==
          output + " cost.steps: must be a whole number >= 0, got 1.5");
}

TEST_CASE("a process runs in its folder, its output whole and its errors' tail kept",
          "[engine-protocol]") {
    TempDir temp;
    ProcessRequest request;
    // 200,000 x on standard error, then a last line; the folder on standard output.
    request.command = {"sh", "-c",
                       "head -c 200000 /dev/zero | tr '\\0' x >&2; echo >&2; echo last >&2; pwd; "
                       "exit 7"};
    request.working_directory = temp.dir.string();
    request.output_limit = 1024;
    const ProcessResult result = run_process(request);
    REQUIRE(!result.not_started);
    CHECK(result.exit_code == 7);
    CHECK(!result.signal);
    CHECK(fs::equivalent(result.output.substr(0, result.output.size() - 1), temp.dir));
    REQUIRE(result.error_tail.size() == kept_error_bytes);
    CHECK(result.error_tail.substr(kept_error_bytes - 7) == "x\nlast\n");
    CHECK(last_line(result.error_tail, 300) == "last");
    CHECK(result.seconds > 0.0);
}

TEST_CASE("an engine's message is its last non-empty line, printable and short",
          "[engine-protocol]") {
    CHECK(last_line("first\nthe reason\n\n  \n", 300) == "the reason");
    CHECK(last_line("bell\a and \x1b[31mred\n", 300) == "bell? and ?[31mred");
    CHECK(last_line(std::string(400, 'x'), 300) == std::string(300, 'x') + "...");
    CHECK(last_line("", 300).empty());
    // Cut between characters, never inside one; a byte that is not UTF-8 is shown as \xNN.
    std::string accents;
    for (int i = 0; i < 350; ++i) {
        accents += "\xc3\xa9";
    }
    CHECK(last_line(accents, 300) == accents.substr(0, 600) + "...");
    CHECK(last_line("bad \xff byte", 300) == "bad \\xff byte");
}

TEST_CASE("an engine's message passes over the stack frames and banner a runtime adds to a crash",
          "[engine-protocol]") {
    // Node's report of an uncaught `throw new Error("no polygons here")`.
    const std::string node =
        "/work/engine.js:12\n    throw new Error(\"no polygons here\");\n"
        "    ^\n\nError: no polygons here\n"
        "    at step (/work/engine.js:12:11)\n"
        "    at Object.<anonymous> (/work/engine.js:40:1)\n"
        "    at node:internal/main/run_main_module:28:49\n\nNode.js v20.19.2\n";
    CHECK(last_line(node, 300) == "Error: no polygons here");
    // Java's: the exception's line comes first, its frames after it.
    CHECK(last_line(
              "Exception in thread \"main\" java.lang.IllegalStateException: no "
              "polygons\n\tat Engine.step(Engine.java:12)\n\tat Engine.main(Engine.java:40)\n",
              300) == "Exception in thread \"main\" java.lang.IllegalStateException: no polygons");
    // A message of the engine's own that starts with "at" is not indented: kept.
    CHECK(last_line("at t = 3 s the solver diverged\n", 300) == "at t = 3 s the solver diverged");
    CHECK(last_line("Node.js v20 is too old for this engine\n", 300) ==
          "Node.js v20 is too old for this engine");
    // Only trailer lines: the last of them, rather than nothing.
    CHECK(last_line("    at somewhere (x.js:1:1)\n", 300) == "at somewhere (x.js:1:1)");
}

#ifdef IMPULSE_WITH_BOX2D
TEST_CASE("the box2d engine runs a canonical scene", "[engine-protocol]") {
    const Scene scene = load_scene((source_dir / "harness/scenes/drop-box.json").string());
    const EngineRun run = run_engine(box2d_engine(), scene);
    CHECK(run.outcome == EngineRun::Outcome::ran);
    CHECK(run.trajectory.engine == "box2d 2.4.1");
    CHECK(run.trajectory.frames.size() == static_cast<std::size_t>(step_count(scene)) + 1);
    CHECK(run.trajectory.scene_sha256 == scene.sha256);

    SECTION("a scene single precision cannot hold is unsupported, naming the file and the value") {
        TempDir temp;
        std::string text = fall_scene_text;
        text.replace(text.find("\"velocity\""), 0, "\"mass\": 1e-300, ");
        spit(temp.dir / "tiny.json", text);
        const Scene tiny = load_scene((temp.dir / "tiny.json").string());
        const EngineRun refused = run_engine(box2d_engine(), tiny);
        CHECK(refused.outcome == EngineRun::Outcome::unsupported);
        CHECK(refused.message.rfind(tiny.file + ": bodies[0].mass: ", 0) == 0);
        CHECK(refused.message.find("Box2D") != std::string::npos);
    }
}
#endif
