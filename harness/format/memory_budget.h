// The memory a run and a comparison may take (docs/memory.md): one limit on
// a trajectory, in bytes of text and in bytes of memory, checked before
// simulating, while recording, before writing and before reading, so that no
// verb writes what another would refuse and none runs out of memory half-way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace impulse::harness {

// The limit's default and the environment variable that changes it.
inline constexpr std::uint64_t default_trajectory_limit_mib = 256;
inline constexpr const char* trajectory_limit_variable = "IMPULSE_MAX_TRAJECTORY_MIB";
inline constexpr std::uint64_t largest_trajectory_limit_mib = 1024 * 1024; // 1 TiB

// The memory model of a trajectory as the harness holds it: 8 bytes a
// number (a double), and for each array, object and string the bookkeeping
// around it (a frame's std::vector and its heap block; an event's fields and
// slack; a std::string, whose characters the text's size already counts).
// fuzz_trajectory checks that the reader never holds more (docs/memory.md).
inline constexpr std::uint64_t bytes_per_number = 8;
inline constexpr std::uint64_t bytes_per_array = 64;
inline constexpr std::uint64_t bytes_per_object = 192;
inline constexpr std::uint64_t bytes_per_string = 32;
// The widest a number is written ("-2.2250738585072014e-308") plus ", ".
inline constexpr std::uint64_t widest_number_text = 26;

// What a trajectory costs: bytes of text, and bytes in memory by the model above.
struct TrajectorySize {
    std::uint64_t text_bytes = 0;
    std::uint64_t numbers = 0;
    std::uint64_t arrays = 0;
    std::uint64_t objects = 0;
    std::uint64_t strings = 0;
    // The model's bytes in memory; the strings' characters are not in it.
    std::uint64_t memory_bytes() const;
    // Both the text and the memory model at most `limit_bytes`.
    bool within(std::uint64_t limit_bytes) const {
        return text_bytes <= limit_bytes && memory_bytes() <= limit_bytes;
    }
};

// The limit in bytes: IMPULSE_MAX_TRAJECTORY_MIB (a whole number of MiB, 1 to
// 1048576) or 256 MiB. Throws InputError naming the variable when it is not one.
std::uint64_t trajectory_limit_bytes();
// "256 MiB (IMPULSE_MAX_TRAJECTORY_MIB changes it)": the end of every refusal.
std::string trajectory_limit_text();

// How a refusal ends: "set IMPULSE_MAX_TRAJECTORY_MIB to a number of MiB to change the limit".
std::string trajectory_limit_advice();

// Counts the numbers, arrays, objects and strings (keys too) of a JSON text,
// in one pass and without allocating: what reading it will hold.
TrajectorySize size_of_text(const std::string& text);

// The most the lines before the frames can take: keys, names, solver block
// and the column names.
TrajectorySize header_size_bound(const std::vector<std::string>& columns);
// The most that a run's frames can take: `frames` rows of `columns` numbers,
// every number as wide as a number is ever written.
TrajectorySize frames_size_bound(std::uint64_t frames, std::uint64_t columns);
// The most one collision event adds, its body names `names_length` bytes together.
TrajectorySize event_size_bound(std::size_t names_length);
TrajectorySize operator+(const TrajectorySize& a, const TrajectorySize& b);

// Throws InputError(file, path, "<what>: [up to] <size>, more than the limit
// of <limit> (how to change it)") when `size` exceeds the limit in text or in
// memory; `bound`: the size is an upper bound ("up to").
void require_within_trajectory_limit(const TrajectorySize& size, const std::string& file,
                                     const std::string& path, const std::string& what,
                                     bool bound = false);

// World stepping (the seed's) keeps every pair of bodies that can collide,
// 8 bytes each (9 with resting contact), and tests each one every step; a
// scene with more pairs than this is refused before it is built and told to
// use stepping "local" (docs/memory.md). IMPULSE_MAX_WORLD_PAIRS changes it.
inline constexpr std::uint64_t default_world_pair_limit = 8'000'000;
inline constexpr const char* world_pair_limit_variable = "IMPULSE_MAX_WORLD_PAIRS";
// The pairs world stepping keeps: every pair but two static bodies.
std::uint64_t world_pair_count(std::uint64_t dynamic_bodies, std::uint64_t static_bodies);
// Throws InputError(file, "solver.stepping", ...) when world stepping of
// these bodies would keep more pairs than the limit.
void require_world_pairs_within_limit(std::uint64_t dynamic_bodies, std::uint64_t static_bodies,
                                      const std::string& file);

// "1.5 MiB", "367 MiB", "2.1 GiB": a size for a message.
std::string bytes_text(std::uint64_t bytes);

} // namespace impulse::harness
