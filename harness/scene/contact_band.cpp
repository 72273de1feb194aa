#include "contact_band.h"

#include "generated_bodies.h"
#include "input_error.h"
#include "text.h"
#include "tunnelling.h"

#include <cstddef>
#include <limits>
#include <string>

namespace impulse::harness {

namespace {

// The walls a gas or pile block makes (generated_bodies.h): the block's
// wall_thickness sets their inradius.
bool is_block_wall(const Scene& scene, std::size_t index) {
    if (index < scene.listed_bodies) {
        return false;
    }
    const std::string& name = scene.bodies[index].name;
    return name == "floor" || name.rfind("wall-", 0) == 0;
}

} // namespace

// Why the smallest inradius r: every body contains the disc of its inradius
// about its centre, so a pair passes through each other's middle only at a
// depth of at least r_a + r_b >= 2 r. The engine holds overlaps to within d
// (time-stepping's guard; the event model's collision search), and a pair
// counts as touching within d. With d < r, touching means nearer than half
// the thinnest body's thickness, and an overlap the engine tolerates stays
// at most half of what would put a body past another's middle, where its
// contact normal would push it through instead of out. Beyond it (d = 1e300)
// every pair of the scene counts as touching, and a wall 1e-300 m thick is
// passed by any overlap the engine allows.
void refuse_contact_band_beyond_bodies(const Scene& scene) {
    const double d = scene.solver.contact_tolerance;
    double thinnest = std::numeric_limits<double>::infinity();
    std::size_t body = 0;
    double thinnest_wall = std::numeric_limits<double>::infinity();
    std::size_t wall = 0;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const double r = inradius(scene.bodies[i].shape);
        double& least = is_block_wall(scene, i) ? thinnest_wall : thinnest;
        if (r < least) {
            least = r;
            (is_block_wall(scene, i) ? wall : body) = i;
        }
    }
    const auto describe = [&](std::size_t i, double r) {
        return body_reference(scene, i) + ", whose inradius (half its thickness) is " +
               sentence_number(r) + " m";
    };
    if (!(thinnest > 0.0) && body < scene.listed_bodies) {
        // No band is thin enough: the shape itself is the fault (a triangle
        // 1e-15 m tall had an inradius of -0 m, and the sentence asked for a
        // tolerance below it).
        throw InputError(scene.file, "bodies[" + std::to_string(body) + "].shape",
                         "has an inradius (half its thickness) of " + sentence_number(thinnest) +
                             " m: no thickness to double precision, so no contact tolerance is "
                             "thinner than it; make the shape thicker");
    }
    if (!(d < thinnest)) {
        throw InputError(scene.file, "solver.contact_tolerance",
                         "is " + sentence_number(d) +
                             " m, but the band in which bodies count as touching must be "
                             "thinner than the thinnest body, " +
                             describe(body, thinnest) +
                             ": wider, pairs far apart count as touching and an overlap the "
                             "engine tolerates can carry a body past another's middle; use a "
                             "solver.contact_tolerance below " +
                             sentence_number(thinnest) + " m (the default is 1e-9 m)");
    }
    if (!(d < thinnest_wall)) {
        const std::string block = scene.pile ? "pile" : "gas";
        throw InputError(scene.file, block + ".wall_thickness",
                         "makes " + describe(wall, thinnest_wall) +
                             ", not more than solver.contact_tolerance " + sentence_number(d) +
                             " m, the band in which bodies count as touching: an overlap the "
                             "engine tolerates could carry a body through the wall; use walls "
                             "thicker than " +
                             sentence_number(2.0 * d) + " m or a smaller solver.contact_tolerance");
    }
}

} // namespace impulse::harness
