// The scratch the overlap guard (engine/overlap_guard.h) reads, set up for a
// hand-built world as a time step would have it: every body at its start,
// nothing moving, and the candidate pairs given (test_dense_robust.cpp,
// test_time_stepping.cpp).
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

#include <utility>
#include <vector>

namespace impulse::test {

inline TimeSteppingScratch guard_scratch(const World& world, std::vector<CandidatePair> pairs) {
    TimeSteppingScratch s;
    for (const Body& b : world.bodies) {
        s.start.push_back(b.state);
        s.poses.push_back(transform_of(b.state));
    }
    s.reach.assign(world.bodies.size(), 0.0);
    s.paired_at = s.start;
    s.pairs = std::move(pairs);
    return s;
}

} // namespace impulse::test
