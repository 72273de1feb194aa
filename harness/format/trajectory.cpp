// Writing impulse/trajectory@1 (docs/design.md, "Trajectory and golden format"),
// and its digest. Goldens are compared bit for bit, so the writer's layout is
// fixed. Reading is in trajectory_reader.cpp.
#include "trajectory.h"

#include "memory_budget.h"
#include "number_format.h"

#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace impulse::harness {

namespace {

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
// so that a golden diff shows exactly the frames and events that moved. Each
// line is appended to `out` as it is made: no second copy of the text.
template <class Item, class Line>
void append_multiline_array(std::string& out, const std::string& key,
                            const std::vector<Item>& items, const Line& line) {
    if (items.empty()) {
        out += "  " + quote(key) + ": []";
        return;
    }
    out += "  " + quote(key) + ": [\n";
    for (std::size_t i = 0; i < items.size(); ++i) {
        out += "    ";
        out += line(items[i]);
        out += (i + 1 < items.size()) ? ",\n" : "\n";
    }
    out += "  ]";
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
    for (const std::vector<double>& frame : trajectory.frames) {
        // A frame that does not match the columns could never be read back.
        if (frame.size() != trajectory.columns.size()) {
            throw std::logic_error("write_trajectory: a frame has " + std::to_string(frame.size()) +
                                   " values but there are " +
                                   std::to_string(trajectory.columns.size()) + " columns");
        }
    }
    std::string out;
    // The most the text can take, reserved once, so that it is never copied
    // while growing (docs/memory.md).
    TrajectorySize bound = header_size_bound(trajectory.columns) +
                           frames_size_bound(trajectory.frames.size(), trajectory.columns.size());
    for (const TrajectoryEvent& event : trajectory.events) {
        bound = bound + event_size_bound(event.a.size() + event.b.size());
    }
    out.reserve(static_cast<std::size_t>(bound.text_bytes));
    out += "{\n";
    out += "  \"schema\": " + quote(trajectory_schema) + ",\n";
    out += "  \"scene\": " + quote(trajectory.scene) + ",\n";
    out += "  \"scene_sha256\": " + quote(trajectory.scene_sha256) + ",\n";
    out += "  \"engine\": " + quote(trajectory.engine) + ",\n";
    out += "  \"solver\": " + solver_object(trajectory.solver) + ",\n";
    out += "  \"digest\": " + quote(digest_hex(digest_of(trajectory))) + ",\n";
    out += "  \"columns\": " + string_list(trajectory.columns) + ",\n";
    append_multiline_array(out, "frames", trajectory.frames, [](const std::vector<double>& frame) {
        return number_list(frame.data(), frame.size());
    });
    out += ",\n";
    append_multiline_array(out, "events", trajectory.events, event_object);
    if (trajectory.partial) {
        // Only a stopped run has the key, so every complete trajectory keeps
        // its bytes.
        out += ",\n  \"partial\": {\"reason\": " + quote(trajectory.partial->reason) +
               ", \"t\": " + format_double(trajectory.partial->t) + "}";
    }
    out += "\n";
    out += "}\n";
    return out;
}

} // namespace impulse::harness
