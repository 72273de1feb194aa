// Tolerances for comparing a new trajectory with a golden (DESIGN.md,
// "Comparing and the golden workflow"). There are no silent defaults: a
// channel without a tolerance cannot be compared in tolerance mode.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

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

} // namespace impulse::harness
