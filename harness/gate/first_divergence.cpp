// The one first divergence of a comparison (first_divergence.h).
#include "first_divergence.h"

#include "text.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>

namespace impulse::harness {

namespace {

// NaN (no t column) sorts after every time.
double time_key(double t) {
    return std::isnan(t) ? HUGE_VAL : t;
}

// "impulse" from "events[0].impulse", in words for a sentence.
std::string event_field_words(const std::string& column) {
    const std::size_t dot = column.find("].");
    const std::string field = dot == std::string::npos ? column : column.substr(dot + 2);
    if (field == "t") {
        return "time";
    }
    if (field == "point.x" || field == "point.y") {
        return "contact point " + field.substr(6);
    }
    if (field == "normal.x" || field == "normal.y") {
        return "normal " + field.substr(7);
    }
    if (field == "vn_before") {
        return "normal velocity before";
    }
    if (field == "vn_after") {
        return "normal velocity after";
    }
    return field;
}

// "the first collision's", "collision 4's (events[3])".
std::string collision_words(std::size_t index) {
    if (index == 0) {
        return "the first collision's";
    }
    return "collision " + std::to_string(index + 1) + "'s (events[" + std::to_string(index) + "])";
}

// Two significant digits: a difference is read for its size.
std::string rough(double value) {
    if (!std::isfinite(value)) {
        return sentence_number(value);
    }
    char buffer[32];
    const std::to_chars_result r =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 2);
    return std::string(buffer, r.ptr);
}

// A few ULP say "rounding"; past a million ULP the count means nothing to a
// reader, and the difference itself does.
std::string ulp_words(const Divergence& d) {
    constexpr std::uint64_t rounding_scale = 1000000;
    if (d.ulp <= rounding_scale) {
        return plural(static_cast<std::size_t>(d.ulp), "ULP", "ULP");
    }
    return rough(d.abs_diff) + " (relative " + rough(d.rel_diff) + ")";
}

std::string event_cause(const Divergence& d, bool the_rest_follows) {
    std::string text = collision_words(d.frame) + " " + event_field_words(d.column) +
                       " differs by " + ulp_words(d);
    return text + (the_rest_follows ? "; every later difference follows from it"
                                    : "; other values differ as early as it does");
}

std::string frame_cause(const Divergence& d, bool an_event_differs) {
    std::string text = d.column + " (the " + channel_names[static_cast<int>(d.channel)] +
                       " channel) differs first, by " + ulp_words(d);
    return text + (an_event_differs ? ", before any collision differs" : "; no collision differs");
}

} // namespace

bool is_event_divergence(const Divergence& divergence) {
    return divergence.column.rfind("events[", 0) == 0;
}

const Divergence* earliest_divergence(const Comparison& comparison) {
    // An event stamped with its step's end, t0 + dt, is the frame's
    // collision though its time is a few ULP past k dt (an engine that
    // stamped so was told a frame's angle differed "before any collision
    // differs" by 1 ULP of time).
    const double slack = comparison.event_time_slack;
    const Divergence* best = nullptr;
    for (const Divergence& d : comparison.first_divergences) {
        if (best == nullptr) {
            best = &d;
            continue;
        }
        const double t = time_key(d.t);
        const double best_t = time_key(best->t);
        const bool event = is_event_divergence(d);
        const bool best_event = is_event_divergence(*best);
        // first_divergences lists frames in column order, then events in
        // index order, so keeping the earlier entry on a tie is the rule.
        const bool earlier = event == best_event ? t < best_t
                             : event             ? t <= best_t + slack
                                                 : t < best_t - slack;
        if (earlier) {
            best = &d;
        }
    }
    return best;
}

std::optional<FirstDivergence> first_divergence_of(const Comparison& comparison) {
    const Divergence* earliest = earliest_divergence(comparison);
    if (earliest == nullptr) {
        return std::nullopt;
    }
    FirstDivergence first;
    first.divergence = *earliest;
    first.is_event = is_event_divergence(*earliest);
    bool an_event_differs = false;
    for (const Divergence& d : comparison.first_divergences) {
        an_event_differs = an_event_differs || is_event_divergence(d);
        // Another value at the same time but not after it in the tie order
        // cannot have followed from it: only a frame at the event's time can.
        const bool same_time = time_key(d.t) == time_key(earliest->t);
        if (&d != earliest && same_time && first.is_event && is_event_divergence(d)) {
            first.the_rest_follows = false;
        }
    }
    first.cause = first.is_event ? event_cause(*earliest, first.the_rest_follows)
                                 : frame_cause(*earliest, an_event_differs);
    return first;
}

std::string shape_clause(const Comparison& comparison) {
    if (comparison.structural.empty()) {
        return "";
    }
    const std::size_t more = comparison.structural.size() - 1;
    return "; the trajectories also differ in shape: " + comparison.structural.front() +
           (more > 0 ? " (and " + std::to_string(more) + " more)" : "");
}

std::string first_divergence_line(const Comparison& comparison) {
    const std::optional<FirstDivergence> first = first_divergence_of(comparison);
    if (!first) {
        return comparison.structural.empty() ? "the trajectories differ"
                                             : comparison.structural.front();
    }
    const Divergence& d = first->divergence;
    return "first divergence: " + d.column + " at t = " + sentence_number(d.t) + " s (golden " +
           sentence_number(d.gold) + ", new " + sentence_number(d.value) + "): " + first->cause +
           shape_clause(comparison);
}

std::string cause_key(const Comparison& comparison) {
    const Divergence* d = earliest_divergence(comparison);
    if (d == nullptr) {
        return "";
    }
    if (is_event_divergence(*d)) {
        return d->column;
    }
    return std::string("the ") + channel_names[static_cast<int>(d->channel)] + " channel";
}

std::vector<std::string> shared_causes(const std::vector<SceneCheck>& checks) {
    std::vector<std::string> order;
    std::map<std::string, std::vector<std::string>> scenes;
    for (const SceneCheck& check : checks) {
        if (check.status != SceneCheck::Status::failed || !check.comparison) {
            continue;
        }
        const std::string key = cause_key(*check.comparison);
        if (key.empty()) {
            continue;
        }
        std::vector<std::string>& names = scenes[key];
        if (names.empty()) {
            order.push_back(key);
        }
        names.push_back(check.engine.empty() ? check.name : check.engine + "/" + check.name);
    }
    std::vector<std::string> lines;
    for (const std::string& key : order) {
        const std::vector<std::string>& names = scenes[key];
        if (names.size() < 2) {
            continue;
        }
        std::string line = std::to_string(names.size()) + " scenes start diverging " +
                           (key.rfind("events[", 0) == 0 ? "at " : "in ") + key + ":";
        for (std::size_t i = 0; i < names.size(); ++i) {
            line += (i == 0 ? " " : ", ") + names[i];
        }
        lines.push_back(line);
    }
    return lines;
}

} // namespace impulse::harness
