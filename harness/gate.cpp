#include "gate.h"

#include "atomic_file.h"
#include "input_error.h"
#include "number_format.h"
#include "run.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <thread>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

// Goldens can be large (long runs); anything beyond this is not a golden.
constexpr std::size_t max_trajectory_bytes = 256u * 1024 * 1024;

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
    std::vector<std::string> paths;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
        // Anything but a folder is listed, so a FIFO or a dangling link named
        // NAME.json is an ERROR row (read_file refuses it) instead of a scene
        // silently left out of the gate; listing opens nothing.
        if (!entry.is_directory() && entry.path().extension() == ".json") {
            paths.push_back(entry.path().string());
        }
    }
    std::sort(paths.begin(), paths.end());
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
    return paths;
}

std::vector<std::string> unreferenced_goldens(const GateRoot& root) {
    std::vector<std::string> names;
    for (const std::string& path : canonical_scenes(root)) {
        names.push_back(stem(path));
    }
    std::vector<std::string> unreferenced;
    std::error_code error;
    if (!fs::is_directory(root.goldens_dir(), error)) {
        return unreferenced;
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(root.goldens_dir())) {
        const std::string name = entry.path().stem().string();
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

        std::error_code error;
        if (!fs::exists(check.golden_file, error)) {
            throw InputError(check.golden_file, "",
                             "no golden for scene '" + scene.name +
                                 "'; bless it with scripts/regen-goldens " + scene.name);
        }
        check.gold = read_trajectory(
            read_file(check.golden_file, max_trajectory_bytes, "a golden is at most that"),
            check.golden_file);
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

        int failed_count = 0;
        const std::string failed = failed_expectations(check.expectations, failed_count);
        std::ostringstream details;
        std::vector<std::string> reasons;
        if (check.stale) {
            reasons.push_back("stale golden: the scene changed since it was blessed; if that was "
                              "intended, run scripts/regen-goldens " +
                              scene.name);
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
    std::vector<SceneCheck> results(paths.size());
    const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(paths.size())));
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i = next++; i < paths.size(); i = next++) {
            results[i] = check_scene(root, paths[i], options);
        }
    };
    std::vector<std::thread> threads;
    for (int t = 1; t < jobs; ++t) {
        threads.emplace_back(worker);
    }
    worker();
    for (std::thread& t : threads) {
        t.join();
    }
    return results;
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

    std::error_code error;
    if (!fs::exists(blessing.golden_file, error)) {
        blessing.outcome = Blessing::Outcome::created;
    } else {
        std::string old_text;
        try {
            old_text =
                read_file(blessing.golden_file, max_trajectory_bytes, "a golden is at most that");
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
    fs::create_directories(root.goldens_dir(), error);
    write_file_atomically(blessing.golden_file, text);
    return blessing;
}

} // namespace impulse::harness
