// The scorecard as JUnit XML for CI (scorecard.h): the engine under test
// only; the references are there for scale, not to be passed.
#include "check_outcome.h"
#include "markup.h"
#include "scorecard.h"

#include <string>

namespace impulse::harness {

namespace {

std::string testcase_head(const SceneScore& scene, const std::string& name, double seconds) {
    return "    <testcase classname=\"impulse.conform." + xml_escape(scene.name, true) +
           "\" name=\"" + xml_escape(name, true) + "\" time=\"" + seconds_text(seconds) + "\"";
}

void write_scene(std::string& out, const SceneScore& scene) {
    const EngineScore& e = scene.engines.front();
    if (e.outcome != EngineScore::Outcome::ran) {
        const bool skipped = e.outcome == EngineScore::Outcome::unsupported;
        out += testcase_head(scene, scene.name, e.seconds) + ">\n";
        if (skipped) {
            out += "      <skipped message=\"" +
                   xml_escape("unsupported by " + e.engine + ": " + e.message, true) + "\"/>\n";
        } else {
            out += "      <error message=\"" + xml_escape(e.message, true) +
                   "\" type=\"engine error\">" + xml_escape(e.message) + "</error>\n";
        }
        out += "    </testcase>\n";
        return;
    }
    // The run's time shared by its checks, so the suite's total is right.
    const double each = e.results.empty() ? 0.0 : e.seconds / static_cast<double>(e.results.size());
    for (const ExpectationResult& r : e.results) {
        out += testcase_head(scene, r.path + " " + check_key(r), each);
        if (r.passed) {
            out += "/>\n";
            continue;
        }
        const std::string message = r.what + (r.detail.empty() ? "" : ": " + r.detail);
        out += ">\n      <failure message=\"" + xml_escape(message, true) +
               "\" type=\"outside the allowance\">" +
               xml_escape(message + "\nscene: " + scene.file) + "</failure>\n    </testcase>\n";
    }
}

} // namespace

std::string scorecard_junit(const Scorecard& card) {
    std::size_t tests = 0, failures = 0, errors = 0, skipped = 0;
    double seconds = 0.0;
    for (const SceneScore& scene : card.scenes) {
        const EngineScore& e = scene.engines.front();
        seconds += e.seconds;
        switch (e.outcome) {
        case EngineScore::Outcome::ran:
            tests += e.results.size();
            failures += e.results.size() - e.within();
            break;
        case EngineScore::Outcome::unsupported:
            ++tests;
            ++skipped;
            break;
        case EngineScore::Outcome::error:
            ++tests;
            ++errors;
            break;
        }
    }
    const std::string totals = " tests=\"" + std::to_string(tests) + "\" failures=\"" +
                               std::to_string(failures) + "\" errors=\"" + std::to_string(errors) +
                               "\" skipped=\"" + std::to_string(skipped) + "\" time=\"" +
                               seconds_text(seconds) + "\"";
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<testsuites name=\"impulse\"" + totals + ">\n";
    out += "  <testsuite name=\"impulse.conform." + xml_escape(card.engine, true) + "\"" + totals +
           ">\n";
    // The references' scores for scale, as properties: they are not the
    // engine under test's to pass, so never a testcase that could fail.
    if (!card.references.empty()) {
        out += "    <properties>\n";
        for (std::size_t e = 0; e < card.references.size(); ++e) {
            out += "      <property name=\"reference " + xml_escape(card.references[e], true) +
                   "\" value=\"" + xml_escape(reference_tally(card, e + 1), true) + "\"/>\n";
        }
        out += "    </properties>\n";
    }
    for (const SceneScore& scene : card.scenes) {
        write_scene(out, scene);
    }
    out += "  </testsuite>\n</testsuites>\n";
    return out;
}

} // namespace impulse::harness
