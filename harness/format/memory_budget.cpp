#include "memory_budget.h"

#include "input_error.h"
#include "strict_json.h"

#include <cstdio>
#include <cstdlib>

namespace impulse::harness {

std::uint64_t TrajectorySize::memory_bytes() const {
    return numbers * bytes_per_number + arrays * bytes_per_array + objects * bytes_per_object +
           strings * bytes_per_string;
}

namespace {

// A whole number from the environment, or `fallback` when the variable is
// unset or empty; InputError naming the variable when it is anything else.
std::uint64_t limit_from_environment(const char* variable, std::uint64_t fallback,
                                     std::uint64_t largest, const std::string& unit) {
    const char* given = std::getenv(variable);
    if (given == nullptr || *given == '\0') {
        return fallback;
    }
    // Digits only: strtoull would take "-1", "0x10" and " 7" silently.
    std::uint64_t number = 0;
    bool valid = true;
    for (const char* c = given; *c != '\0'; ++c) {
        valid = valid && *c >= '0' && *c <= '9' && number <= largest;
        if (valid) {
            number = number * 10 + static_cast<std::uint64_t>(*c - '0');
        }
    }
    if (!valid || number < 1 || number > largest) {
        throw InputError(variable, "",
                         "must be a whole number of " + unit + " from 1 to " +
                             std::to_string(largest) + ", got '" + given + "'");
    }
    return number;
}

} // namespace

std::uint64_t trajectory_limit_bytes() {
    return limit_from_environment(trajectory_limit_variable, default_trajectory_limit_mib,
                                  largest_trajectory_limit_mib, "MiB") *
           1024 * 1024;
}

std::string trajectory_limit_text() {
    return bytes_text(trajectory_limit_bytes()) + " (set " + trajectory_limit_variable +
           " to a number of MiB to change it)";
}

std::string trajectory_limit_advice() {
    return std::string("set ") + trajectory_limit_variable +
           " to a number of MiB to change the limit";
}

TrajectorySize size_of_text(const std::string& text) {
    TrajectorySize size;
    size.text_bytes = text.size();
    JsonStringScanner strings;
    bool in_number = false;
    for (const char c : text) {
        const bool was_in_string = strings.in_string();
        if (strings.consumes(c)) {
            if (!was_in_string) { // an opening quote: one more string
                ++size.strings;
                in_number = false;
            }
            continue;
        }
        const bool digit = c >= '0' && c <= '9';
        if (!in_number && (digit || c == '-')) {
            ++size.numbers;
        }
        in_number = digit || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
        if (c == '[') {
            ++size.arrays;
        } else if (c == '{') {
            ++size.objects;
        }
    }
    return size;
}

TrajectorySize header_size_bound(const std::vector<std::string>& columns) {
    TrajectorySize size;
    // Keys, schema, scene name, hashes, engine and solver block fit in 2 KiB
    // (a name is at most 64 bytes); each column name is quoted and separated.
    size.text_bytes = 2048;
    for (const std::string& column : columns) {
        size.text_bytes += column.size() + 4;
    }
    size.numbers = 16; // the solver block's
    size.arrays = 8;   // columns, frames, events, solver overrides
    size.objects = 2;  // the document, the solver block
    size.strings = 64 + columns.size();
    return size;
}

TrajectorySize frames_size_bound(std::uint64_t frames, std::uint64_t columns) {
    TrajectorySize size;
    // "    [" + numbers + "],\n" per frame.
    size.text_bytes = frames * (8 + columns * widest_number_text);
    size.numbers = frames * columns;
    size.arrays = frames;
    return size;
}

TrajectorySize event_size_bound(std::size_t names_length) {
    TrajectorySize size;
    // The keys, quotes and brackets of one event line are 104 bytes; 8 numbers.
    size.text_bytes = 128 + names_length + 8 * widest_number_text;
    size.numbers = 8;
    size.arrays = 2;
    size.objects = 1;
    size.strings = 10; // 8 keys, 2 names
    return size;
}

TrajectorySize operator+(const TrajectorySize& a, const TrajectorySize& b) {
    return {a.text_bytes + b.text_bytes, a.numbers + b.numbers, a.arrays + b.arrays,
            a.objects + b.objects, a.strings + b.strings};
}

void require_within_trajectory_limit(const TrajectorySize& size, const std::string& file,
                                     const std::string& path, const std::string& what, bool bound) {
    const std::uint64_t limit = trajectory_limit_bytes();
    const std::string up_to = bound ? "up to " : "";
    if (size.text_bytes > limit) {
        throw InputError(file, path,
                         what + ": " + up_to + bytes_text(size.text_bytes) +
                             " of trajectory text, more than the limit of " +
                             trajectory_limit_text());
    }
    if (size.memory_bytes() > limit) {
        throw InputError(file, path,
                         what + ": " + up_to + bytes_text(size.memory_bytes()) + " in memory (" +
                             std::to_string(size.numbers) + " numbers), more than the limit of " +
                             trajectory_limit_text());
    }
}

std::uint64_t world_pair_count(std::uint64_t dynamic_bodies, std::uint64_t static_bodies) {
    return dynamic_bodies * (dynamic_bodies - (dynamic_bodies > 0 ? 1 : 0)) / 2 +
           dynamic_bodies * static_bodies;
}

void require_world_pairs_within_limit(std::uint64_t dynamic_bodies, std::uint64_t static_bodies,
                                      const std::string& file) {
    const std::uint64_t limit = limit_from_environment(
        world_pair_limit_variable, default_world_pair_limit, std::uint64_t{1} << 40, "pairs");
    const std::uint64_t pairs = world_pair_count(dynamic_bodies, static_bodies);
    if (pairs <= limit) {
        return;
    }
    throw InputError(file, "solver.stepping",
                     "world stepping (the default) keeps and tests every pair of bodies each "
                     "step: " +
                         std::to_string(pairs) + " pairs here (" + bytes_text(pairs * 9) +
                         "), more than the limit of " + std::to_string(limit) + " (set " +
                         world_pair_limit_variable +
                         " to change it); use \"stepping\": \"local\", which keeps no pair "
                         "list, for this many bodies");
}

std::string bytes_text(std::uint64_t bytes) {
    const double mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
    char buffer[32];
    if (mib >= 1024.0) {
        std::snprintf(buffer, sizeof buffer, "%.1f GiB", mib / 1024.0);
    } else if (mib == static_cast<double>(static_cast<std::uint64_t>(mib))) {
        std::snprintf(buffer, sizeof buffer, "%.0f MiB", mib);
    } else if (mib >= 1.0) {
        std::snprintf(buffer, sizeof buffer, "%.1f MiB", mib);
    } else {
        std::snprintf(buffer, sizeof buffer, "%.2g MiB", mib);
    }
    return buffer;
}

} // namespace impulse::harness
