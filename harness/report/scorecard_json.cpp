// The scorecard as JSON, impulse/conformance@1 (scorecard.h; the fields are
// documented in docs/conformance.md).
#include "scorecard.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

namespace impulse::harness {

namespace {

using Json = nlohmann::ordered_json;

// null for what a check has no number for, and for what is not finite (JSON
// cannot hold it; the detail sentence says what it was).
Json number(std::optional<double> value) {
    return value && std::isfinite(*value) ? Json(*value) : Json(nullptr);
}

const char* outcome_word(const EngineScore& e) {
    switch (e.outcome) {
    case EngineScore::Outcome::ran:
        return e.passed() ? "passed" : "failed";
    case EngineScore::Outcome::unsupported:
        return "unsupported";
    case EngineScore::Outcome::error:
        return "error";
    }
    return "error";
}

Json result_json(const ExpectationResult& r) {
    Json j;
    j["path"] = r.path;
    j["check"] = check_key(r);
    j["what"] = r.what;
    const bool numeric = r.allowed.has_value();
    const double off = std::abs(r.actual - r.expected);
    j["exact"] = number(numeric ? std::optional(r.expected) : std::nullopt);
    j["value"] = number(numeric ? std::optional(r.actual) : std::nullopt);
    j["abs_error"] = number(numeric ? std::optional(off) : std::nullopt);
    j["rel_error"] = number(numeric && r.expected != 0.0 ? std::optional(off / std::abs(r.expected))
                                                         : std::nullopt);
    j["allowed"] = number(r.allowed);
    j["within"] = r.passed;
    j["detail"] = r.detail;
    return j;
}

Json engine_json(const EngineScore& e) {
    Json j;
    j["engine"] = e.engine;
    j["outcome"] = outcome_word(e);
    j["message"] = e.message;
    j["seconds"] = number(e.seconds);
    j["checks"] = e.results.size();
    j["within"] = e.within();
    Json results = Json::array();
    for (const ExpectationResult& r : e.results) {
        results.push_back(result_json(r));
    }
    j["results"] = std::move(results);
    return j;
}

} // namespace

std::string scorecard_json(const Scorecard& card) {
    const ConformanceCounts c = count_engine(card.scenes);
    Json document;
    document["schema"] = conformance_schema;
    document["engine"] = card.engine;
    document["references"] = card.references;
    document["scenes_dir"] = card.scenes_dir;
    document["notes"] = card.notes;
    document["passed"] = conforms(c);
    document["counts"] = {{"scenes", c.scenes}, {"passed", c.passed},
                          {"failed", c.failed}, {"unsupported", c.unsupported},
                          {"errors", c.errors}, {"checks", c.checks},
                          {"within", c.within}};
    // Each reference's tally, as "counts" is the engine under test's.
    Json reference_counts = Json::array();
    for (std::size_t e = 0; e < card.references.size(); ++e) {
        const ConformanceCounts r = count_engine(card.scenes, e + 1);
        reference_counts.push_back({{"engine", card.references[e]},
                                    {"scenes", r.scenes},
                                    {"passed", r.passed},
                                    {"failed", r.failed},
                                    {"unsupported", r.unsupported},
                                    {"errors", r.errors},
                                    {"checks", r.checks},
                                    {"within", r.within}});
    }
    document["reference_counts"] = std::move(reference_counts);
    Json scenes = Json::array();
    for (const SceneScore& s : card.scenes) {
        Json scene;
        scene["name"] = s.name;
        scene["file"] = s.file;
        Json engines = Json::array();
        for (const EngineScore& e : s.engines) {
            engines.push_back(engine_json(e));
        }
        scene["engines"] = std::move(engines);
        scenes.push_back(std::move(scene));
    }
    document["scenes"] = std::move(scenes);
    // Invalid UTF-8 in an engine's message is replaced, never a crash.
    return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace impulse::harness
