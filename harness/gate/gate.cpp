#include "gate.h"

#include "atomic_file.h"
#include "golden_settings.h"
#include "input_error.h"
#include "number_format.h"
#include "parallel_check.h"
#include "run.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : text) {
        h = (h ^ c) * 0x100000001b3ull;
    }
    return h;
}

std::string stem(const std::string& path) {
    return fs::path(path).stem().string();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Whether anything is at `path`, the entry itself and not what it points to:
// a dangling symlink or a symlink loop exists (and fails to read with a
// sentence); an error other than "not there" (no permission) counts as there,
// so reading it says what is wrong instead of "missing".
bool entry_exists(const std::string& path) {
    std::error_code error;
    return fs::symlink_status(path, error).type() != fs::file_type::not_found;
}

std::string lower_case(std::string text) {
    for (char& c : text) {
        if (c >= 'A' && c <= 'Z') {
            c = static_cast<char>(c - 'A' + 'a');
        }
    }
    return text;
}

const char* case_reason = "differ only in case: on a case-insensitive file system (macOS, "
                          "Windows) they are one file and their goldens would overwrite each "
                          "other; rename one";

// Scene files whose names (their goldens' names) differ only in case are
// refused as a pair. The same name twice is one scene named twice, not a clash.
void refuse_case_collisions(const std::vector<std::string>& scene_paths) {
    for (std::size_t i = 0; i < scene_paths.size(); ++i) {
        for (std::size_t j = i + 1; j < scene_paths.size(); ++j) {
            const std::string a = stem(scene_paths[i]), b = stem(scene_paths[j]);
            if (a != b && lower_case(a) == lower_case(b)) {
                throw InputError(scene_paths[i], "", "and " + scene_paths[j] + " " + case_reason);
            }
        }
    }
}

// A golden named like the scene but for case (goldens/Drop.json for scene
// drop) is the scene's golden on a case-insensitive file system and an
// orphan elsewhere: refused, never blessed over or pruned.
void refuse_case_variant_golden(const GateRoot& root, const std::string& scene_path,
                                const std::string& name) {
    std::error_code error;
    for (fs::directory_iterator it(root.goldens_dir(), error), end; !error && it != end;
         it.increment(error)) {
        const std::string golden_name = it->path().stem().string();
        if (it->path().extension() == ".json" && golden_name != name &&
            lower_case(golden_name) == lower_case(name)) {
            throw InputError(it->path().string(), "",
                             "and the scene file " + scene_path + " " + case_reason);
        }
    }
}

// A scene's golden is goldens/NAME.json, so a scene file must be NAME.json:
// otherwise two files (a copy, or one renamed without its name) would write
// one golden in turn, each blessing losing the other's.
Scene load_scene_for_golden(const std::string& scene_path) {
    Scene scene = load_scene(scene_path);
    if (stem(scene_path) != scene.name) {
        throw InputError(scene_path, "name",
                         "is \"" + scene.name + "\" but the file is " +
                             fs::path(scene_path).filename().string() +
                             ": a scene's golden is goldens/NAME.json, so its file must be "
                             "NAME.json");
    }
    return scene;
}

Tolerances tolerances_for(const Scene& scene, const CheckOptions& options) {
    Tolerances t = scene.tolerances;
    if (options.atol) {
        t = parse_tolerance_option("--atol", *options.atol, t);
    }
    if (options.rtol) {
        t = parse_tolerance_option("--rtol", *options.rtol, t);
    }
    if (options.ulp) {
        t = parse_tolerance_option("--ulp", *options.ulp, t);
    }
    return t;
}

std::string first_divergence_line(const Comparison& comparison) {
    if (!comparison.structural.empty()) {
        return comparison.structural.front();
    }
    if (comparison.first_divergences.empty()) {
        return "the trajectories differ";
    }
    // The earliest divergent frame is where the motion first parted; an event
    // field is named only when no frame differs.
    const Divergence* first = nullptr;
    for (const Divergence& d : comparison.first_divergences) {
        const bool is_event = d.column.rfind("events[", 0) == 0;
        if (!is_event && (first == nullptr || d.t < first->t)) {
            first = &d;
        }
    }
    if (first == nullptr) {
        first = &comparison.first_divergences.front();
    }
    return "first divergence: " + first->column + " at t = " + format_double(first->t) +
           " s (golden " + format_double(first->gold) + ", new " + format_double(first->value) +
           ")";
}

std::string failed_expectations(const std::vector<ExpectationResult>& results, int& count) {
    std::ostringstream out;
    count = 0;
    for (const ExpectationResult& r : results) {
        if (!r.passed) {
            ++count;
            out << "  " << r.path << " " << r.what << ": expected " << format_double(r.expected)
                << ", got " << format_double(r.actual);
            if (!r.detail.empty()) {
                out << " (" << r.detail << ")";
            }
            out << "\n";
        }
    }
    return out.str();
}

// Fails the check, with one line and the details, for each thing that
// differs: a stale golden, other settings, the data, a broken expectation.
void record_verdict(SceneCheck& check) {
    int failed_count = 0;
    const std::string failed = failed_expectations(check.expectations, failed_count);
    std::ostringstream details;
    std::vector<std::string> reasons;
    if (check.stale) {
        reasons.push_back("stale golden: the scene changed since it was blessed; if that was "
                          "intended, run scripts/regen-goldens " +
                          check.name);
    }
    const SettingsComparison settings = compare_settings(*check.gold, *check.value);
    check.warnings = settings.notes;
    if (!settings.differences.empty()) {
        std::string joined;
        details << "settings that differ from the golden's:\n";
        for (const std::string& d : settings.differences) {
            joined += (joined.empty() ? "" : "; ") + d;
            details << "  " << d << "\n";
        }
        reasons.push_back("the golden was recorded with other settings: " + joined);
    }
    if (!check.comparison->passed) {
        reasons.push_back(first_divergence_line(*check.comparison));
        details << describe(*check.comparison);
    }
    if (failed_count > 0) {
        reasons.push_back(std::to_string(failed_count) + " declared expectation" +
                          (failed_count == 1 ? "" : "s") + " failed");
        details << "failed expectations:\n" << failed;
    }
    if (!reasons.empty()) {
        check.status = SceneCheck::Status::failed;
        check.message = reasons.front();
        for (std::size_t i = 1; i < reasons.size(); ++i) {
            check.message += "; " + reasons[i];
        }
        check.details = details.str();
    }
}

} // namespace

