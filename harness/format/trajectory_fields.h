// The checks of each piece of an impulse/trajectory@1 document, shared by the
// streaming reader (trajectory_stream.cpp) and the validation after it
// (trajectory_reader.cpp). Internal to the trajectory reader.
#pragma once

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

// What the helpers throw; read_trajectory adds the file name and turns it
// into an InputError, so the helpers need not carry the name around.
struct Invalid {
    std::string path;
    std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& message);

// `got "abc"`, `got true`, `got an array`: what was found instead, short
// enough for one line.
std::string got(const Json& value);

void require_object(const Json& value, const std::string& path);
void require_array(const Json& value, const std::string& path);
const Json& require_key(const Json& object, const std::string& path, const std::string& key);
// Refuses keys outside `allowed`, naming the first one found.
void reject_unknown_keys(const Json& object, const std::string& path,
                         const std::vector<std::string>& allowed);

std::string read_name(const Json& value, const std::string& path);
// A JSON integer as a double, refused if a double cannot hold it exactly.
double exact_integer(std::int64_t integer, const std::string& path);
double exact_integer(std::uint64_t integer, const std::string& path);
// Numbers come back with the bits they were written with.
double read_number(const Json& value, const std::string& path);
std::string read_lower_hex(const Json& value, const std::string& path, std::size_t digits);
std::uint64_t hex_to_u64(const std::string& hex);

void check_schema(const Json& top);
std::vector<std::pair<std::string, std::string>> read_solver(const Json& solver);
std::vector<std::string> read_columns(const Json& value);
TrajectoryEvent read_event(const Json& value, const std::string& path);

} // namespace impulse::harness::trajectory_fields
