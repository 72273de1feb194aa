// Validation of an engine's standard output. The text is streamed by the
// trajectory reader's own pieces (trajectory_stream.h), so 256 MiB of frames
// take about the memory of their doubles; what read_trajectory accepts for
// goldens does not change: the rules of the protocol are checked here, on
// top of the stream, against the scene the engine was given.
#include "engine_output.h"

#include "engine_process.h"
#include "memory_budget.h"
#include "number_format.h"
#include "strict_json.h"
#include "trajectory_columns.h"
#include "trajectory_fields.h"
#include "trajectory_stream.h"

#include <cmath>
#include <limits>
#include <set>

namespace impulse::harness {

namespace {

using namespace trajectory_fields;

// How far a frame's or an event's time may be from where it belongs, in
// units of dt: an engine that accumulates t += dt drifts by rounding only.
constexpr double time_slack = 1e-6;

// Finds the non-finite token a parse error stopped at: JSON has no NaN or
// Infinity, but Python's json.dump writes them, and "invalid literal" would
// not tell its author why.
class NonFiniteFinder : public nlohmann::json_sax<nlohmann::json> {
  public:
    explicit NonFiniteFinder(const std::string& text) : text_(text) {}
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    // `position` counts the characters read: the offending one is the last.
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception&) override {
        const std::size_t at = position == 0 ? 0 : position - 1;
        if (text_.compare(at, 3, "NaN") == 0) {
            token_ = "NaN";
        } else if (text_.compare(at, 8, "Infinity") == 0) {
            token_ = at > 0 && text_[at - 1] == '-' ? "-Infinity" : "Infinity";
        }
        return false;
    }
    const std::string& token() const { return token_; }

  private:
    const std::string& text_;
    std::string token_;
};

std::string non_finite_token(const std::string& text) {
    NonFiniteFinder finder(text);
    nlohmann::json::sax_parse(text, &finder);
    return finder.token();
}

InputError output_error(const std::string& label, const std::string& path,
                        const std::string& message) {
    return InputError(label, path.empty() ? "output" : "output " + path, message);
}

// A syntax error caused by text around the trajectory (a debug print before
// or after it), or by a trajectory cut short, says so and shows how the output begins. Found by a
// helper writing an engine: "line 1, column 1: invalid literal" did not say that standard output
// must hold the trajectory alone.
std::string with_stray_text(const std::string& text, const std::string& message) {
    const std::string only = "standard output must hold only the trajectory; write anything "
                             "else to standard error";
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (text[first] != '{') {
        // Its first line, printable and cut as an engine's message is.
        constexpr std::size_t shown_chars = 40;
        const std::string line = text.substr(first, text.find('\n', first) - first);
        return "begins with \"" + last_line(line, shown_chars) +
               "\", not with a trajectory's \"{\" (" + only + ")";
    }
    // "...; expected end of input": something after the closing brace.
    if (message.find("; expected end of input") != std::string::npos) {
        return message + " (text follows the trajectory: " + only + ")";
    }
    // The text stops inside the trajectory: the parser says "unexpected end of
    // input", or, cut inside a number, string or literal, names what it last
    // read; either way the last character is no closing brace (an outside
    // review's engine killed mid-write was told text followed it, and one cut
    // inside a number was told nothing).
    const std::size_t last = text.find_last_not_of(" \t\r\n");
    if (message.find("unexpected end of input") != std::string::npos || text[last] != '}') {
        return message + " (the output stops inside the trajectory: the engine exited, or "
                         "closed standard output, before writing all of it; flush it before "
                         "exiting)";
    }
    return message;
}

// The stream, its syntax errors named as the engine's output.
StreamedDocument stream_output(const std::string& text, const std::string& label) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
        throw output_error(label, "",
                           "is empty: the engine exited with 0 but wrote no trajectory on "
                           "standard output");
    }
    check_json_text(text, label + ": output");
    // The stream skips a top-level array without keeping it; say what it was.
    if (text[text.find_first_not_of(" \t\r\n")] == '[') {
        throw output_error(label, "",
                           "the top level must be a JSON object (a trajectory), got an array");
    }
    const TrajectorySize size = size_of_text(text);
    require_within_trajectory_limit(size, label + ": output", "", "is too large to read");
    try {
        return stream_trajectory(text, "output", static_cast<std::size_t>(size.arrays));
    } catch (const InputError& error) {
        std::string message = error.message();
        if (message.rfind("not valid JSON", 0) == 0) {
            const std::string token = non_finite_token(text);
            if (!token.empty()) {
                message = token + " is not a finite number (JSON has no " + token +
                          "; write a number, or exit 3 if the scene is beyond the engine)";
            } else {
                message = with_stray_text(text, message);
            }
        }
        throw output_error(label, error.json_path(), message);
    }
}

