// impulse/run@1 (run_json.h).
#include "run_json.h"

#include "number_format.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace impulse::harness {

namespace {

using Json = nlohmann::ordered_json;

// JSON has no NaN or infinity: null stands for a value that is not a number.
Json number(double value) {
    return std::isfinite(value) ? Json(value) : Json(nullptr);
}

Json expectation_json(const ExpectationResult& r) {
    Json j;
    j["path"] = r.path;
    j["what"] = r.what;
    j["passed"] = r.passed;
    j["expected"] = number(r.expected);
    j["actual"] = number(r.actual);
    j["allowed"] = r.allowed ? number(*r.allowed) : Json(nullptr);
    j["message"] = r.passed ? Json(nullptr) : Json(expectation_message(r));
    return j;
}

} // namespace

std::string expectation_message(const ExpectationResult& r) {
    if (!r.numeric) {
        return r.path + ": " + r.what + ": " + r.detail; // no "expected 0, got 0" beside an inf
    }
    return r.path + ": " + r.what + ": expected " + format_double(r.expected) + ", got " +
           format_double(r.actual) + (r.detail.empty() ? "" : " (" + r.detail + ")");
}

std::string run_json(const RunResult& result) {
    const Trajectory& t = *result.trajectory;
    Json document;
    document["schema"] = run_schema;
    document["scene"] = result.scene->name;
    document["scene_file"] = result.scene->file;
    document["engine"] = result.engine_name;
    document["engine_version"] = t.engine;
    document["trajectory"] = result.trajectory_file ? Json(*result.trajectory_file) : Json(nullptr);
    // Frames are recorded at t = 0 and after every step.
    document["steps"] = t.frames.empty() ? 0 : t.frames.size() - 1;
    document["frames"] = t.frames.size();
    document["events"] = t.events.size();
    document["t_end"] =
        t.frames.empty() || t.frames.back().empty() ? Json(nullptr) : number(t.frames.back()[0]);
    document["partial"] = t.partial
                              ? Json{{"reason", t.partial->reason}, {"t", number(t.partial->t)}}
                              : Json(nullptr);
    document["warnings"] = result.scene->warnings;
    if (result.expectations) {
        Json expectations = Json::array();
        bool passed = true;
        for (const ExpectationResult& r : *result.expectations) {
            expectations.push_back(expectation_json(r));
            passed = passed && r.passed;
        }
        document["expectations"] = std::move(expectations);
        document["passed"] = passed;
    } else {
        document["expectations"] = nullptr;
        document["passed"] = false;
    }
    return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace impulse::harness
