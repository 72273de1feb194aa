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

} // namespace

std::string junit_xml(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    const std::string totals = " tests=\"" + std::to_string(checks.size()) + "\" failures=\"" +
                               std::to_string(c.failed) + "\" errors=\"" +
                               std::to_string(c.errors) + "\"";
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<testsuites name=\"impulse\"" + totals + " time=\"" + seconds_text(c.seconds) + "\">\n";
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
               "\" type=\"" + (failed ? failure_kind(check) : std::string("input error")) + "\">" +
               xml_escape(junit_body(check)) + "</" + element + ">\n";
        out += "    </testcase>\n";
    }
    out += "  </testsuite>\n</testsuites>\n";
    return out;
}

} // namespace impulse::harness
