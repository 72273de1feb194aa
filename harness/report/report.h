// The gate's reports: a summary fit for a pull-request comment and an HTML
// page per run, written to `check --report DIR`; and JUnit XML for CI.
#pragma once

#include "scene_check.h"

#include <string>
#include <vector>

namespace impulse::harness {

std::string junit_xml(const std::vector<SceneCheck>& checks);
std::string summary_markdown(const std::vector<SceneCheck>& checks);
// Writes summary.md, index.html and one SVG per failed scene into dir
// (created if missing); throws InputError when it cannot.
void write_report(const std::string& dir, const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
