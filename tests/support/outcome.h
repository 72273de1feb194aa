// Asserting on what a run of the real tool did (test::Outcome of tool.h):
// shared by the tests that drive projects, engines and verbs end to end.
#pragma once

#include "tool.h"

#include <algorithm>
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

// The line after the first line of `text` that begins, after its spaces,
// with `start`, without its leading spaces; "" when there is none.
inline std::string line_after(const std::string& text, const std::string& start) {
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::size_t first = text.find_first_not_of(' ', at);
        if (first < end && text.compare(first, start.size(), start) == 0 && end < text.size()) {
            const std::size_t next_end = std::min(text.find('\n', end + 1), text.size());
            const std::size_t next = std::min(text.find_first_not_of(' ', end + 1), next_end);
            return text.substr(next, next_end - next);
        }
        at = end + 1;
    }
    return "";
}

} // namespace impulse::test
