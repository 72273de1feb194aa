// Reading and writing impulse/trajectory@1 (DESIGN.md, "Trajectory and golden
// format"). Goldens are compared bit for bit, so the writer's layout is fixed
// and the reader is strict: a golden that does not parse cleanly is an input
// error naming the file and JSON path, never a crash.
#include "trajectory.h"

#include "input_error.h"
#include "number_format.h"
#include "strict_json.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace impulse::harness {

namespace {

// ordered_json keeps object keys in document order, which the solver block
// needs so that it is written back the way it was read.
using Json = nlohmann::ordered_json;

constexpr std::uint64_t fnv_offset_basis = 0xcbf29ce484222325ULL;
constexpr std::uint64_t fnv_prime = 0x100000001b3ULL;

const char* const hex_digits = "0123456789abcdef";

// ---------------------------------------------------------------- digest

// Feeds the 8 bytes of the IEEE bit pattern low byte first, so the digest is
// the same on hosts of either byte order.
void fnv1a_add(std::uint64_t& hash, double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) {
        hash ^= (bits >> (8 * byte)) & 0xFFU;
        hash *= fnv_prime;
    }
}

// ---------------------------------------------------------------- writing

// A JSON string literal. Names are limited to [A-Za-z0-9._-] upstream, but
// anything else is still escaped rather than written broken.
std::string quote(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\b':
            out += "\\b";
            break;
        case '\f':
            out += "\\f";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                const auto code = static_cast<unsigned char>(c);
                out += "\\u00";
                out += hex_digits[code >> 4];
                out += hex_digits[code & 0xFU];
            } else {
                out += c; // UTF-8 passes through unchanged
            }
        }
    }
    out += '"';
    return out;
}

// "[a, b, c]" on one line.
std::string number_list(const double* values, std::size_t count) {
    std::string out = "[";
    for (std::size_t i = 0; i < count; ++i) {
        if (i > 0) {
            out += ", ";
        }
        out += format_double(values[i]);
    }
    out += ']';
    return out;
}

std::string solver_object(const std::vector<std::pair<std::string, std::string>>& solver) {
    std::string out = "{";
    for (std::size_t i = 0; i < solver.size(); ++i) {
        if (i > 0) {
            out += ", ";
        }
        out += quote(solver[i].first) + ": " + solver[i].second;
    }
    out += '}';
    return out;
}

std::string string_list(const std::vector<std::string>& strings) {
    std::string out = "[";
    for (std::size_t i = 0; i < strings.size(); ++i) {
        if (i > 0) {
            out += ", ";
        }
        out += quote(strings[i]);
    }
    out += ']';
    return out;
}

std::string event_object(const TrajectoryEvent& event) {
    return "{\"t\": " + format_double(event.t) + ", \"a\": " + quote(event.a) +
           ", \"b\": " + quote(event.b) + ", \"point\": " + number_list(event.point, 2) +
           ", \"normal\": " + number_list(event.normal, 2) +
           ", \"impulse\": " + format_double(event.impulse) +
           ", \"vn_before\": " + format_double(event.vn_before) +
           ", \"vn_after\": " + format_double(event.vn_after) + "}";
}

// `"key": [` + one line per item + `  ]`, or `"key": []` when there are none,
// so that a golden diff shows exactly the frames and events that moved.
std::string multiline_array(const std::string& key, const std::vector<std::string>& lines) {
    if (lines.empty()) {
        return "  " + quote(key) + ": []";
    }
    std::string out = "  " + quote(key) + ": [\n";
    for (std::size_t i = 0; i < lines.size(); ++i) {
        out += "    " + lines[i];
        out += (i + 1 < lines.size()) ? ",\n" : "\n";
    }
    out += "  ]";
    return out;
}

// ---------------------------------------------------------------- reading

// What the reading helpers throw; read_trajectory adds the file name and turns
// it into an InputError, so the helpers need not carry the name around.
struct Invalid {
    std::string path;
    std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw Invalid{path, message};
}

