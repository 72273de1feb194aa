// The gate's reports written to `check --report DIR`: summary.md (summary.h),
// index.html and the failed scenes' pictures (html_report.h). JUnit XML for CI
// is junit.h; both are included here for the callers that write either.
#pragma once

#include "junit.h"
#include "scene_check.h"
#include "summary.h"

#include <string>
#include <vector>

namespace impulse::harness {

// Writes summary.md, index.html and one SVG per failed scene into dir
// (created if missing); throws InputError when it cannot.
void write_report(const std::string& dir, const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
