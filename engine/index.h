#pragma once

#include <cstddef>

namespace impulse {

// The solvers and the island search count bodies and points with int (the
// sizes the problem statements use); their scratch lives in std::vector.
inline std::size_t at(int i) {
    return static_cast<std::size_t>(i);
}

} // namespace impulse
