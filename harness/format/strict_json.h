// JSON as the harness reads it from scenes, trajectories and goldens: a file
// that is wrong says how, in one sentence, and never crashes the reader.
#pragma once

#include "input_error.h"

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace impulse::harness {

// Deeper files are refused before nlohmann's recursive parser sees them.
inline constexpr int max_json_nesting = 64;

// Parses `text`, throwing InputError naming `file` for: a merge-conflict
// marker (with its line), nesting deeper than max_json_nesting, a syntax error
// or a number too large for a double (nlohmann's position and reason,
// shortened, and the JSON path when it stopped where a value belongs: 1e999,
// NaN, Infinity), and a key repeated in one object (with its JSON path), which
// nlohmann would otherwise resolve silently by keeping one value. Json is
// nlohmann::json or nlohmann::ordered_json.
template <class Json> Json parse_strict_json(const std::string& text, const std::string& file);

// The ordinals (0-based, counting every number token in document order) of
// the integer tokens spelled exactly -0. JSON allows them and nlohmann reads
// them as the integer 0, losing the sign; trajectories promise that -0.0 and
// +0.0 are told apart in every spelling, so their reader turns these into the
// double -0.0. Scenes keep the plain reading, so no scene's fingerprint moves.
std::vector<std::size_t> minus_zero_integers(const std::string& text);

// The checks parse_strict_json makes before parsing (merge-conflict markers,
// nesting), for readers that stream the text through nlohmann::sax_parse.
void check_json_text(const std::string& text, const std::string& file);
// The InputError parse_strict_json throws for nlohmann's parse_error or
// out_of_range; `path_of_next_value` is where the parser stood.
InputError json_syntax_error(const nlohmann::json::exception& error, const std::string& file,
                             const std::string& path_of_next_value);

// Reads JSON text a character at a time and says which characters belong to a
// string literal (its quotes included), so scanners of the raw text (nesting
// depth, number tokens, size counts) never mistake a string's contents for
// structure.
class JsonStringScanner {
  public:
    // True when `c` is part of a string literal, quotes included.
    bool consumes(char c) {
        if (in_string_) {
            if (escaped_) {
                escaped_ = false;
            } else if (c == '\\') {
                escaped_ = true;
            } else if (c == '"') {
                in_string_ = false;
            }
            return true;
        }
        in_string_ = c == '"';
        return in_string_;
    }
    bool in_string() const { return in_string_; }

  private:
    bool in_string_ = false;
    bool escaped_ = false;
};

// JSON paths as messages print them: `parent.key`, or `parent["odd key"]` for
// keys that are not plain identifiers, and `parent[3]`.
std::string json_member_path(const std::string& parent, const std::string& key);
std::string json_element_path(const std::string& parent, std::size_t index);

// For "unknown key (did you mean gravity?)": the known key closest to `key` by
// edit distance when it is a plausible typo (at most two edits, and fewer than
// half the key's length, so "x" suggests nothing), else "".
std::string closest_known_key(const std::string& key, const std::vector<std::string>& known);

} // namespace impulse::harness
