// Small string helpers for the sentences and tables the harness prints, each
// defined once here instead of again in every file that needs one.
#pragma once

#include <cstddef>
#include <string>

namespace impulse::harness {

// 'name': how a sentence names a body, a scene or a key.
std::string single_quoted(const std::string& name);
// "text": a string value as it is written in JSON (the solver settings, the
// engine name); no escaping, so only for text known to need none.
std::string double_quoted(const std::string& text);
// "1 scene", "3 scenes".
// ASCII lower case: names and folders told apart only by case are one file
// on macOS and Windows.
std::string lower_case(std::string text);

std::string plural(std::size_t n, const char* one, const char* many);
// Text padded with spaces to width, on the right (default) or on the left
// (right = true, for numbers); longer text is left as it is.
std::string padded(std::string text, std::size_t width, bool right = false);
// Fixed-point with `digits` decimals, locale-free (tables, SVG coordinates).
std::string fixed_text(double value, int digits);
// A number for a sentence: format_double's shortest round trip, and also
// what format_double refuses ("NaN", "inf", "-inf").
std::string sentence_number(double value);

} // namespace impulse::harness
