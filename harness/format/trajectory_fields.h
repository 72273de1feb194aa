// The checks of each piece of an impulse/trajectory@1 document, shared by the
// streaming reader (trajectory_stream.cpp) and the validation after it
// (trajectory_reader.cpp). Internal to the trajectory reader.
#pragma once

#include "json_fields.h"
#include "trajectory.h"

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::trajectory_fields {

// ordered_json keeps object keys in document order, which the solver block
// needs so that it is written back the way it was read.
using Json = nlohmann::ordered_json;

// The typed reading every format shares (json_fields.h); read_trajectory
// turns a FieldError into an InputError naming the file.
using json_fields::fail;
using json_fields::FieldError;
using json_fields::got;
using json_fields::read_string;
using json_fields::reject_unknown_keys;
using json_fields::require_array;
using json_fields::require_key;
using json_fields::require_object;

// Throws a FieldError at `path` when `text` holds a control character
// (below 0x20, or 0x7f).
void require_printable(const std::string& text, const std::string& path);

std::string read_name(const Json& value, const std::string& path);
// A JSON integer as a double, refused if a double cannot hold it exactly.
double exact_integer(std::int64_t integer, const std::string& path);
double exact_integer(std::uint64_t integer, const std::string& path);
// Numbers come back with the bits they were written with; an integer a
// double cannot hold exactly is refused.
double read_number(const Json& value, const std::string& path);
std::string read_lower_hex(const Json& value, const std::string& path, std::size_t digits);
std::uint64_t hex_to_u64(const std::string& hex);

void check_schema(const Json& top);
std::vector<std::pair<std::string, std::string>> read_solver(const Json& solver);
std::vector<std::string> read_columns(const Json& value);
TrajectoryEvent read_event(const Json& value, const std::string& path);

} // namespace impulse::harness::trajectory_fields
