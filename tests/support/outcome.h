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

// A refusal as the user meets it where no file or JSON path is asserted:
// exit 2, one line on stderr, no abort and no stack trace.
inline void require_one_sentence(const Outcome& o) {
    INFO(o.err);
    REQUIRE(o.exited);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find('\n') == o.err.size() - 1);
    CHECK(o.err.find("internal error") == std::string::npos);
}

inline bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

} // namespace impulse::test
