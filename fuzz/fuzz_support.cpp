#include "fuzz_support.h"

#include "input_error.h"
#include "memory_budget.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace impulse::fuzz {

using harness::InputError;
using harness::Trajectory;
using harness::TrajectoryEvent;

std::string text_of(const std::uint8_t* data, std::size_t size) {
    return size == 0 ? std::string() : std::string(reinterpret_cast<const char*>(data), size);
}

void finding(const std::string& what) {
    std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

namespace {

// The digests in read_trajectory's message "stored digest X does not match
// the data (Y): ...", or false when the message is about something else.
bool digest_mismatch(const std::string& message, std::string& stored, std::string& computed) {
    const std::string before = "stored digest ";
    const std::string middle = " does not match the data (";
    const std::size_t at = message.find(before);
    if (at == std::string::npos) {
        return false;
    }
    const std::size_t stored_at = at + before.size();
    const std::size_t computed_at = stored_at + 16 + middle.size();
    if (message.size() < computed_at + 16 ||
        message.compare(stored_at + 16, middle.size(), middle) != 0) {
        return false;
    }
    stored = message.substr(stored_at, 16);
    computed = message.substr(computed_at, 16);
    return true;
}

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_event(const TrajectoryEvent& a, const TrajectoryEvent& b) {
    return same_bits(a.t, b.t) && a.a == b.a && a.b == b.b && same_bits(a.point[0], b.point[0]) &&
           same_bits(a.point[1], b.point[1]) && same_bits(a.normal[0], b.normal[0]) &&
           same_bits(a.normal[1], b.normal[1]) && same_bits(a.impulse, b.impulse) &&
           same_bits(a.vn_before, b.vn_before) && same_bits(a.vn_after, b.vn_after);
}

} // namespace

std::optional<Trajectory> read_trajectory_fixing_digest(const std::string& text) {
    try {
        return harness::read_trajectory(text, "fuzz.json");
    } catch (const InputError& error) {
        std::string stored;
        std::string computed;
        if (!digest_mismatch(error.what(), stored, computed)) {
            return std::nullopt;
        }
        const std::size_t at = text.find("\"" + stored + "\"");
        if (at == std::string::npos) {
            return std::nullopt; // written with escapes: leave it
        }
        std::string fixed = text;
        fixed.replace(at + 1, 16, computed);
        try {
            return harness::read_trajectory(fixed, "fuzz.json");
        } catch (const InputError&) {
            return std::nullopt; // the same digest text also stood somewhere earlier
        }
    }
}

bool same_trajectory(const Trajectory& a, const Trajectory& b) {
    if (a.scene != b.scene || a.scene_sha256 != b.scene_sha256 || a.engine != b.engine ||
        a.solver != b.solver || a.columns != b.columns || a.frames.size() != b.frames.size() ||
        a.events.size() != b.events.size()) {
        return false;
    }
    for (std::size_t k = 0; k < a.frames.size(); ++k) {
        if (a.frames[k].size() != b.frames[k].size()) {
            return false;
        }
        for (std::size_t j = 0; j < a.frames[k].size(); ++j) {
            if (!same_bits(a.frames[k][j], b.frames[k][j])) {
                return false;
            }
        }
    }
    for (std::size_t k = 0; k < a.events.size(); ++k) {
        if (!same_event(a.events[k], b.events[k])) {
            return false;
        }
    }
    return true;
}

void check_round_trip(const Trajectory& trajectory) {
    const std::string written = harness::write_trajectory(trajectory);
    Trajectory again;
    try {
        again = harness::read_trajectory(written, "fuzz.json");
    } catch (const InputError& error) {
        finding(std::string("a trajectory written by write_trajectory does not read back: ") +
                error.what());
    }
    if (!same_trajectory(trajectory, again)) {
        finding("a trajectory written and read back is not the same trajectory");
    }
    if (harness::write_trajectory(again) != written) {
        finding("a trajectory written, read back and written again gives other bytes");
    }
}

namespace {

// The trajectory with its frames repeated k times (the digest is the writer's).
Trajectory repeated(const Trajectory& trajectory, std::size_t k) {
    Trajectory scaled = trajectory;
    scaled.frames.clear();
    scaled.frames.reserve(trajectory.frames.size() * k);
    for (std::size_t i = 0; i < k; ++i) {
        scaled.frames.insert(scaled.frames.end(), trajectory.frames.begin(),
                             trajectory.frames.end());
    }
    return scaled;
}

// A heap block as glibc's malloc takes it: the size rounded up to 16, plus 16.
std::uint64_t block(std::size_t bytes) {
    return bytes == 0 ? 0 : (bytes + 15) / 16 * 16 + 16;
}

// The heap a string holds beyond its own 32 bytes (short ones hold none).
std::uint64_t heap_of(const std::string& text) {
    return text.capacity() > 15 ? block(text.capacity() + 1) : 0;
}

// What the trajectory holds in memory, counted as malloc allocates it.
std::uint64_t held_bytes(const Trajectory& t) {
    std::uint64_t bytes = heap_of(t.scene) + heap_of(t.scene_sha256) + heap_of(t.engine);
    bytes += block(t.solver.capacity() * sizeof(t.solver[0]));
    for (const auto& [key, value] : t.solver) {
        bytes += heap_of(key) + heap_of(value);
    }
    bytes += block(t.columns.capacity() * sizeof(std::string));
    for (const std::string& column : t.columns) {
        bytes += heap_of(column);
    }
    bytes += block(t.frames.capacity() * sizeof(t.frames[0]));
    for (const std::vector<double>& frame : t.frames) {
        bytes += block(frame.capacity() * sizeof(double));
    }
    bytes += block(t.events.capacity() * sizeof(TrajectoryEvent));
    for (const TrajectoryEvent& event : t.events) {
        bytes += heap_of(event.a) + heap_of(event.b);
    }
    return bytes;
}

bool over_limit(const harness::TrajectorySize& size) {
    const std::uint64_t limit = harness::trajectory_limit_bytes();
    return size.text_bytes > limit || size.memory_bytes() > limit;
}

// The smallest k >= 1 whose k-fold text the limit refuses; its size grows
// linearly with k, so the estimate from k = 1 and 2 is corrected by a step at most.
std::size_t smallest_refused(const Trajectory& trajectory) {
    const auto size_at = [&](std::size_t k) {
        return harness::size_of_text(harness::write_trajectory(repeated(trajectory, k)));
    };
    const harness::TrajectorySize one = size_at(1);
    const harness::TrajectorySize two = size_at(2);
    const std::uint64_t limit = harness::trajectory_limit_bytes();
    // Refused as soon as either the text or the memory is over.
    std::size_t k = std::numeric_limits<std::size_t>::max();
    for (const auto& [at_one, per] :
         {std::pair{one.memory_bytes(), two.memory_bytes() - one.memory_bytes()},
          {one.text_bytes, two.text_bytes - one.text_bytes}}) {
        const std::size_t first_over = at_one > limit ? 1
                                       : per == 0
                                           ? std::numeric_limits<std::size_t>::max()
                                           : static_cast<std::size_t>((limit - at_one) / per + 2);
        k = std::min(k, first_over);
    }
    while (k > 1 && over_limit(size_at(k - 1))) {
        --k;
    }
    while (!over_limit(size_at(k))) {
        ++k;
    }
    return k;
}

} // namespace

void check_memory_budget(const Trajectory& trajectory) {
    if (trajectory.frames.empty()) {
        return; // nothing to repeat
    }
    const std::size_t k = smallest_refused(trajectory);
    try {
        harness::read_trajectory(harness::write_trajectory(repeated(trajectory, k)), "fuzz.json");
        finding("a trajectory over the memory budget was read");
    } catch (const InputError& error) {
        if (std::string(error.what()).find("is too large to read") == std::string::npos) {
            finding(std::string("a trajectory over the memory budget was parsed before it was "
                                "refused: ") +
                    error.what());
        }
    }
    if (k == 1) {
        return;
    }
    const Trajectory under = repeated(trajectory, k - 1);
    const std::string text = harness::write_trajectory(under);
    Trajectory read;
    try {
        read = harness::read_trajectory(text, "fuzz.json");
    } catch (const InputError& error) {
        finding(std::string("a trajectory within the memory budget was refused: ") + error.what());
    }
    if (!same_trajectory(read, under)) {
        finding("a trajectory within the memory budget did not read back the same");
    }
    const harness::TrajectorySize size = harness::size_of_text(text);
    if (held_bytes(read) > size.memory_bytes() + size.text_bytes) {
        finding("the reader holds " + std::to_string(held_bytes(read)) +
                " bytes, more than the budget's model of its text counts (" +
                std::to_string(size.memory_bytes()) + " + " + std::to_string(size.text_bytes) +
                " bytes of text)");
    }
}

} // namespace impulse::fuzz
