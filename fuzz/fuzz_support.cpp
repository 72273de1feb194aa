#include "fuzz_support.h"

#include "input_error.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

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

} // namespace impulse::fuzz