// `got "abc"`, `got true`, `got an array`: what was found instead, short
// enough for one line.
std::string got(const Json& value) {
    if (value.is_object()) {
        return "got an object";
    }
    if (value.is_array()) {
        return "got an array";
    }
    std::string text = value.dump();
    constexpr std::size_t longest = 40;
    if (text.size() > longest) {
        std::size_t cut = longest;
        // never cut a UTF-8 sequence in half
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) {
            --cut;
        }
        text = text.substr(0, cut) + "...";
    }
    return "got " + text;
}

// Every type below is checked before get<>(), so nlohmann's type_error never
// escapes.

void require_object(const Json& value, const std::string& path) {
    if (!value.is_object()) {
        fail(path, "must be an object, " + got(value));
    }
}

void require_array(const Json& value, const std::string& path) {
    if (!value.is_array()) {
        fail(path, "must be an array, " + got(value));
    }
}

const Json& require_key(const Json& object, const std::string& path, const std::string& key) {
    const auto found = object.find(key);
    if (found == object.end()) {
        fail(json_member_path(path, key), "the required key is missing");
    }
    return *found;
}

// Refuses keys outside `allowed`, naming the first one found.
void reject_unknown_keys(const Json& object, const std::string& path,
                         const std::vector<std::string>& allowed) {
    for (const auto& item : object.items()) {
        bool known = false;
        for (const std::string& name : allowed) {
            known = known || item.key() == name;
        }
        if (!known) {
            std::string names;
            for (const std::string& name : allowed) {
                names += (names.empty() ? "" : ", ") + name;
            }
            const std::string closest = closest_known_key(item.key(), allowed);
            fail(json_member_path(path, item.key()),
                 (closest.empty() ? "unknown key" : "unknown key (did you mean " + closest + "?)") +
                     "; the keys allowed here are " + names);
        }
    }
}

std::string read_string(const Json& value, const std::string& path) {
    if (!value.is_string()) {
        fail(path, "must be a string, " + got(value));
    }
    return value.get<std::string>();
}

std::string read_name(const Json& value, const std::string& path) {
    std::string name = read_string(value, path);
    if (name.empty()) {
        fail(path, "must not be empty");
    }
    return name;
}

// A JSON integer as a double, refused if a double cannot hold it exactly:
// the writer only ever writes integers that are exact doubles (to_chars
// writes 2^60 as all 19 of its digits), so an inexact one was typed by hand.
template <typename Integer> double exact_integer(Integer integer, const std::string& path) {
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

// Numbers come back with the bits they were written with: floats through
// nlohmann's correctly rounded parse, integers converted exactly.
double read_number(const Json& value, const std::string& path) {
    if (value.is_number_unsigned()) {
        return exact_integer(value.get<std::uint64_t>(), path);
    }
    if (value.is_number_integer()) {
        return exact_integer(value.get<std::int64_t>(), path);
    }
    if (value.is_number_float()) {
        const double number = value.get<double>();
        if (!std::isfinite(number)) {
            fail(path, "must be a finite number");
        }
        return number;
    }
    fail(path, "must be a number, " + got(value));
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
    for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string path = json_element_path("columns", i);
        std::string name = read_name(value[i], path);
        for (std::size_t earlier = 0; earlier < columns.size(); ++earlier) {
            if (columns[earlier] == name) {
                fail(path, quote(name) + " repeats " + json_element_path("columns", earlier));
            }
        }
        columns.push_back(std::move(name));
    }
    if (columns.empty() || columns.front() != "t") {
        fail("columns", "the first column must be \"t\"");
    }
    return columns;
}

std::vector<std::vector<double>> read_frames(const Json& value, std::size_t column_count) {
    require_array(value, "frames");
    std::vector<std::vector<double>> frames;
    frames.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string path = json_element_path("frames", i);
        const Json& row = value[i];
        require_array(row, path);
        if (row.size() != column_count) {
            fail(path, "has " + std::to_string(row.size()) + " values but there are " +
                           std::to_string(column_count) + " columns");
        }
        std::vector<double> frame(column_count);
        for (std::size_t j = 0; j < column_count; ++j) {
            frame[j] = read_number(row[j], json_element_path(path, j));
        }
        frames.push_back(std::move(frame));
    }
    return frames;
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

std::vector<TrajectoryEvent> read_events(const Json& value) {
    require_array(value, "events");
    std::vector<TrajectoryEvent> events;
    events.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
        events.push_back(read_event(value[i], json_element_path("events", i)));
    }
    return events;
}

