// JSON text whose doubles read back to the identical bits: nlohmann builds
// the document, this writes it with format_double (number_format.h), the
// spelling goldens use, so a number in `impulse check --json` is the exact
// value the gate compared and reads the same in any language.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace impulse::harness {

// Indented by two spaces, keys in insertion order, a newline at the end.
// A double that is not finite (JSON cannot hold it) is null; invalid UTF-8
// in a string is replaced, never a crash.
std::string exact_json_text(const nlohmann::ordered_json& document);

} // namespace impulse::harness
