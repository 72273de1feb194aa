// The gate's reports written to `check --report DIR`: summary.md (summary.h),
// index.html and the failed scenes' pictures (html_report.h). JUnit XML for CI
// is junit.h; both are included here for the callers that write either.
#pragma once

#include "junit.h"
#include "scene_check.h"
#include "summary.h"

#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

// The files every report has, whatever the checks: known before any scene
// runs, so a verb refuses a bad one (a folder, a link, its own --json) first.
std::vector<std::string> report_fixed_files(const std::string& dir);

// Every file of the report on these checks, path and content, not written:
// the caller checks each path against its other outputs before writing any.
std::vector<std::pair<std::string, std::string>>
report_files(const std::string& dir, const std::vector<SceneCheck>& checks);

// Writes report_files into dir (created if missing), each path checked before
// any is written; throws InputError when it cannot.
void write_report(const std::string& dir,
                  const std::vector<std::pair<std::string, std::string>>& files);
void write_report(const std::string& dir, const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
