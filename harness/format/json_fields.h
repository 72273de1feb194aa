// Typed reading of a parsed JSON document, shared by the scene loader and the
// trajectory reader: each check names the JSON path of what is wrong, and each
// mistake is worded the same way in every file the harness reads.
//
// The helpers throw FieldError (path and message, no file name): the reader at
// the top of each format catches it and turns it into an InputError naming the
// file, so the helpers need not carry the file around. Every type is checked
// before get<>(), so nlohmann's type_error never escapes.
//
// Json is nlohmann::json (scenes: keys sorted, so the fingerprint is canonical)
// or nlohmann::ordered_json (trajectories: keys in document order, so the
// solver block is written back the way it was read); both are instantiated.
#pragma once

#include <string>
#include <vector>

namespace impulse::harness::json_fields {

struct FieldError {
    std::string path;
    std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& message);

// `"abc"`, `true`, `1.5`, `an array`: what a value is, short enough for one
// line (a long string is cut, never inside a UTF-8 sequence).
template <class Json> std::string shown(const Json& value);
// "got " + shown(value): what was found instead, for "must be X, got Y".
template <class Json> std::string got(const Json& value);

template <class Json> void require_object(const Json& value, const std::string& path);
template <class Json> void require_array(const Json& value, const std::string& path);
// The value at `key`; "is required but missing" at PATH.KEY when there is none.
template <class Json>
const Json& require_key(const Json& object, const std::string& path, const std::string& key);
// Typos must not pass silently: refuses the first key (in the object's own
// order) outside `allowed`, with a did-you-mean when it is a plausible typo.
template <class Json>
void reject_unknown_keys(const Json& object, const std::string& path,
                         const std::vector<std::string>& allowed);

template <class Json> std::string read_string(const Json& value, const std::string& path);
template <class Json> bool read_bool(const Json& value, const std::string& path);
// Any JSON number, as the nearest double; refused when not finite.
template <class Json> double read_number(const Json& value, const std::string& path);

// "a, b, c": the names a message lists.
std::string list_of(const std::vector<std::string>& names);

} // namespace impulse::harness::json_fields
