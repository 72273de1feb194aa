// A generated block's box (the gas's room, the pile's box), and every listed
// body, must lie where positions resolve the contact tolerance
// (docs/formats.md, "The pile block", spacing). One rule for all of them.
#include "contact_candidates.h"
#include "scene_reading.h"

#include <algorithm>
#include <cmath>
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

namespace {

// The clause every refusal below shares: "positions resolve ... of it (why); ".
std::string resolvable_clause(double contact_tolerance) {
    return "positions resolve the contact tolerance only within " +
           number_text(resolvable_extent(contact_tolerance)) +
           " m of it (2^48 times solver.contact_tolerance " + number_text(contact_tolerance) +
           " m: a double holds x to within x 2^-52); ";
}

} // namespace

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
                          " m from the origin, walls included, but " +
                          resolvable_clause(contact_tolerance) + cure);
}

// A polygon's vertices, by the same rule, before it is recentred: given 1e8 m
// from its body's origin (found by an outside review), a 0.16 m triangle's
// corners are held only to 1.5e-8 m, and recentring would carry the body
// itself 1e8 m out, refused there at a position the file never gave.
void refuse_unresolvable_vertices(const Node& node, const Polygon& polygon,
                                  double contact_tolerance) {
    double reach = 0.0;
    for (int i = 0; i < polygon.count; ++i) {
        const Vec2 v = polygon.vertices[static_cast<std::size_t>(i)];
        reach = std::max({reach, std::fabs(v.x), std::fabs(v.y)});
    }
    const double limit = resolvable_extent(contact_tolerance);
    if (reach <= limit) {
        return;
    }
    node.fail("has vertices " + number_text(reach) + " m from the body's origin, but " +
              resolvable_clause(contact_tolerance) +
              "give the vertices about the polygon's own centre (that centre in the body's "
              "position), or raise solver.contact_tolerance");
}

// Listed bodies, by the same rule: found by an outside review, the canonical
// pile moved 1e12 m from the origin ended 2.3 cm deep, and moved 1e15 m
// (where positions resolve to 0.125 m) it ran with every expectation met.
// A body's reach is its centre's larger coordinate plus its farthest vertex
// (or radius); the path named is its position.
void refuse_unresolvable_bodies(const Node& listed, const Scene& scene) {
    const double limit = resolvable_extent(scene.solver.contact_tolerance);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& body = scene.bodies[i];
        const double reach = std::max(std::fabs(body.position.x), std::fabs(body.position.y)) +
                             rotation_radius(body.shape);
        if (reach <= limit) {
            continue;
        }
        listed.element(i)
            .member("position")
            .fail("puts the body " + number_text(reach) + " m from the origin, but " +
                  resolvable_clause(scene.solver.contact_tolerance) +
                  "move the scene nearer the origin, or raise solver.contact_tolerance");
    }
}

} // namespace impulse::harness::scene_reading
