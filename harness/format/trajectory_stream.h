// Reading a trajectory in one pass over its text (nlohmann::sax_parse), with
// no document tree for the bulk of it: each frame becomes a row of doubles and
// each event a TrajectoryEvent as they are read, so a file of B bytes holding
// N numbers takes about B + 8 N bytes (docs/memory.md), where a tree of it
// took more than 30 times B. Internal to the trajectory reader.
#pragma once

#include "trajectory_fields.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::trajectory_fields {

// The first thing wrong with the frames, found while streaming; which one is
// reported is decided once the columns are known (trajectory_reader.cpp), in
// the order a check of the whole document takes: frame by frame, each frame's
// shape before its values.
struct FrameProblem {
    std::size_t frame = 0;
    FieldError invalid;
};

// The document as the stream leaves it.
struct StreamedDocument {
    // The top-level value; for an object, every member but the frames and
    // events arrays, which stand here as empty arrays.
    Json top;
    std::vector<std::vector<double>> frames; // as read; rows not arrays are empty
    std::optional<FrameProblem> first_frame_not_array;
    std::optional<FrameProblem> first_bad_value;
    bool frames_streamed = false;
    std::vector<TrajectoryEvent> events; // up to the first that is wrong
    std::optional<FieldError> first_bad_event;
    bool events_streamed = false;
};

// Parses `text` (already through check_json_text). Throws InputError naming
// `file` for a syntax error, a number out of range or a repeated key, as
// parse_strict_json does; what is wrong with the trajectory's fields is left
// in the result. `frames_hint` (at least the number of frames, e.g. the
// count of arrays) is reserved up front, sparing the copies of a growing vector.
StreamedDocument stream_trajectory(const std::string& text, const std::string& file,
                                   std::size_t frames_hint);

} // namespace impulse::harness::trajectory_fields
