// Doubles as JSON text that reads back to the identical bits (docs/design.md,
// "Doubles are written in shortest round-trip form").
#pragma once

#include <string>

namespace impulse::harness {

// The shortest text that reads back to exactly `value`: std::to_chars' output
// ("0", "3", "0.1", "1e+22", "5e-324"), except that negative zero is written
// "-0.0" because JSON readers take "-0" for the integer 0 and lose the sign.
// Throws std::logic_error for NaN and infinities: JSON cannot hold them, so a
// caller that gets here has let a non-finite value through.
std::string format_double(double value);

// A number for a table a person reads: `digits` significant digits
// (std::to_chars' general format, locale-free: "0.4515", "1.1e-16", "0"),
// "NaN", "inf" and "-inf" for what is not finite. Never parsed back; files
// carry format_double's exact text.
std::string significant_text(double value, int digits);

// Reads one JSON number (the whole of `text`, nothing around it) into
// `value`. Returns false, leaving `value` alone, for anything else and for
// numbers a double cannot hold (overflow, underflow to zero).
bool parse_double(const std::string& text, double& value);

} // namespace impulse::harness
