// A generated block's box (the gas's room, the pile's box) must lie where
// positions resolve the contact tolerance (docs/formats.md, "The pile
// block", spacing). One rule for both blocks.
#include "scene_reading.h"

#include <string>

namespace impulse::harness::scene_reading {

namespace {

// 2^48: a double holds a coordinate x to within x 2^-52, so within this many
// contact tolerances of the origin every position is held to 1/16 of the
// tolerance or better.
constexpr double contact_tolerances_across = 281474976710656.0;

} // namespace

double resolvable_extent(double contact_tolerance) {
    return contact_tolerances_across * contact_tolerance;
}

// Further out, touching is decided by rounding: behind 1e17 m of wall a
// wall's face moves by metres, and a box 1e154 m wide squares to infinity in
// the narrow phase, so the run stops with NaN positions after writing a
// partial trajectory. Refused at load, before anything runs.
void refuse_unresolvable_extent(const Node& block, const std::string& key, const std::string& box,
                                double extent, double contact_tolerance, const std::string& cure) {
    const double limit = resolvable_extent(contact_tolerance);
    if (extent <= limit) {
        return;
    }
    // The key is named even when absent: its default is what to change then.
    json_fields::fail(json_member_path(block.path(), key),
                      "gives " + box + " reaching " + number_text(extent) +
                          " m from the origin, walls included, but positions resolve the contact "
                          "tolerance only within " +
                          number_text(limit) + " m of it (2^48 times solver.contact_tolerance " +
                          number_text(contact_tolerance) +
                          " m: a double holds x to within x 2^-52); " + cure);
}

} // namespace impulse::harness::scene_reading
