// A recorded run in the impulse/trajectory@1 format (docs/design.md): frames of
// every dynamic body's state at t = 0 and after every full step, and every
// resolved collision.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

inline constexpr const char* trajectory_schema = "impulse/trajectory@1";

struct TrajectoryEvent {
    double t = 0.0;
    std::string a;
    std::string b;
    double point[2] = {0.0, 0.0};
    double normal[2] = {0.0, 0.0};
    double impulse = 0.0;
    double vn_before = 0.0;
    double vn_after = 0.0;
};

// A run that stopped before the scene's duration (a refused resting contact,
// a Zeno cascade, too many collisions): the sentence that stopped it, and the
// time of the last frame recorded. Written as "partial": {"reason": ...,
// "t": ...} after the events (docs/formats.md); a trajectory without it ran
// to the end. The gate never takes a partial trajectory as a golden.
struct TrajectoryPartial {
    std::string reason;
    double t = 0.0;
};

// The solver block is kept as ordered (key, JSON text) pairs so that it is
// written back in the order it was read, whatever simulator produced it.
struct Trajectory {
    std::string scene;
    std::string scene_sha256;
    std::string engine;
    std::vector<std::pair<std::string, std::string>> solver; // key -> JSON value text
    std::vector<std::string> columns;
    std::vector<std::vector<double>> frames;
    std::vector<TrajectoryEvent> events;
    std::optional<TrajectoryPartial> partial;
};

// FNV-1a 64 over the little-endian bytes of every double's bit pattern, frames
// row by row, then each event's t, point, normal, impulse, vn_before, vn_after.
std::uint64_t digest_of(const Trajectory& trajectory);
// 16 lowercase hex digits.
std::string digest_hex(std::uint64_t digest);

// Serialises in the fixed key order of docs/design.md, one frame per line, doubles
// in shortest round-trip form (-0.0 kept as "-0.0").
std::string write_trajectory(const Trajectory& trajectory);

// Parses and validates; throws InputError naming `file` and the JSON path.
// Checks the stored digest against the data.
// Refuses, before parsing, a text whose numbers, frames and events would
// take more memory than the trajectory limit (docs/memory.md).
Trajectory read_trajectory(const std::string& text, const std::string& file);

// Reads the file at `path` (at most the trajectory limit) and parses it;
// `what` names it in a refusal ("a golden", "a trajectory").
Trajectory read_trajectory_file(const std::string& path, const std::string& what);
// The text of a trajectory file within the trajectory limit.
std::string read_trajectory_text(const std::string& path, const std::string& what);

// Refuses (InputError naming `file`) a text read_trajectory would refuse for
// its size: every writer calls it first, so nothing is written that the
// readers refuse.
void require_readable_size(const std::string& text, const std::string& file);

} // namespace impulse::harness
