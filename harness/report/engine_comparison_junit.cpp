// impulse compare as JUnit XML for CI (engine_comparison.h): a testcase per
// scene and engine, so CI shows each reference's result on each scene; only
// the judged reference can fail one.
#include "engine_comparison.h"
#include "markup.h"

#include <cstdio>
#include <string>

namespace impulse::harness {

namespace {

struct Totals {
    std::size_t tests = 0, failures = 0, skipped = 0;
};

std::string testcase(const std::string& scene, const std::string& engine) {
    return "    <testcase classname=\"impulse.compare." + xml_escape(scene, true) + "\" name=\"" +
           xml_escape(engine, true) + "\"";
}

std::string skipped_case(const std::string& scene, const std::string& engine,
                         const std::string& message, Totals& totals) {
    ++totals.tests;
    ++totals.skipped;
    return testcase(scene, engine) + ">\n      <skipped message=\"" + xml_escape(message, true) +
           "\"/>\n    </testcase>\n";
}

// The judged reference's rows outside tolerance, one line each.
std::string outside_lines(const EngineComparison& c, std::size_t column) {
    std::string text;
    for (const ObservableReadings& r : c.rows) {
        if (!r.within(column)) {
            text += r.path + ", " + r.name + ": outside the tolerance of the engine under study\n";
        }
    }
    return text;
}

std::string worst_line(const EngineComparison& c, const std::string& engine) {
    const std::optional<WorstError> worst = worst_error({c}, engine);
    if (!worst) {
        return "no row with an exact answer";
    }
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.3g%%", 100.0 * worst->relative);
    return "worst error against the exact answer " + std::string(buffer) + " (" + worst->row + ")";
}

std::string scene_cases(const EngineComparison& c, Totals& totals) {
    std::string out;
    for (std::size_t i = 0; i < c.engines.size(); ++i) {
        const EngineColumn& e = c.engines[i];
        if (!e.run) {
            out += skipped_case(c.name, e.name, e.unsupported, totals);
            continue;
        }
        ++totals.tests;
        out += testcase(c.name, e.name) + ">\n";
        if (judged_column(c) == i && rows_outside(c) > 0) {
            ++totals.failures;
            const std::string message = std::to_string(rows_outside(c)) + " of " +
                                        std::to_string(c.rows.size()) +
                                        " rows outside the scene's tolerance";
            out += "      <failure message=\"" + xml_escape(message, true) +
                   "\" type=\"outside the tolerance\">" +
                   xml_escape(outside_lines(c, i) + "scene: " + c.file) + "</failure>\n";
        }
        out += "      <system-out>" + xml_escape(worst_line(c, e.name)) +
               "</system-out>\n    </testcase>\n";
    }
    return out;
}

} // namespace

ComparisonSuite comparison_junit_suite(const ComparisonReport& report) {
    Totals totals;
    std::string cases;
    for (const EngineComparison& c : report.scenes) {
        if (c.nothing_declared()) {
            // One case for the scene, so CI shows it was not compared.
            cases += skipped_case(c.name, report.engine, no_observables_sentence, totals);
            continue;
        }
        cases += scene_cases(c, totals);
        for (const ReferenceEngine& r : report.skipped) {
            cases += skipped_case(c.name, r.name, unavailable_sentence(r), totals);
        }
    }
    ComparisonSuite suite;
    suite.tests = totals.tests;
    suite.failures = totals.failures;
    suite.skipped = totals.skipped;
    suite.xml = "  <testsuite name=\"impulse.compare\"" + counts_attributes(suite) + ">\n" + cases +
                "  </testsuite>\n";
    return suite;
}

std::string counts_attributes(const ComparisonSuite& suite) {
    return " tests=\"" + std::to_string(suite.tests) + "\" failures=\"" +
           std::to_string(suite.failures) + "\" errors=\"0\" skipped=\"" +
           std::to_string(suite.skipped) + "\"";
}

std::string comparison_junit(const ComparisonReport& report) {
    const ComparisonSuite suite = comparison_junit_suite(report);
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"impulse\"" +
           counts_attributes(suite) + ">\n" + suite.xml + "</testsuites>\n";
}

} // namespace impulse::harness
