// The pieces of an impulse/trajectory@1 document, checked one by one: each
// names its JSON path when it is wrong (see trajectory_fields.h).
#include "trajectory_fields.h"

#include "number_format.h"
#include "strict_json.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <type_traits>

namespace impulse::harness::trajectory_fields {

void require_printable(const std::string& text, const std::string& path) {
    // Names and reasons are printed in tables and sentences: a newline or an
    // escape sequence in one would forge lines or colours on the terminal (an
    // outside review's golden printed "FAKE LINE" in red through check).
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto byte = static_cast<unsigned char>(text[i]);
        if (byte < 0x20 || byte == 0x7f) {
            char code[8];
            std::snprintf(code, sizeof code, "0x%02X", byte);
            fail(path, std::string("holds the control character ") + code + " at byte " +
                           std::to_string(i) + "; it is printed, so it must be printable text");
        }
    }
}

std::string read_name(const Json& value, const std::string& path) {
    std::string name = read_string(value, path);
    if (name.empty()) {
        fail(path, "must not be empty");
    }
    require_printable(name, path);
    return name;
}

// A JSON integer as a double, refused if a double cannot hold it exactly:
// the writer only ever writes integers that are exact doubles (to_chars
// writes 2^60 as all 19 of its digits), so an inexact one was typed by hand.
namespace {

template <typename Integer> double exact_integer_of(Integer integer, const std::string& path) {
    const double as_double = static_cast<double>(integer);
    // 2^63 and 2^64 are exact doubles one past the largest int64 and uint64;
    // checking them first keeps the cast back from overflowing.
    const double limit =
        std::is_signed<Integer>::value ? 9223372036854775808.0 : 18446744073709551616.0;
    if (as_double >= limit || static_cast<Integer>(as_double) != integer) {
        fail(path, "the integer " + std::to_string(integer) +
                       " cannot be held exactly by a double (the nearest is " +
                       format_double(as_double) + ")");
    }
    return as_double;
}

} // namespace

double exact_integer(std::int64_t integer, const std::string& path) {
    return exact_integer_of(integer, path);
}

double exact_integer(std::uint64_t integer, const std::string& path) {
    return exact_integer_of(integer, path);
}

// Numbers come back with the bits they were written with: floats through
// nlohmann's correctly rounded parse, integers converted exactly.
double read_number(const Json& value, const std::string& path) {
    if (value.is_number_unsigned()) {
        return exact_integer(value.get<std::uint64_t>(), path);
    }
    if (value.is_number_integer()) {
        return exact_integer(value.get<std::int64_t>(), path);
    }
    return json_fields::read_number(value, path);
}

// Exactly `count` numbers, e.g. a contact point.
void read_fixed_numbers(const Json& value, const std::string& path, double* out,
                        std::size_t count) {
    require_array(value, path);
    if (value.size() != count) {
        fail(path, "must hold exactly " + std::to_string(count) + " numbers, got " +
                       std::to_string(value.size()));
    }
    for (std::size_t i = 0; i < count; ++i) {
        out[i] = read_number(value[i], json_element_path(path, i));
    }
}

std::string read_lower_hex(const Json& value, const std::string& path, std::size_t digits) {
    const std::string text = read_string(value, path);
    bool hex = text.size() == digits;
    for (const char c : text) {
        hex = hex && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
    }
    if (!hex) {
        fail(path, "must be " + std::to_string(digits) + " lowercase hex digits, " + got(value));
    }
    return text;
}

std::string quote(const std::string& text) {
    // The text came through nlohmann's lexer, which refuses broken UTF-8, so
    // dump() cannot throw; it escapes as the writer does.
    return Json(text).dump();
}

std::uint64_t hex_to_u64(const std::string& hex) {
    std::uint64_t number = 0;
    for (const char c : hex) {
        const int digit = (c >= 'a') ? c - 'a' + 10 : c - '0';
        number = (number << 4) | static_cast<std::uint64_t>(digit);
    }
    return number;
}

void check_schema(const Json& top) {
    const std::string schema = read_string(require_key(top, "", "schema"), "schema");
    if (schema == trajectory_schema) {
        return;
    }
    const std::string family = "impulse/trajectory@";
    if (schema.rfind(family, 0) == 0) {
        fail("schema", "version " + schema.substr(family.size()) +
                           " of the trajectory format is not supported; this build reads " +
                           trajectory_schema + " only");
    }
    fail("schema", "must be \"" + std::string(trajectory_schema) + "\", got " + quote(schema) +
                       ": this is not a trajectory file");
}

// A solver value as JSON text. Floating-point numbers go through
// format_double, as the simulator wrote them: nlohmann's dump() would turn
// "1e-04" into "0.0001", and a golden read and written again would change
// bytes. Everything else is nlohmann's compact text.
std::string solver_value_text(const Json& value) {
    if (value.is_number_float() && std::isfinite(value.get<double>())) {
        return format_double(value.get<double>());
    }
    return value.dump();
}

// Each key with its value's text, in document order.
std::vector<std::pair<std::string, std::string>> read_solver(const Json& solver) {
    require_object(solver, "solver");
    std::vector<std::pair<std::string, std::string>> pairs;
    for (const auto& item : solver.items()) {
        pairs.emplace_back(item.key(), solver_value_text(item.value()));
    }
    return pairs;
}

std::vector<std::string> read_columns(const Json& value) {
    require_array(value, "columns");
    std::vector<std::string> columns;
    // A map, not a scan of the earlier names: a 100,000-body run has 600,001 columns.
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string path = json_element_path("columns", i);
        std::string name = read_name(value[i], path);
        const auto [earlier, added] = seen.emplace(name, i);
        if (!added) {
            fail(path, quote(name) + " repeats " + json_element_path("columns", earlier->second));
        }
        columns.push_back(std::move(name));
    }
    if (columns.empty() || columns.front() != "t") {
        fail("columns", "the first column must be \"t\"");
    }
    return columns;
}

TrajectoryEvent read_event(const Json& value, const std::string& path) {
    require_object(value, path);
    reject_unknown_keys(value, path,
                        {"t", "a", "b", "point", "normal", "impulse", "vn_before", "vn_after"});
    const auto field = [&](const char* key) -> const Json& {
        return require_key(value, path, key);
    };
    TrajectoryEvent event;
    event.t = read_number(field("t"), json_member_path(path, "t"));
    event.a = read_name(field("a"), json_member_path(path, "a"));
    event.b = read_name(field("b"), json_member_path(path, "b"));
    read_fixed_numbers(field("point"), json_member_path(path, "point"), event.point, 2);
    read_fixed_numbers(field("normal"), json_member_path(path, "normal"), event.normal, 2);
    event.impulse = read_number(field("impulse"), json_member_path(path, "impulse"));
    event.vn_before = read_number(field("vn_before"), json_member_path(path, "vn_before"));
    event.vn_after = read_number(field("vn_after"), json_member_path(path, "vn_after"));
    return event;
}

} // namespace impulse::harness::trajectory_fields