std::string GateRoot::scenes_dir() const {
    return (fs::path(root) / "harness" / "scenes").string();
}
std::string GateRoot::goldens_dir() const {
    return (fs::path(root) / "goldens").string();
}
std::string GateRoot::golden_path(const std::string& scene_name) const {
    return (fs::path(goldens_dir()) / (scene_name + ".json")).string();
}

bool ci_mode() {
    const char* ci = std::getenv("CI");
    if (ci == nullptr) {
        return false;
    }
    const std::string value = ci;
    return !(value.empty() || value == "0" || value == "false");
}

std::vector<std::string> canonical_scenes(const GateRoot& root) {
    const std::string dir = root.scenes_dir();
    std::error_code error;
    if (!fs::is_directory(dir, error)) {
        throw InputError(dir, "",
                         "no scene folder here; run from the repository root or give --root");
    }
    // Every NAME.json entry is a scene, whatever it is: one that cannot be
    // read (a dangling symlink, a folder) is that scene's error when it is
    // loaded, never skipped, and its golden is never pruned.
    std::vector<std::string> paths;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".json") {
            paths.push_back(entry.path().string());
        }
    }
    std::sort(paths.begin(), paths.end());
    refuse_case_collisions(paths);
    return paths;
}

std::string resolve_scene(const GateRoot& root, const std::string& argument) {
    std::error_code error;
    if (fs::is_regular_file(argument, error) || fs::path(argument).extension() == ".json" ||
        argument.find('/') != std::string::npos) {
        return argument;
    }
    return (fs::path(root.scenes_dir()) / (argument + ".json")).string();
}

std::vector<std::string> scenes_named(const GateRoot& root,
                                      const std::vector<std::string>& arguments) {
    if (arguments.empty()) {
        return canonical_scenes(root);
    }
    std::vector<std::string> paths;
    for (const std::string& argument : arguments) {
        paths.push_back(resolve_scene(root, argument));
    }
    refuse_case_collisions(paths);
    return paths;
}

std::vector<std::string> unreferenced_goldens(const GateRoot& root) {
    // Lower case: a golden differing from a scene's name only in case is
    // refused by check and bless for that scene, never pruned.
    std::vector<std::string> names;
    for (const std::string& path : canonical_scenes(root)) {
        names.push_back(lower_case(stem(path)));
    }
    std::vector<std::string> unreferenced;
    std::error_code error;
    if (!fs::is_directory(root.goldens_dir(), error)) {
        return unreferenced;
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(root.goldens_dir())) {
        const std::string name = lower_case(entry.path().stem().string());
        if (entry.path().extension() == ".json" &&
            std::find(names.begin(), names.end(), name) == names.end()) {
            unreferenced.push_back(entry.path().string());
        }
    }
    std::sort(unreferenced.begin(), unreferenced.end());
    return unreferenced;
}

std::vector<std::string> shard(const std::vector<std::string>& scene_paths, int k, int n) {
    std::vector<std::string> kept;
    for (const std::string& path : scene_paths) {
        if (static_cast<int>(fnv1a(stem(path)) % static_cast<std::uint64_t>(n)) == k - 1) {
            kept.push_back(path);
        }
    }
    return kept;
}