std::vector<std::string> expected_columns(const Scene& scene) {
    std::vector<std::string> columns = {"t"};
    for (const SceneBody& body : scene.bodies) {
        if (!body.is_static) {
            for (const char* channel : body_channel_suffixes) {
                columns.push_back(body.name + channel);
            }
        }
    }
    return columns;
}

// Exactly the scene's dynamic bodies' columns: the first wrong or missing one
// is named with what was expected there.
std::vector<std::string> read_expected_columns(const Json& value, const Scene& scene) {
    require_array(value, "columns");
    std::vector<std::string> expected = expected_columns(scene);
    const std::string count = std::to_string(expected.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string path = json_element_path("columns", i);
        const std::string name = read_name(value[i], path);
        if (i >= expected.size()) {
            fail(path, Json(name).dump() +
                           " is one column too many: \"t\" and six per dynamic "
                           "body of the scene make " +
                           count);
        }
        if (name != expected[i]) {
            fail(path, "must be " + Json(expected[i]).dump() + ", got " + Json(name).dump() +
                           " (\"t\", then NAME.x, NAME.y, NAME.angle, NAME.vx, NAME.vy, "
                           "NAME.omega for each dynamic body in the scene's order)");
        }
    }
    if (value.size() < expected.size()) {
        fail("columns", "column " + Json(expected[value.size()]).dump() + " is missing (" +
                            std::to_string(value.size()) + " of " + count + " columns given)");
    }
    return expected;
}

// steps + 1 frames, each as long as the columns, at t = k dt within time_slack dt.
void check_frames(const StreamedDocument& document, std::size_t columns, const Scene& scene) {
    const long long steps = step_count(scene);
    const std::size_t wanted = static_cast<std::size_t>(steps) + 1;
    if (document.frames.size() != wanted) {
        fail("frames", "has " + std::to_string(document.frames.size()) + " frames; the scene's " +
                           std::to_string(steps) + " steps (duration " +
                           format_double(scene.duration) + " s, dt " + format_double(scene.dt) +
                           " s) make " + std::to_string(wanted));
    }
    const auto& not_array = document.first_frame_not_array;
    const auto& bad_value = document.first_bad_value;
    for (std::size_t k = 0; k < wanted; ++k) {
        if (not_array && not_array->frame == k) {
            throw not_array->invalid;
        }
        const std::vector<double>& frame = document.frames[k];
        if (frame.size() != columns) {
            fail(json_element_path("frames", k), "has " + std::to_string(frame.size()) +
                                                     " values but there are " +
                                                     std::to_string(columns) + " columns");
        }
        if (bad_value && bad_value->frame == k) {
            throw bad_value->invalid;
        }
        const double t = static_cast<double>(k) * scene.dt;
        if (!(std::fabs(frame[0] - t) <= time_slack * scene.dt)) {
            fail(json_element_path(json_element_path("frames", k), 0),
                 "t must be " + format_double(t) + " (frame " + std::to_string(k) +
                     " is the state at k dt, within 1e-6 dt), got " + format_double(frame[0]));
        }
    }
}

// `end`: the run's last time, steps dt (or the duration, when later).
void check_event(const TrajectoryEvent& e, const std::string& path,
                 const std::set<std::string>& bodies, double end, double slack, double previous) {
    for (const auto& [key, name] : {std::pair{"a", &e.a}, {"b", &e.b}}) {
        if (bodies.count(*name) == 0) {
            fail(json_member_path(path, key),
                 "no body of the scene is named " + Json(*name).dump());
        }
    }
    if (e.a == e.b) {
        fail(json_member_path(path, "b"), "is the same body as a; an event is between two");
    }
    const double length = std::hypot(e.normal[0], e.normal[1]);
    if (!(std::fabs(length - 1.0) <= 1e-6)) {
        fail(json_member_path(path, "normal"),
             "must be a unit vector (within 1e-6), has length " + format_double(length));
    }
    if (!(e.impulse >= 0.0)) {
        fail(json_member_path(path, "impulse"),
             "is the normal impulse's magnitude, must be >= 0, got " + format_double(e.impulse));
    }
    const std::string t = json_member_path(path, "t");
    if (!(e.t >= 0.0 && e.t <= end + slack)) {
        fail(t, "must lie in the run, from 0 to " + format_double(end) + " s, got " +
                    format_double(e.t));
    }
    if (e.t < previous) {
        fail(t, "is before the previous event's (" + format_double(previous) +
                    "); events are in time order");
    }
}

