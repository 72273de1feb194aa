// Scene texts for the loader's tests (test_scene_*.cpp), and the check that
// the loader refuses one with the file, the JSON path and the reason.
#pragma once

#include "input_error.h"
#include "scene.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace impulse::test {

inline const std::string test_file = "scenes/test.json";

// A valid scene with one dynamic disc; `extra` is spliced in among the
// top-level keys (end it with a comma).
inline std::string scene_with(const std::string& extra) {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, )" + extra +
           R"( "bodies": [{"name": "ball", "shape": {"circle": 0.5}}]})";
}

// A valid scene header around the given bodies array.
inline std::string scene_with_bodies(const std::string& bodies) {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, "bodies": )" +
           bodies + "}";
}

// A scene whose only body is {"name": "b", FIELDS}.
inline std::string scene_with_body(const std::string& fields) {
    return scene_with_bodies(R"([{"name": "b", )" + fields + "}]");
}

// Static ground with its top at y = 0; "ball" (a disc of radius 0.5) 1 m above
// it; "tilted", a 2 x 1 box turned 0.5 rad, free to rotate, well above it;
// "crate", a non-rotating unit box 1 m above it.
inline const std::string standard_bodies = R"([
    {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
    {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 1.5]},
    {"name": "tilted", "shape": {"box": [1, 0.5]}, "angle": 0.5, "position": [5, 3]},
    {"name": "crate", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [-5, 1.5]}])";

// Free space: two discs 3 m apart closing along x, and two non-rotating boxes
// in line along x, closing.
inline const std::string free_bodies = R"([
    {"name": "a", "shape": {"circle": 0.5}, "velocity": [2, 0]},
    {"name": "b", "shape": {"circle": 0.5}, "position": [3, 0]},
    {"name": "p", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [0, 5],
     "velocity": [1, 0]},
    {"name": "q", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [3, 5]}])";

// A scene with the given expectations (a JSON array), bodies and further
// top-level keys (end them with a comma).
inline std::string expecting(const std::string& expectations,
                             const std::string& bodies = standard_bodies,
                             const std::string& extra = "") {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, )" + extra +
           R"( "expectations": )" + expectations + R"(, "bodies": )" + bodies + "}";
}

// expecting() in free space, without gravity.
inline std::string free_space(const std::string& expectations,
                              const std::string& bodies = free_bodies) {
    return expecting(expectations, bodies, R"("gravity": [0, 0],)");
}

// The InputError message parse_scene gives for `text`, or "" when it accepts
// the scene. Any other exception escapes and fails the test.
inline std::string rejection(const std::string& text, const std::string& file = test_file) {
    try {
        impulse::harness::parse_scene(text, file);
    } catch (const impulse::harness::InputError& error) {
        return error.what();
    }
    return "";
}

// parse_scene refuses `text` with "FILE: PATH: ..." (or "FILE: ..." for an
// empty path) and a message containing `reason`.
inline void require_rejected(const std::string& text, const std::string& path,
                             const std::string& reason) {
    INFO("scene: " << text);
    CHECK_THROWS_AS(impulse::harness::parse_scene(text, test_file), impulse::harness::InputError);
    const std::string message = rejection(text);
    INFO("message: " << message);
    const std::string where = path.empty() ? test_file + ": " : test_file + ": " + path + ": ";
    CHECK(message.rfind(where, 0) == 0);
    CHECK(message.find(reason) != std::string::npos);
}

// Each value of `document` at a JSON pointer that starts with one of
// `prefixes` ("" for all), every leaf and every container above it, replaced
// in turn by each of `replacements`: the loader accepts the result or refuses
// it with an InputError, and nothing else escapes.
inline void require_only_input_errors(const nlohmann::json& document,
                                      const std::vector<std::string>& prefixes,
                                      const std::vector<nlohmann::json>& replacements) {
    const nlohmann::json flat = document.flatten();
    std::vector<std::string> pointers;
    for (const auto& [pointer, value] : flat.items()) {
        bool wanted = false;
        for (const std::string& prefix : prefixes) {
            wanted = wanted || pointer.rfind(prefix, 0) == 0;
        }
        if (!wanted) {
            continue;
        }
        for (std::string p = pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) {
            pointers.push_back(p);
        }
    }
    for (const std::string& pointer : pointers) {
        for (const nlohmann::json& replacement : replacements) {
            nlohmann::json changed = document;
            changed[nlohmann::json::json_pointer(pointer)] = replacement;
            INFO(pointer << " = " << replacement.dump());
            CHECK_NOTHROW(rejection(changed.dump()));
        }
    }
}

} // namespace impulse::test
