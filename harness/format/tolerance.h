// Tolerances for comparing a new trajectory with a golden (docs/design.md,
// "Comparing and the golden workflow"). There are no silent defaults: a
// channel without a tolerance cannot be compared in tolerance mode.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// The quantities a comparison tells apart. Frame columns map to the first four
// (x, y -> position; angle; vx, vy -> velocity; omega -> angular_velocity);
// event fields: t -> event_time, point -> position, normal -> angle,
// impulse -> impulse, vn_before / vn_after -> velocity.
enum class Channel { position, angle, velocity, angular_velocity, impulse, event_time };
inline constexpr int channel_count = 6;
inline constexpr std::array<const char*, channel_count> channel_names = {
    "position", "angle", "velocity", "angular_velocity", "impulse", "event_time"};

// A value passes when |new - gold| <= atol + rtol * |gold|, or when the two
// doubles are at most `ulp` units in the last place apart (either suffices, so
// a ULP-only bound works near zero and an atol-only bound works across scales).
struct ChannelTolerance {
    double atol = 0.0;
    double rtol = 0.0;
    std::uint64_t ulp = 0;
};

struct Tolerances {
    std::array<std::optional<ChannelTolerance>, channel_count> channels{};

    const std::optional<ChannelTolerance>& operator[](Channel c) const {
        return channels[static_cast<int>(c)];
    }
    std::optional<ChannelTolerance>& operator[](Channel c) { return channels[static_cast<int>(c)]; }
};

// Distance in units in the last place between two finite doubles; +0.0 and
// -0.0 are 0 apart here (exact mode tells them apart separately).
std::uint64_t ulp_distance(double a, double b);

bool within(const ChannelTolerance& tolerance, double gold, double value);

struct Trajectory;

// The channel a frame column measures: "t" -> event_time (frame times are on
// the same clock as event times, and a tolerance mode that compared them
// exactly could not absorb a changed time accumulation), "BODY.x" / "BODY.y"
// -> position, "BODY.angle" -> angle, "BODY.vx" / "BODY.vy" -> velocity,
// "BODY.omega" -> angular_velocity; nullopt for any other column.
std::optional<Channel> column_channel(const std::string& column);

// Applies one command-line tolerance option to `base` and returns the result.
// `option` is "--atol", "--rtol" or "--ulp" and names the field it sets.
// `text` is one value for every channel ("1e-9") or channel=value pairs
// separated by commas ("position=1e-9,velocity=1e-6"). The value replaces that
// field of that channel and keeps the channel's other fields; a channel
// without a tolerance in `base` gets one whose other fields are 0 (nothing
// added to the bound). atol and rtol are finite numbers >= 0, ulp a whole
// number >= 0. Throws std::invalid_argument, one sentence naming the option
// and the bad part, for anything else (the command line turns it into exit 2).
Tolerances parse_tolerance_option(const std::string& option, const std::string& text,
                                  Tolerances base);

// The channels `gold` has values to compare for (its frame columns when it has
// frames; event_time, position, angle, impulse and velocity when it has
// events) that `tolerances` gives no tolerance for, in channel order. Tolerance
// mode refuses to run while this is non-empty: there are no silent defaults.
std::vector<Channel> channels_without_tolerance(const Trajectory& gold,
                                                const Tolerances& tolerances);

} // namespace impulse::harness
