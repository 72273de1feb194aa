// A scene's name as its files carry it (NAME.json, goldens/NAME.json), and
// the rule that two names differing only in case are one file on macOS and
// Windows: shared by the scene lists and by check and bless.
#pragma once

#include "text.h" // lower_case, for the rule below

#include <string>

namespace impulse::harness {

// "drop" for ".../drop.json".
std::string scene_stem(const std::string& path);
// The end of the sentence refusing two names that differ only in case.
extern const char* const case_clash_reason;

} // namespace impulse::harness
