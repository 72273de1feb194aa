// Reading impulse/trajectory@1 (docs/design.md, "Trajectory and golden format"):
// strict, so a golden that does not parse cleanly is an input error naming the
// file and JSON path, never a crash; and bounded, so a file is refused before
// it is parsed when holding it would exceed the trajectory limit
// (docs/memory.md).
#include "atomic_file.h"
#include "input_error.h"
#include "memory_budget.h"
#include "number_format.h"
#include "strict_json.h"
#include "trajectory.h"
#include "trajectory_fields.h"
#include "trajectory_stream.h"

namespace impulse::harness {

namespace {

using namespace trajectory_fields;

// The frames' first problem in document order, now that the column count is
// known: frame by frame, a frame's shape (an array of the right length)
// before its values.
void check_frames(const StreamedDocument& document, std::size_t column_count) {
    const std::optional<FrameProblem>& not_array = document.first_frame_not_array;
    const std::optional<FrameProblem>& bad_value = document.first_bad_value;
    std::size_t last = document.frames.size();
    for (const auto* problem : {&not_array, &bad_value}) {
        if (*problem && (*problem)->frame < last) {
            last = (*problem)->frame;
        }
    }
    for (std::size_t i = 0; i < document.frames.size() && i <= last; ++i) {
        if (not_array && not_array->frame == i) {
            throw not_array->invalid;
        }
        const std::size_t size = document.frames[i].size();
        if (size != column_count) {
            fail(json_element_path("frames", i), "has " + std::to_string(size) +
                                                     " values but there are " +
                                                     std::to_string(column_count) + " columns");
        }
        if (bad_value && bad_value->frame == i) {
            throw bad_value->invalid;
        }
    }
}

// "partial": {"reason": SENTENCE, "t": T}, T a finite number.
TrajectoryPartial read_partial(const Json& value) {
    require_object(value, "partial");
    reject_unknown_keys(value, "partial", {"reason", "t"});
    TrajectoryPartial partial;
    partial.reason = read_string(require_key(value, "partial", "reason"), "partial.reason");
    if (partial.reason.empty()) {
        fail("partial.reason", "must say why the run stopped, got an empty string");
    }
    require_printable(partial.reason, "partial.reason");
    partial.t = read_number(require_key(value, "partial", "t"), "partial.t");
    return partial;
}

Trajectory read_validated(StreamedDocument document) {
    const Json& top = document.top;
    if (!top.is_object()) {
        fail("", "the top level must be a JSON object, " + got(top));
    }
    // The schema first: a scene file given by mistake should be told so, not
    // told about its unknown keys.
    check_schema(top);
    reject_unknown_keys(top, "",
                        {"schema", "scene", "scene_sha256", "engine", "solver", "digest", "columns",
                         "frames", "events", "partial"});

    Trajectory trajectory;
    trajectory.scene = read_name(require_key(top, "", "scene"), "scene");
    trajectory.scene_sha256 =
        read_lower_hex(require_key(top, "", "scene_sha256"), "scene_sha256", 64);
    trajectory.engine = read_name(require_key(top, "", "engine"), "engine");
    trajectory.solver = read_solver(require_key(top, "", "solver"));
    const std::string stored_digest = read_lower_hex(require_key(top, "", "digest"), "digest", 16);
    trajectory.columns = read_columns(require_key(top, "", "columns"));

    // Streamed arrays stand in the top object as empty arrays; anything else
    // there is what was found instead of an array.
    require_array(require_key(top, "", "frames"), "frames");
    check_frames(document, trajectory.columns.size());
    trajectory.frames = std::move(document.frames);
    require_array(require_key(top, "", "events"), "events");
    if (document.first_bad_event) {
        throw *document.first_bad_event;
    }
    trajectory.events = std::move(document.events);
    if (top.contains("partial")) {
        trajectory.partial = read_partial(top["partial"]);
        // The writer sets it to the last frame's time: where the run stopped.
        const double last = trajectory.frames.empty() ? 0.0 : trajectory.frames.back().front();
        if (!(trajectory.partial->t == last)) {
            fail("partial.t", "is " + format_double(trajectory.partial->t) +
                                  ", but the last frame is at t = " + format_double(last) +
                                  " (a stopped run ends at its last frame)");
        }
    }

    const std::uint64_t computed = digest_of(trajectory);
    if (computed != hex_to_u64(stored_digest)) {
        fail("digest", "stored digest " + stored_digest + " does not match the data (" +
                           digest_hex(computed) + "): the file was edited by hand or is corrupt");
    }
    return trajectory;
}

} // namespace

Trajectory read_trajectory(const std::string& text, const std::string& file) {
    check_json_text(text, file);
    // Refused before parsing: what the numbers, frames and events would take.
    const TrajectorySize size = size_of_text(text);
    require_within_trajectory_limit(size, file, "", "is too large to read");
    try {
        return read_validated(stream_trajectory(text, file, static_cast<std::size_t>(size.arrays)));
    } catch (const FieldError& invalid) {
        throw InputError(file, invalid.path, invalid.message);
    }
}

Trajectory read_trajectory_file(const std::string& path, const std::string& what) {
    return read_trajectory(read_trajectory_text(path, what), path);
}

std::string read_trajectory_text(const std::string& path, const std::string& what) {
    return read_file(path, static_cast<std::size_t>(trajectory_limit_bytes()),
                     what + " is at most that; " + trajectory_limit_advice());
}

void require_readable_size(const std::string& text, const std::string& file) {
    require_within_trajectory_limit(size_of_text(text), file, "",
                                    "is not written, since no verb could read it back");
}

} // namespace impulse::harness
