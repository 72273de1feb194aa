// Asserting on what a run of the real tool did (test::Outcome of tool.h):
// shared by the tests that drive projects, engines and verbs end to end.
#pragma once

#include "tool.h"

#include <catch2/catch.hpp>
#include <string>

namespace impulse::test {

// The run exited (no signal) with `code`; its output shown when it did not.
inline void require_exit(const Outcome& o, int code) {
    INFO("stdout:\n" << o.out << "stderr:\n" << o.err);
    REQUIRE(o.exited);
    REQUIRE(o.exit_code == code);
}

inline bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

} // namespace impulse::test