void check_events(const StreamedDocument& document, const Scene& scene) {
    if (document.first_bad_event) {
        throw *document.first_bad_event;
    }
    const double last_frame = static_cast<double>(step_count(scene)) * scene.dt;
    const double end = std::max(scene.duration, last_frame);
    std::set<std::string> bodies; // a gas has thousands, and a run many events
    for (const SceneBody& body : scene.bodies) {
        bodies.insert(body.name);
    }
    double previous = 0.0;
    for (std::size_t i = 0; i < document.events.size(); ++i) {
        const TrajectoryEvent& e = document.events[i];
        check_event(e, json_element_path("events", i), bodies, end, time_slack * scene.dt,
                    previous);
        previous = e.t;
    }
}

// The engine's solver block: settings as strings, numbers or booleans.
std::vector<std::pair<std::string, std::string>> read_engine_solver(const Json& solver) {
    require_object(solver, "solver");
    for (const auto& item : solver.items()) {
        const std::string path = json_member_path("solver", item.key());
        if (item.key() == "overrides") {
            fail(path, "is the harness's key: it records the command line's overrides itself");
        }
        const Json& value = item.value();
        if (!value.is_string() && !value.is_number() && !value.is_boolean()) {
            fail(path, "must be a string, a number or a boolean, " + got(value));
        }
    }
    return read_solver(solver);
}

EngineCost read_cost(const Json& cost) {
    require_object(cost, "cost");
    reject_unknown_keys(cost, "cost", {"seconds", "steps"});
    EngineCost result;
    result.seconds = read_number(require_key(cost, "cost", "seconds"), "cost.seconds");
    if (!(result.seconds >= 0.0)) {
        fail("cost.seconds", "must be >= 0, got " + format_double(result.seconds));
    }
    if (cost.contains("steps")) {
        const Json& steps = cost.at("steps");
        if (!steps.is_number_unsigned()) {
            fail("cost.steps", "must be a whole number >= 0, " + got(steps));
        }
        const std::uint64_t count = steps.get<std::uint64_t>();
        if (count > static_cast<std::uint64_t>(std::numeric_limits<long long>::max())) {
            fail("cost.steps", "is too large, got " + std::to_string(count));
        }
        result.steps = static_cast<long long>(count);
    }
    return result;
}

// The optional keys of the top level, each checked when present.
void read_header(const Json& top, const OutputContext& context, EngineOutput& output) {
    Trajectory& trajectory = output.trajectory;
    trajectory.engine = context.engine_name;
    if (top.contains("engine")) {
        trajectory.engine = read_name(top.at("engine"), "engine");
    }
    if (top.contains("solver")) {
        trajectory.solver = read_engine_solver(top.at("solver"));
    }
    if (top.contains("scene")) {
        const std::string name = read_name(top.at("scene"), "scene");
        if (name != context.scene->name) {
            fail("scene", "must be the scene's name " + Json(context.scene->name).dump() +
                              ", got " + Json(name).dump());
        }
    }
    for (const char* ignored : {"scene_sha256", "digest"}) {
        if (top.contains(ignored)) {
            read_string(top.at(ignored), ignored); // ignored, but not any value at all
        }
    }
    if (top.contains("cost")) {
        output.cost = read_cost(top.at("cost"));
    }
}

EngineOutput read_validated(StreamedDocument document, const OutputContext& context) {
    const Json& top = document.top;
    if (!top.is_object()) {
        fail("", "the top level must be a JSON object (a trajectory), " + got(top));
    }
    check_schema(top);
    reject_unknown_keys(top, "",
                        {"schema", "columns", "frames", "events", "engine", "solver", "scene",
                         "scene_sha256", "digest", "cost"});
    EngineOutput output;
    read_header(top, context, output);
    Trajectory& trajectory = output.trajectory;
    trajectory.columns = read_expected_columns(require_key(top, "", "columns"), *context.received);
    require_array(require_key(top, "", "frames"), "frames");
    check_frames(document, trajectory.columns.size(), *context.received);
    if (top.contains("events")) {
        require_array(top.at("events"), "events");
        check_events(document, *context.received);
    }
    trajectory.frames = std::move(document.frames);
    trajectory.events = std::move(document.events);
    trajectory.scene = context.scene->name;
    trajectory.scene_sha256 = context.scene->sha256;
    if (!context.overrides.empty()) {
        trajectory.solver.emplace_back("overrides", context.overrides);
    }
    return output;
}

} // namespace

std::string engine_run_label(const std::string& engine_name, const Scene& scene) {
    return "engine '" + engine_name + "' on " + scene.file;
}

EngineOutput read_engine_output(const std::string& text, const OutputContext& context) {
    const std::string label = engine_run_label(context.engine_name, *context.scene);
    StreamedDocument document = stream_output(text, label);
    try {
        return read_validated(std::move(document), context);
    } catch (const FieldError& invalid) {
        throw output_error(label, invalid.path, invalid.message);
    }
}

} // namespace impulse::harness
