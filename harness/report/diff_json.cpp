// impulse/diff@1 (diff_json.h).
#include "diff_json.h"

#include "first_divergence.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace impulse::harness {

namespace {

using Json = nlohmann::ordered_json;

// JSON has no NaN or infinity: null stands for a value that is not a number.
Json number(double value) {
    return std::isfinite(value) ? Json(value) : Json(nullptr);
}

const char* channel_name(Channel channel) {
    return channel_names[static_cast<std::size_t>(channel)];
}

// One differing value, with the numbers the terminal prints for it.
Json divergence_json(const Divergence& d) {
    Json j;
    j["column"] = d.column;
    j["channel"] = channel_name(d.channel);
    j[is_event_divergence(d) ? "event" : "frame"] = d.frame;
    j["t"] = number(d.t);
    j["golden"] = number(d.gold);
    j["new"] = number(d.value);
    j["abs"] = number(d.abs_diff);
    j["rel"] = number(d.rel_diff);
    j["ulp"] = d.ulp;
    return j;
}

Json first_json(const Comparison& comparison) {
    const std::optional<FirstDivergence> first = first_divergence_of(comparison);
    if (!first) {
        return nullptr;
    }
    Json j = divergence_json(first->divergence);
    j["the_rest_follows"] = first->the_rest_follows;
    j["cause"] = first->cause;
    return j;
}

Json compared_channels_json(const Comparison& comparison) {
    Json channels = Json::object();
    for (std::size_t c = 0; c < channel_count; ++c) {
        const ChannelSummary& s = comparison.channels[c];
        if (s.compared == 0) {
            continue; // the trajectories have no values of this channel
        }
        channels[channel_names[c]] = {{"compared", s.compared},
                                      {"differing", s.differing},
                                      {"max_abs", number(s.max_abs)},
                                      {"max_rel", number(s.max_rel)},
                                      {"max_ulp", s.max_ulp}};
    }
    return channels;
}

} // namespace

const char* diff_verdict(const Comparison& comparison) {
    return comparison.identical ? "identical" : comparison.passed ? "within tolerance" : "differs";
}

std::string diff_json(const DiffInput& input, const Comparison& comparison) {
    Json document;
    document["schema"] = diff_schema;
    document["golden"] = input.golden_file;
    document["new"] = input.new_file;
    document["mode"] = input.tolerance_mode ? "tolerance" : "exact";
    document["verdict"] = diff_verdict(comparison);
    document["passed"] = comparison.passed;
    document["same_scene"] = input.same_scene;
    document["structural"] = comparison.structural;
    document["first_divergence"] = first_json(comparison);
    // The terminal's line, word for word, when the comparison failed.
    document["first_divergence_line"] =
        comparison.passed ? Json(nullptr) : Json(first_divergence_line(comparison));
    Json columns = Json::array();
    for (const Divergence& d : comparison.first_divergences) {
        columns.push_back(divergence_json(d));
    }
    document["columns"] = std::move(columns);
    document["channels"] = compared_channels_json(comparison);
    // Invalid UTF-8 in a column name is replaced, never a crash.
    return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace impulse::harness
