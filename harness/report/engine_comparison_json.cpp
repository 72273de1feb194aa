// impulse compare as JSON, impulse/engine-comparison@1 (engine_comparison.h;
// the fields are documented in docs/references.md).
#include "engine_comparison.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace impulse::harness {

namespace {

using Json = nlohmann::ordered_json;

Json number(std::optional<double> value) {
    return value && std::isfinite(*value) ? Json(*value) : Json(nullptr);
}

Json reference_json(const ReferenceEngine& r) {
    Json j;
    j["name"] = r.name;
    j["title"] = r.title;
    if (!r.available) {
        j["missing"] = r.missing;
        j["install"] = r.install;
    }
    return j;
}

// The solver block as recorded: each value is JSON text, kept as JSON.
Json settings_json(const EngineColumn& e) {
    Json settings = Json::object();
    for (const auto& [key, value] : e.settings) {
        settings[key] = Json::parse(value, nullptr, false);
    }
    return settings;
}

Json engine_json(const EngineColumn& e) {
    Json j;
    j["name"] = e.name;
    j["unsupported"] = e.unsupported.empty() ? Json(nullptr) : Json(e.unsupported);
    j["engine"] = e.run ? Json(e.engine) : Json(nullptr);
    j["settings"] = e.run ? settings_json(e) : Json(nullptr);
    j["command"] = e.command;
    return j;
}

Json row_json(const EngineComparison& c, const ObservableReadings& r) {
    Json j;
    j["path"] = r.path;
    j["name"] = r.name;
    j["exact"] = number(r.exact);
    Json values = Json::object(), errors = Json::object();
    for (std::size_t i = 0; i < c.engines.size(); ++i) {
        const std::optional<double>& v = r.values[i];
        values[c.engines[i].name] = number(v);
        errors[c.engines[i].name] =
            number(v && r.exact ? std::optional<double>(*v - *r.exact) : std::nullopt);
    }
    j["values"] = std::move(values);
    j["errors"] = std::move(errors);
    j["tolerance"] = number(r.tolerance());
    const std::optional<std::size_t> judged = judged_column(c);
    j["within"] = judged ? Json(r.within(*judged)) : Json(nullptr);
    j["note"] = r.note;
    return j;
}

Json scene_json(const EngineComparison& c) {
    Json j;
    j["name"] = c.name;
    j["file"] = c.file;
    const SceneStatus status = scene_status(c);
    j["status"] = status_name(status);
    // Neither a pass nor a failure: nothing was compared, or nothing ran.
    j["passed"] = status == SceneStatus::passed   ? Json(true)
                  : status == SceneStatus::failed ? Json(false)
                                                  : Json(nullptr);
    if (status == SceneStatus::no_observables) {
        j["note"] = no_observables_sentence;
    }
    if (c.skipped()) {
        j["skipped"] = c.engines.front().unsupported;
    }
    j["dt"] = c.dt;
    j["scene_integrator"] = c.scene_integrator;
    j["stopped"] = c.stopped.empty() ? Json(nullptr) : Json(c.stopped);
    j["warnings"] = c.warnings;
    Json engines = Json::array();
    for (const EngineColumn& e : c.engines) {
        engines.push_back(engine_json(e));
    }
    j["engines"] = std::move(engines);
    Json rows = Json::array();
    for (const ObservableReadings& r : c.rows) {
        rows.push_back(row_json(c, r));
    }
    j["rows"] = std::move(rows);
    return j;
}

} // namespace

std::string comparison_json(const ComparisonReport& report) {
    Json document;
    document["schema"] = engine_comparison_schema;
    document["engine"] = report.engine;
    document["engine_integrator"] = report.scene_integrator ? "scene" : "symplectic-euler";
    document["judged"] = judged_reference;
    Json references = Json::array(), skipped = Json::array();
    for (const ReferenceEngine& r : report.references) {
        references.push_back(reference_json(r));
    }
    for (const ReferenceEngine& r : report.skipped) {
        skipped.push_back(reference_json(r));
    }
    document["references"] = std::move(references);
    document["skipped_references"] = std::move(skipped);
    document["notes"] = report.notes;
    document["passed"] = comparison_passed(report);
    Json scenes = Json::array();
    for (const EngineComparison& c : report.scenes) {
        scenes.push_back(scene_json(c));
    }
    document["scenes"] = std::move(scenes);
    // Invalid UTF-8 in an engine's message is replaced, never a crash.
    return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace impulse::harness
