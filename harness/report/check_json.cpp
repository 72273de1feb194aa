// The gate's results as JSON, impulse/check@1 (check_json.h).
#include "check_json.h"

#include "check_outcome.h"
#include "exact_json.h"
#include "first_divergence.h"

#include <cstddef>
#include <nlohmann/json.hpp>

namespace impulse::harness {

namespace {

using Json = nlohmann::ordered_json;
using Status = SceneCheck::Status;

Json text_or_null(const std::string& text) {
    return text.empty() ? Json(nullptr) : Json(text);
}

// The first divergence as the terminal states it: its line, then each of
// the numbers that line shows, exactly.
Json divergence_json(const Comparison& comparison) {
    const std::optional<FirstDivergence> first = first_divergence_of(comparison);
    if (!first) {
        return nullptr;
    }
    const Divergence& d = first->divergence;
    Json j;
    j["line"] = first_divergence_line(comparison);
    j["column"] = d.column;
    const std::size_t dot = d.column.rfind('.');
    if (first->is_event) {
        j["body"] = nullptr;
        j["event"] = d.frame;
        j["frame"] = nullptr;
    } else {
        j["body"] = dot == std::string::npos ? Json(nullptr) : Json(d.column.substr(0, dot));
        j["event"] = nullptr;
        j["frame"] = d.frame;
    }
    j["field"] = dot == std::string::npos ? d.column : d.column.substr(dot + 1);
    j["channel"] = channel_names[static_cast<std::size_t>(d.channel)];
    j["t"] = d.t;
    j["golden"] = d.gold;
    j["new"] = d.value;
    j["abs"] = d.abs_diff;
    j["rel"] = d.rel_diff;
    j["ulp"] = d.ulp;
    j["cause"] = first->cause;
    j["the_rest_follows"] = first->the_rest_follows;
    return j;
}

Json channels_json(const Comparison& comparison) {
    Json j = Json::object();
    for (std::size_t i = 0; i < comparison.channels.size(); ++i) {
        const ChannelSummary& s = comparison.channels[i];
        Json c;
        c["compared"] = s.compared;
        c["differing"] = s.differing;
        c["max_abs"] = s.max_abs;
        c["max_rel"] = s.max_rel;
        c["max_ulp"] = s.max_ulp;
        j[channel_names[i]] = std::move(c);
    }
    return j;
}

Json failed_expectations_json(const SceneCheck& check) {
    Json list = Json::array();
    for (const ExpectationResult& r : check.expectations) {
        if (!r.passed) {
            Json j;
            j["path"] = r.path;
            j["what"] = r.what;
            j["expected"] = r.expected;
            j["got"] = r.actual;
            j["allowed"] = r.allowed ? Json(*r.allowed) : Json(nullptr);
            j["message"] = text_or_null(r.detail);
            list.push_back(std::move(j));
        }
    }
    return list;
}

Json scene_json(const SceneCheck& check, const CheckRun& run) {
    Json j;
    j["name"] = display_name(check);
    j["engine"] = check.engine.empty() ? run.engine : check.engine;
    j["path"] = text_or_null(check.scene_file);
    j["golden"] = text_or_null(check.golden_file);
    j["status"] = check_status_key(check);
    j["failure"] = check.status == Status::failed  ? Json(failure_kind(check))
                   : check.status == Status::error ? Json(error_kind(check))
                                                   : Json(nullptr);
    j["seconds"] = check.seconds;
    // The row's sentence (the terminal's), for every status but ok.
    j["message"] = check.status == Status::passed ? Json(nullptr) : text_or_null(check.message);
    j["stale"] = check.stale;
    const bool compared = check.comparison.has_value();
    j["identical"] = compared ? Json(check.comparison->identical) : Json(nullptr);
    j["first_divergence"] = compared ? divergence_json(*check.comparison) : Json(nullptr);
    j["structural"] = compared ? Json(check.comparison->structural) : Json::array();
    j["channels"] = compared ? channels_json(*check.comparison) : Json(nullptr);
    j["failed_expectations"] = failed_expectations_json(check);
    Json warnings = check.scene_warnings;
    for (const std::string& warning : check.warnings) {
        warnings.push_back(warning);
    }
    j["warnings"] = warnings;
    return j;
}

Json totals_json(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    Json j;
    j["scenes"] = checks.size();
    j["passed"] = c.passed;
    j["failed"] = c.failed;
    j["errors"] = c.errors;
    j["skipped"] = c.skipped;
    j["seconds"] = c.seconds;
    return j;
}

// The project's regen command when a scene failed (every check of one
// project carries the same), else null: nothing to accept.
Json accept_json(const std::vector<SceneCheck>& checks) {
    if (count_checks(checks).failed == 0) {
        return nullptr;
    }
    for (const SceneCheck& check : checks) {
        if (!check.regen.empty()) {
            return check.regen;
        }
    }
    return "impulse regen";
}

} // namespace

const char* check_status_key(const SceneCheck& check) {
    switch (check.status) {
    case Status::passed:
        return "ok";
    case Status::error:
        return "error";
    case Status::skipped:
        return "skipped";
    case Status::failed:
        break;
    }
    if (check.stale) {
        return "stale";
    }
    return check.comparison && !check.comparison->passed ? "diff" : "failed";
}

std::string check_json(const std::vector<SceneCheck>& checks, const CheckRun& run) {
    Json document;
    document["schema"] = check_schema;
    document["mode"] = run.tolerance_mode ? "tolerance" : "exact";
    document["ci"] = run.ci;
    document["shard"] = run.shard ? Json(*run.shard) : Json(nullptr);
    document["notes"] = run.shard_notes;
    Json scenes = Json::array();
    for (const SceneCheck& check : checks) {
        scenes.push_back(scene_json(check, run));
    }
    document["scenes"] = std::move(scenes);
    document["shared_causes"] = shared_causes(checks);
    document["totals"] = totals_json(checks);
    document["accept"] = accept_json(checks);
    // The comparison's own document (impulse/engine-comparison@1), whole.
    document["comparison"] =
        run.comparison ? Json::parse(comparison_json(*run.comparison)) : Json(nullptr);
    document["comparison_error"] = text_or_null(run.comparison_error);
    document["exit_code"] = run.exit_code;
    return exact_json_text(document);
}

} // namespace impulse::harness
