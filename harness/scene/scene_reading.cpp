// The typed reads of scene_reading.h: json_fields on a Node, plus the
// ranges and shapes of values only scenes have.
#include "scene_reading.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

namespace impulse::harness::scene_reading {

namespace {

constexpr std::size_t max_name_length = 64;

bool is_ascii_letter_or_digit(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

// Scene and body names become file names (goldens/NAME.json) and column
// prefixes (NAME.x), so they are kept to characters that cannot leave the
// goldens folder or break a column name: no slash, no leading dot.
bool is_valid_name(const std::string& name) {
    if (name.empty() || name.size() > max_name_length || !is_ascii_letter_or_digit(name[0])) {
        return false;
    }
    return std::all_of(name.begin(), name.end(), [](char c) {
        return is_ascii_letter_or_digit(c) || c == '.' || c == '_' || c == '-';
    });
}

} // namespace

// Shortest text that reads back to the same double (std::to_chars), so a
// value quoted in a message is exactly the value the file holds.
std::string number_text(double value) {
    char buffer[32];
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string shown(const Node& node) {
    return json_fields::shown(node.json());
}

void require_object(const Node& node) {
    json_fields::require_object(node.json(), node.path());
}

void require_array(const Node& node) {
    json_fields::require_array(node.json(), node.path());
}

std::optional<Node> optional_member(const Node& object, const std::string& key) {
    if (!object.has(key)) {
        return std::nullopt;
    }
    return object.member(key);
}

Node required_member(const Node& object, const std::string& key) {
    return Node(json_fields::require_key(object.json(), object.path(), key),
                json_member_path(object.path(), key));
}

// Typos must not pass silently (docs/design.md): every key must be one the format knows.
void reject_unknown_keys(const Node& object, const std::vector<std::string>& known) {
    json_fields::reject_unknown_keys(object.json(), object.path(), known);
}

std::string read_string(const Node& node) {
    return json_fields::read_string(node.json(), node.path());
}

bool read_bool(const Node& node) {
    return json_fields::read_bool(node.json(), node.path());
}

double read_number(const Node& node) {
    return json_fields::read_number(node.json(), node.path());
}

double read_positive(const Node& node) {
    const double value = read_number(node);
    if (!(value > 0.0)) {
        node.fail("must be > 0, got " + number_text(value));
    }
    return value;
}

// A count: a JSON number with no fractional part (3, or 3.0 written as a
// float), from `low` to `high`.
long long read_whole(const Node& node, long long low, long long high) {
    const double value = read_number(node);
    if (value != std::floor(value) || value < static_cast<double>(low) ||
        value > static_cast<double>(high)) {
        node.fail("must be a whole number from " + std::to_string(low) + " to " +
                  std::to_string(high) + ", got " + number_text(value));
    }
    return static_cast<long long>(value);
}

double read_non_negative(const Node& node) {
    const double value = read_number(node);
    if (!(value >= 0.0)) {
        node.fail("must be >= 0, got " + number_text(value));
    }
    return value;
}

void read_atol_rtol(const Node& node, const std::string& what, double& atol, double& rtol) {
    if (!node.has("atol") && !node.has("rtol")) {
        node.fail("must give atol or rtol (or both); " + what + " has no default tolerance");
    }
    if (const std::optional<Node> given = optional_member(node, "atol")) {
        atol = read_non_negative(*given);
    }
    if (const std::optional<Node> given = optional_member(node, "rtol")) {
        rtol = read_non_negative(*given);
    }
}

// [x, y]
Vec2 read_vec2(const Node& node) {
    if (!node.json().is_array() || node.json().size() != 2) {
        node.fail("must be an array of two numbers [x, y], got " + shown(node));
    }
    return {read_number(node.element(0)), read_number(node.element(1))};
}

std::string read_string_or(const Node& object, const std::string& key, std::string fallback) {
    return read_or(object, key, std::move(fallback), read_string);
}
bool read_bool_or(const Node& object, const std::string& key, bool fallback) {
    return read_or(object, key, fallback, read_bool);
}
double read_number_or(const Node& object, const std::string& key, double fallback) {
    return read_or(object, key, fallback, read_number);
}
double read_positive_or(const Node& object, const std::string& key, double fallback) {
    return read_or(object, key, fallback, read_positive);
}
Vec2 read_vec2_or(const Node& object, const std::string& key, Vec2 fallback) {
    return read_or(object, key, fallback, read_vec2);
}

std::string read_name(const Node& node) {
    const std::string name = read_string(node);
    if (!is_valid_name(name)) {
        node.fail("must be 1 to 64 letters, digits, '.', '_' or '-', starting with a letter or "
                  "digit, got " +
                  shown(node));
    }
    return name;
}

} // namespace impulse::harness::scene_reading