Trajectory read_validated(const std::string& text, const std::string& file) {
    const Json top = parse_strict_json<Json>(text, file, MinusZero::negative_zero);
    if (!top.is_object()) {
        fail("", "the top level must be a JSON object, " + got(top));
    }
    // The schema first: a scene file given by mistake should be told so, not
    // told about its unknown keys.
    check_schema(top);
    reject_unknown_keys(top, "",
                        {"schema", "scene", "scene_sha256", "engine", "solver", "digest", "columns",
                         "frames", "events"});

    Trajectory trajectory;
    trajectory.scene = read_name(require_key(top, "", "scene"), "scene");
    trajectory.scene_sha256 =
        read_lower_hex(require_key(top, "", "scene_sha256"), "scene_sha256", 64);
    trajectory.engine = read_name(require_key(top, "", "engine"), "engine");
    trajectory.solver = read_solver(require_key(top, "", "solver"));
    const std::string stored_digest = read_lower_hex(require_key(top, "", "digest"), "digest", 16);
    trajectory.columns = read_columns(require_key(top, "", "columns"));
    trajectory.frames = read_frames(require_key(top, "", "frames"), trajectory.columns.size());
    trajectory.events = read_events(require_key(top, "", "events"));

    const std::uint64_t computed = digest_of(trajectory);
    if (computed != hex_to_u64(stored_digest)) {
        fail("digest", "stored digest " + stored_digest + " does not match the data (" +
                           digest_hex(computed) + "): the file was edited by hand or is corrupt");
    }
    return trajectory;
}

} // namespace

std::uint64_t digest_of(const Trajectory& trajectory) {
    std::uint64_t hash = fnv_offset_basis;
    for (const std::vector<double>& frame : trajectory.frames) {
        for (const double value : frame) {
            fnv1a_add(hash, value);
        }
    }
    for (const TrajectoryEvent& event : trajectory.events) {
        for (const double value :
             {event.t, event.point[0], event.point[1], event.normal[0], event.normal[1],
              event.impulse, event.vn_before, event.vn_after}) {
            fnv1a_add(hash, value);
        }
    }
    return hash;
}

std::string digest_hex(std::uint64_t digest) {
    std::string hex(16, '0');
    for (std::size_t i = 0; i < 16; ++i) {
        hex[15 - i] = hex_digits[(digest >> (4 * i)) & 0xFU];
    }
    return hex;
}

std::string write_trajectory(const Trajectory& trajectory) {
    std::vector<std::string> frame_lines;
    frame_lines.reserve(trajectory.frames.size());
    for (const std::vector<double>& frame : trajectory.frames) {
        // A frame that does not match the columns could never be read back.
        if (frame.size() != trajectory.columns.size()) {
            throw std::logic_error("write_trajectory: a frame has " + std::to_string(frame.size()) +
                                   " values but there are " +
                                   std::to_string(trajectory.columns.size()) + " columns");
        }
        frame_lines.push_back(number_list(frame.data(), frame.size()));
    }
    std::vector<std::string> event_lines;
    event_lines.reserve(trajectory.events.size());
    for (const TrajectoryEvent& event : trajectory.events) {
        event_lines.push_back(event_object(event));
    }

    std::string out = "{\n";
    out += "  \"schema\": " + quote(trajectory_schema) + ",\n";
    out += "  \"scene\": " + quote(trajectory.scene) + ",\n";
    out += "  \"scene_sha256\": " + quote(trajectory.scene_sha256) + ",\n";
    out += "  \"engine\": " + quote(trajectory.engine) + ",\n";
    out += "  \"solver\": " + solver_object(trajectory.solver) + ",\n";
    out += "  \"digest\": " + quote(digest_hex(digest_of(trajectory))) + ",\n";
    out += "  \"columns\": " + string_list(trajectory.columns) + ",\n";
    out += multiline_array("frames", frame_lines) + ",\n";
    out += multiline_array("events", event_lines) + "\n";
    out += "}\n";
    return out;
}

Trajectory read_trajectory(const std::string& text, const std::string& file) {
    try {
        return read_validated(text, file);
    } catch (const Invalid& invalid) {
        throw InputError(file, invalid.path, invalid.message);
    }
}

} // namespace impulse::harness
