// The JSON the report page embeds for its script: short numbers (the page
// draws them; the exact values are in the trajectories) and strings that can
// sit inside a <script> element without ending it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness {

// `digits` significant digits; "null" for what JSON cannot hold (NaN, inf).
std::string json_number(double value, int digits);
// A JSON string with '<', '>' and '&' as \u escapes, so "</script>" in a
// body's name cannot close the element that holds the data.
std::string json_string(const std::string& text);
// "[v0,v1,...]" with json_number.
std::string json_numbers(const std::vector<double>& values, int digits);

// Which frames of `count` a page shows: every stride-th, the last, and
// `keep` (a frame that must be seen, npos for none), in order, at most
// about `budget`. All of them when count <= budget.
std::vector<std::size_t> sampled_frames(std::size_t count, std::size_t budget, std::size_t keep);

} // namespace impulse::harness
