// The conformance suite (conformance.h): the rule that picks the scenes, and
// scoring engines on their expectations.
#include "conformance.h"

#include "atomic_file.h"
#include "input_error.h"
#include "parallel_check.h"
#include "strict_json.h"
#include "text.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <thread>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

// As scene.cpp's limit: a scene is a few kilobytes.
constexpr std::size_t max_scene_bytes = std::size_t{16} * 1024 * 1024;

bool names(const std::vector<std::string>& keys, const std::string& key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

// A model key's value as the scene file spells it.
std::string model_value(const SolverSettings& solver, const std::string& key) {
    if (key == "contacts") {
        return double_quoted(contact_mode_name(solver.contacts));
    }
    if (key == "vertex_normal") {
        return double_quoted(vertex_normal_name(solver.vertex_normal));
    }
    if (key == "stepping") {
        return double_quoted(stepping_name(solver.stepping));
    }
    return solver.resting ? "true" : "false";
}

// The keys the file's solver block names, defaults included.
std::vector<std::string> solver_keys_of(const std::string& text, const std::string& file) {
    const nlohmann::json document = parse_strict_json<nlohmann::json>(text, file);
    std::vector<std::string> keys;
    const auto solver = document.find("solver");
    if (solver != document.end() && solver->is_object()) {
        for (const auto& item : solver->items()) {
            keys.push_back(item.key());
        }
    }
    return keys;
}

EngineScore score_in(const EngineSpec& engine, const Scene& scene) {
    EngineScore score;
    score.engine = engine.name;
    const auto start = std::chrono::steady_clock::now();
    try {
        const EngineRun run = run_engine(engine, scene);
        score.seconds = run.seconds;
        if (run.outcome == EngineRun::Outcome::unsupported) {
            score.outcome = EngineScore::Outcome::unsupported;
            score.message = run.message;
            return score;
        }
        score.results = evaluate_expectations(scene, run.trajectory);
        return score;
    } catch (const InputError& e) {
        score.message = e.what(); // names the engine, the scene and what went wrong
    } catch (const std::bad_alloc&) {
        score.message = printable_path(scene.file) + ": ran out of memory running it in " +
                        single_quoted(engine.name);
    } catch (const std::exception& e) {
        score.message = printable_path(scene.file) + ": internal error running it in " +
                        single_quoted(engine.name) + ": " + e.what();
    }
    score.outcome = EngineScore::Outcome::error;
    score.results.clear();
    score.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return score;
}

} // namespace

std::optional<std::string> conformance_exclusion(const Scene& scene,
                                                 const std::vector<std::string>& solver_keys) {
    if (scene.expectations.empty()) {
        return "it declares no expectations, so there is nothing to score";
    }
    for (const std::string key : model_solver_keys) {
        if (names(solver_keys, key)) {
            return "its solver block chooses a collision model (" + double_quoted(key) + ": " +
                   model_value(scene.solver, key) +
                   "), so its answers hold under that model, not for every correct engine";
        }
    }
    const Integrator integrator = scene.solver.integrator;
    const bool gravity = scene.gravity.x != 0.0 || scene.gravity.y != 0.0;
    if (gravity &&
        (integrator == Integrator::euler || integrator == Integrator::symplectic_euler)) {
        return std::string("it is integrated with ") + integrator_name(integrator) +
               " under gravity, which is not exact in free flight, so its answers are what "
               "survives that integrator's error: a study of the integrator";
    }
    return std::nullopt;
}

std::vector<ShippedScene> shipped_scenes(const std::string& dir) {
    std::vector<std::string> paths;
    std::error_code error;
    for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
        if (it->path().extension() == ".json") {
            paths.push_back(it->path().string());
        }
    }
    if (error) {
        throw InputError(dir, "", "cannot list the shipped scenes: " + error.message());
    }
    std::sort(paths.begin(), paths.end());
    std::vector<ShippedScene> shipped;
    for (const std::string& path : paths) {
        const std::string text = read_file(path, max_scene_bytes, "a scene is a few kilobytes");
        ShippedScene s{parse_scene(text, path), solver_keys_of(text, path), std::nullopt};
        s.exclusion = conformance_exclusion(s.scene, s.solver_keys);
        shipped.push_back(std::move(s));
    }
    return shipped;
}

std::size_t EngineScore::within() const {
    return static_cast<std::size_t>(std::count_if(
        results.begin(), results.end(), [](const ExpectationResult& r) { return r.passed; }));
}

SceneScore score_scene(const Scene& scene, const std::vector<EngineSpec>& engines) {
    SceneScore score;
    score.name = scene.name;
    score.file = scene.file;
    for (const EngineSpec& engine : engines) {
        score.engines.push_back(score_in(engine, scene));
    }
    return score;
}

std::vector<SceneScore> score_scenes(const std::vector<Scene>& scenes,
                                     const std::vector<EngineSpec>& engines,
                                     const ScoringOptions& options) {
    std::vector<SceneScore> scores(scenes.size());
    // score_scene turns an engine's failure into its row; what escapes it
    // (memory exhausted even for that) ends the run with one sentence.
    for_each_index(scenes.size(), options.jobs, [&](std::size_t i) {
        if (options.on_start) {
            options.on_start(scenes[i].name);
        }
        scores[i] = score_scene(scenes[i], engines);
        if (options.on_done) {
            options.on_done();
        }
    });
    return scores;
}

ConformanceCounts count_engine(const std::vector<SceneScore>& scores, std::size_t index) {
    ConformanceCounts c;
    for (const SceneScore& scene : scores) {
        if (index >= scene.engines.size()) {
            continue;
        }
        const EngineScore& e = scene.engines[index];
        ++c.scenes;
        switch (e.outcome) {
        case EngineScore::Outcome::ran:
            (e.passed() ? c.passed : c.failed) += 1;
            c.checks += e.results.size();
            c.within += e.within();
            break;
        case EngineScore::Outcome::unsupported:
            ++c.unsupported;
            break;
        case EngineScore::Outcome::error:
            ++c.errors;
            break;
        }
    }
    return c;
}

bool conforms(const ConformanceCounts& counts) {
    return counts.errors == 0 && counts.failed == 0 && counts.passed > 0;
}

std::string check_key(const ExpectationResult& result) {
    std::string key = result.what.substr(0, result.what.find(", "));
    for (const char* component : {" (x)", " (y)"}) {
        const std::string suffix = component;
        if (key.size() > suffix.size() &&
            key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) {
            key.erase(key.size() - suffix.size());
        }
    }
    return key;
}

} // namespace impulse::harness
