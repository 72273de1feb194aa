// JUnit XML (junit.h), text built by hand from the checks alone, so the same
// checks always give the same bytes.
#include "junit.h"

#include "check_outcome.h"
#include "markup.h"

namespace impulse::harness {

namespace {

using Status = SceneCheck::Status;

std::string junit_body(const SceneCheck& check) {
    std::string body = check.details.empty() ? check.message : check.details;
    std::string files;
    if (!check.scene_file.empty()) {
        files += "scene: " + check.scene_file + "\n";
    }
    if (!check.golden_file.empty()) {
        files += "golden: " + check.golden_file + "\n";
    }
    if (!files.empty()) {
        if (!body.empty() && body.back() != '\n') {
            body += "\n";
        }
        body += (body.empty() ? "" : "\n") + files;
    }
    return body;
}

std::string totals_attributes(std::size_t tests, std::size_t failures, std::size_t errors) {
    return " tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) +
           "\" errors=\"" + std::to_string(errors) + "\"";
}

std::string xml_head(const std::string& totals, const CheckCounts& c) {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"impulse\"" + totals +
           " time=\"" + seconds_text(c.seconds) + "\">\n";
}

// The gate's <testsuite> element, indented for <testsuites>.
std::string gate_suite(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    const std::string totals = totals_attributes(checks.size(), c.failed, c.errors);
    std::string out;
    out += "  <testsuite name=\"impulse.gate\"" + totals + " skipped=\"" +
           std::to_string(c.skipped) + "\" time=\"" + seconds_text(c.seconds) + "\">\n";
    for (const SceneCheck& check : checks) {
        out += "    <testcase classname=\"impulse.gate\" name=\"" +
               xml_escape(display_name(check), true) + "\" time=\"" + seconds_text(check.seconds) +
               "\"";
        if (check.status == Status::passed) {
            out += "/>\n";
            continue;
        }
        if (check.status == Status::skipped) {
            // An engine's refusal of the scene's settings: neither a pass nor a failure.
            out += ">\n      <skipped message=\"" + xml_escape(check.message, true) + "\"/>\n";
            out += "    </testcase>\n";
            continue;
        }
        const bool failed = check.status == Status::failed;
        const char* element = failed ? "failure" : "error";
        std::string message = check.message.empty() ? outcome_line(check) : check.message;
        if (message.empty()) {
            message = failed ? "does not match its golden" : "could not be checked";
        }
        out += ">\n      <" + std::string(element) + " message=\"" + xml_escape(message, true) +
               "\" type=\"" + (failed ? failure_kind(check) : error_kind(check)) + "\">" +
               xml_escape(junit_body(check)) + "</" + element + ">\n";
        out += "    </testcase>\n";
    }
    return out + "  </testsuite>\n";
}

} // namespace

std::string junit_xml(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    return xml_head(totals_attributes(checks.size(), c.failed, c.errors), c) + gate_suite(checks) +
           "</testsuites>\n";
}

std::string junit_xml(const std::vector<SceneCheck>& checks, const ComparisonReport& comparison) {
    const CheckCounts c = count_checks(checks);
    const ComparisonSuite suite = comparison_junit_suite(comparison);
    const std::string totals =
        totals_attributes(checks.size() + suite.tests, c.failed + suite.failures, c.errors);
    return xml_head(totals, c) + gate_suite(checks) + suite.xml + "</testsuites>\n";
}

} // namespace impulse::harness
