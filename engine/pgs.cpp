#include "pgs.h"

namespace impulse {

PgsResult solve_pgs(const World&, const std::vector<ContactPoint>&, const std::vector<double>&,
                    std::vector<double>&, const PgsSettings&, PgsScratch&) {
    return {}; // interface only: engine/pgs.cpp is written by its owner
}

} // namespace impulse
