// The pile scene the adversarial input tests start from (test_pile_input.cpp,
// test_extreme_input.cpp), and the edits they make to it: each case changes
// one thing in a scene that runs.
#pragma once

#include "bad_input.h"

#include <string>

namespace impulse::test {

// Six bodies of both kinds on 3 columns and 2 rows at spacing 0.71, dropped
// for five steps; "resting": true with six bodies runs the event model
// (auto, world stepping), which the tunnelling check applies to. Named
// drop-box: the gate runs each case in place of that canonical scene, and a
// refusal made before simulating comes after the check that a scene's name
// is its file's. `more` (top-level members, no trailing comma) ends it.
inline std::string input_pile(const std::string& more = "") {
    return R"({
  "schema": "impulse/scene@1",
  "name": "drop-box",
  "restitution": 0.5,
  "dt": 0.01,
  "duration": 0.05,
  "solver": {"integrator": "verlet", "resting": true},
  "pile": {"count": 6, "shape": "mixed", "size": [0.05, 0.25], "density": [1, 4], "spacing": 0.71, "seed": 1})" +
           (more.empty() ? std::string("\n") : ",\n" + more + "\n") + "}\n";
}

// `scene`, an input_pile(), with one member of its pile block given `value`.
inline std::string with_pile_value(const std::string& scene, const std::string& key,
                                   const std::string& value) {
    return replace_once(scene, line_of(scene, "pile"),
                        with_value(line_of(scene, "pile"), key, value));
}

// `scene`, an input_pile(), with `block` as its solver.
inline std::string with_pile_solver(const std::string& scene, const std::string& block) {
    return replace_once(scene, R"("solver": {"integrator": "verlet", "resting": true})",
                        R"("solver": )" + block);
}

} // namespace impulse::test