SceneCheck check_scene(const GateRoot& root, const std::string& scene_path,
                       const CheckOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    SceneCheck check;
    check.scene_file = scene_path;
    check.name = stem(scene_path);
    try {
        check.scene = load_scene_for_golden(scene_path);
        const Scene& scene = *check.scene;
        check.name = scene.name;
        check.golden_file = root.golden_path(scene.name);

        std::optional<Tolerances> tolerances;
        if (options.tolerance_mode) {
            tolerances = tolerances_for(scene, options);
        }
        check.value = run_scene(scene);
        check.expectations = evaluate_expectations(scene, *check.value);

        refuse_case_variant_golden(root, scene_path, scene.name);
        if (!entry_exists(check.golden_file)) {
            throw InputError(check.golden_file, "",
                             "no golden for scene '" + scene.name +
                                 "'; bless it with scripts/regen-goldens " + scene.name);
        }
        check.gold = read_trajectory_file(check.golden_file, "a golden");
        if (tolerances) {
            const std::vector<Channel> missing =
                channels_without_tolerance(*check.gold, *tolerances);
            if (!missing.empty()) {
                throw InputError(scene.file, "tolerance",
                                 std::string("no tolerance for channel '") +
                                     channel_names[static_cast<int>(missing.front())] +
                                     "' in tolerance mode; give it in the scene's tolerance "
                                     "block or with --atol/--rtol/--ulp");
            }
        }
        check.comparison = compare(*check.gold, *check.value, tolerances);
        check.stale = check.gold->scene_sha256 != scene.sha256;

        record_verdict(check);
    } catch (const InputError& e) {
        check.status = SceneCheck::Status::error;
        check.message = e.what();
    } catch (const std::invalid_argument& e) {
        check.status = SceneCheck::Status::error;
        check.message = e.what();
    }
    check.seconds = seconds_since(start);
    return check;
}

std::vector<SceneCheck> check_scenes(const GateRoot& root, const std::vector<std::string>& paths,
                                     const CheckOptions& options) {
    // on_start and on_done may run on any worker thread (the progress bar's are thread-safe).
    return check_each(paths, options.jobs, [&](const std::string& path) {
        if (options.on_start) {
            options.on_start(path);
        }
        SceneCheck result = check_scene(root, path, options);
        if (options.on_done) {
            options.on_done();
        }
        return result;
    });
}

Blessing bless_scene(const GateRoot& root, const std::string& scene_path) {
    Blessing blessing;
    blessing.name = stem(scene_path);
    const Scene scene = load_scene_for_golden(scene_path);
    blessing.name = scene.name;
    blessing.golden_file = root.golden_path(scene.name);
    const Trajectory trajectory = run_scene(scene);
    int failed_count = 0;
    const std::string failed =
        failed_expectations(evaluate_expectations(scene, trajectory), failed_count);
    if (failed_count > 0) {
        blessing.outcome = Blessing::Outcome::refused;
        blessing.summary = "the run breaks " + std::to_string(failed_count) +
                           " of the scene's own expectations, so it is not blessed:\n" + failed;
        return blessing;
    }
    const std::string text = write_trajectory(trajectory);
    // Never a golden that check would refuse.
    require_readable_size(text, blessing.golden_file);

    refuse_case_variant_golden(root, scene_path, scene.name);
    if (!entry_exists(blessing.golden_file)) {
        blessing.outcome = Blessing::Outcome::created;
    } else {
        std::string old_text;
        try {
            old_text = read_trajectory_text(blessing.golden_file, "a golden");
        } catch (const InputError& e) {
            old_text.clear();
            blessing.summary = std::string("the old golden could not be read: ") + e.what() + "\n";
        }
        if (old_text == text) {
            blessing.outcome = Blessing::Outcome::unchanged;
            return blessing;
        }
        blessing.outcome = Blessing::Outcome::changed;
        try {
            const Trajectory old = read_trajectory(old_text, blessing.golden_file);
            if (old.scene_sha256 != scene.sha256) {
                blessing.summary += "the scene itself changed since the last blessing\n";
            }
            blessing.summary += describe(compare(old, trajectory, std::nullopt));
        } catch (const InputError& e) {
            if (blessing.summary.empty()) {
                blessing.summary = std::string("the old golden does not parse: ") + e.what() + "\n";
            }
        }
    }
    std::error_code error;
    fs::create_directories(root.goldens_dir(), error);
    try {
        write_file_atomically(blessing.golden_file, text);
    } catch (const InputError& e) {
        // The scene is fine; the folder or the disk is not.
        blessing.outcome = Blessing::Outcome::unwritten;
        blessing.summary = e.what();
    }
    return blessing;
}

} // namespace impulse::harness
