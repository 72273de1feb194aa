// Per-channel tolerances: the ULP metric, the pass rule, and the command-line
// form of tolerances (docs/design.md, "Comparing and the golden workflow").
#include "tolerance.h"

#include "trajectory.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <system_error>

namespace impulse::harness {

namespace {

constexpr std::uint64_t sign_bit = 0x8000000000000000ull;

std::uint64_t bits_of(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// The field a tolerance option sets.
enum class Field { atol, rtol, ulp };

Field field_of(const std::string& option) {
    if (option == "--atol") {
        return Field::atol;
    }
    if (option == "--rtol") {
        return Field::rtol;
    }
    if (option == "--ulp") {
        return Field::ulp;
    }
    // Only code passes `option`, so this is a programming error, not bad input.
    throw std::invalid_argument("parse_tolerance_option: '" + option +
                                "' is not --atol, --rtol or --ulp");
}

std::string channel_list() {
    std::string list;
    for (int i = 0; i < channel_count; ++i) {
        list += (i == 0 ? "" : ", ") + std::string(channel_names[static_cast<std::size_t>(i)]);
    }
    return list;
}

std::optional<Channel> channel_named(const std::string& name) {
    for (int i = 0; i < channel_count; ++i) {
        if (name == channel_names[static_cast<std::size_t>(i)]) {
            return static_cast<Channel>(i);
        }
    }
    return std::nullopt;
}

// " (in 'position=x')" when the bad value came from a channel=value pair, so
// the message points at the pair as the user typed it.
std::string where(const std::string& value, const std::string& item) {
    return value == item ? "" : " (in '" + item + "')";
}

// Sets one field of `slot` from `value`, creating the channel's tolerance
// (all fields 0) when it has none yet.
void set_field(std::optional<ChannelTolerance>& slot, Field field, const std::string& option,
               const std::string& value, const std::string& item) {
    ChannelTolerance tolerance = slot.value_or(ChannelTolerance{});
    const char* first = value.data();
    const char* last = first + value.size();
    if (field == Field::ulp) {
        std::uint64_t ulp = 0;
        // from_chars takes neither a sign nor spaces for an unsigned type.
        const auto [ptr, ec] = std::from_chars(first, last, ulp);
        if (value.empty() || ec != std::errc() || ptr != last) {
            throw std::invalid_argument(option + ": '" + value + "'" + where(value, item) +
                                        " is not a whole number of ULPs >= 0");
        }
        tolerance.ulp = ulp;
    } else {
        double number = 0.0;
        const auto [ptr, ec] = std::from_chars(first, last, number);
        if (value.empty() || ec != std::errc() || ptr != last || !std::isfinite(number) ||
            !(number >= 0.0)) {
            throw std::invalid_argument(option + ": '" + value + "'" + where(value, item) +
                                        " is not a finite number >= 0");
        }
        // +0.0 for "-0", so the stored tolerance never carries a sign.
        (field == Field::atol ? tolerance.atol : tolerance.rtol) = number + 0.0;
    }
    slot = tolerance;
}

std::vector<std::string> split_on_commas(const std::string& text) {
    std::vector<std::string> items;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = text.find(',', start);
        items.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) {
            return items;
        }
        start = comma + 1;
    }
}

} // namespace

std::uint64_t ulp_distance(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) {
        return std::numeric_limits<std::uint64_t>::max();
    }
    // IEEE 754 orders same-signed doubles like their magnitude bits, and both
    // zeros have magnitude 0; so on the line ... -2, -1, 0, 1, 2 ... a double
    // sits at +/- its magnitude bits.
    const std::uint64_t ua = bits_of(a);
    const std::uint64_t ub = bits_of(b);
    const std::uint64_t ma = ua & ~sign_bit;
    const std::uint64_t mb = ub & ~sign_bit;
    if ((ua & sign_bit) == (ub & sign_bit)) {
        return ma > mb ? ma - mb : mb - ma;
    }
    // Opposite signs: the way passes through zero. Each magnitude is below
    // 2^63, so the sum cannot overflow.
    return ma + mb;
}

bool within(const ChannelTolerance& tolerance, double gold, double value) {
    if (std::isnan(gold) || std::isnan(value)) {
        return false; // even an unbounded ULP tolerance must not pass a NaN
    }
    return std::fabs(value - gold) <= tolerance.atol + tolerance.rtol * std::fabs(gold) ||
           ulp_distance(gold, value) <= tolerance.ulp;
}

std::optional<Channel> column_channel(const std::string& column) {
    if (column == "t") {
        return Channel::event_time;
    }
    // The last dot, so a body name may itself contain dots.
    const std::size_t dot = column.rfind('.');
    if (dot == std::string::npos || dot == 0) {
        return std::nullopt;
    }
    const std::string quantity = column.substr(dot + 1);
    if (quantity == "x" || quantity == "y") {
        return Channel::position;
    }
    if (quantity == "angle") {
        return Channel::angle;
    }
    if (quantity == "vx" || quantity == "vy") {
        return Channel::velocity;
    }
    if (quantity == "omega") {
        return Channel::angular_velocity;
    }
    return std::nullopt;
}

Tolerances parse_tolerance_option(const std::string& option, const std::string& text,
                                  Tolerances base) {
    const Field field = field_of(option);
    if (text.find('=') == std::string::npos) {
        // One value for every channel. A comma here means a list that forgot
        // its channel names, which the number check below reports.
        for (auto& slot : base.channels) {
            set_field(slot, field, option, text, text);
        }
        return base;
    }
    std::array<bool, channel_count> seen{};
    for (const std::string& item : split_on_commas(text)) {
        const std::size_t eq = item.find('=');
        if (item.empty() || eq == std::string::npos) {
            throw std::invalid_argument(option + ": '" + item + "' in '" + text +
                                        "' is not channel=value; give one value for every "
                                        "channel or pairs such as position=1e-9,velocity=1e-6");
        }
        const std::string name = item.substr(0, eq);
        const std::optional<Channel> channel = channel_named(name);
        if (!channel) {
            throw std::invalid_argument(option + ": '" + name +
                                        "' is not a channel; the channels are " + channel_list());
        }
        const auto index = static_cast<std::size_t>(*channel);
        if (seen[index]) {
            throw std::invalid_argument(option + ": channel '" + name + "' is given twice in '" +
                                        text + "'");
        }
        seen[index] = true;
        set_field(base.channels[index], field, option, item.substr(eq + 1), item);
    }
    return base;
}

std::vector<Channel> channels_without_tolerance(const Trajectory& gold,
                                                const Tolerances& tolerances) {
    std::array<bool, channel_count> needed{};
    if (!gold.frames.empty()) {
        for (const std::string& column : gold.columns) {
            if (const std::optional<Channel> channel = column_channel(column)) {
                needed[static_cast<std::size_t>(*channel)] = true;
            }
        }
    }
    if (!gold.events.empty()) {
        // Event fields: t, point, normal, impulse, vn_before / vn_after.
        for (Channel channel : {Channel::event_time, Channel::position, Channel::angle,
                                Channel::impulse, Channel::velocity}) {
            needed[static_cast<std::size_t>(channel)] = true;
        }
    }
    std::vector<Channel> missing;
    for (int i = 0; i < channel_count; ++i) {
        const auto channel = static_cast<Channel>(i);
        if (needed[static_cast<std::size_t>(i)] && !tolerances[channel]) {
            missing.push_back(channel);
        }
    }
    return missing;
}

} // namespace impulse::harness
