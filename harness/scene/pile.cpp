// The "pile" block's generator (pile.h; docs/formats.md, "The pile block").
//
// Every number is produced by a stated sequence of IEEE double operations, so
// another implementation following docs/formats.md gets the same bits.
#include "pile.h"

#include "gas.h"
#include "generated_bodies.h"
#include "trig.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace impulse::harness {

namespace {

// sqrt(2) rounded to the nearest double, written out so that the bound does
// not depend on a library.
constexpr double sqrt2 = 1.4142135623730951;

// lo + (hi - lo) u: lo when the range is empty, whatever u.
double between(double lo, double hi, double u) {
    return lo + (hi - lo) * u;
}

} // namespace

int pile_columns(const PileSpec& spec) {
    return spec.columns > 0 ? spec.columns : gas_lattice_side(spec.count);
}

int pile_rows(const PileSpec& spec) {
    const int k = pile_columns(spec);
    return (spec.count + k - 1) / k;
}

double pile_largest_diameter(const PileSpec& spec) {
    const double circle = 2.0 * spec.size_max;
    return spec.kinds == PileSpec::Kinds::circle ? circle : circle * sqrt2;
}

double pile_lattice_extent(const PileSpec& spec) {
    const double width = static_cast<double>(pile_columns(spec)) * spec.spacing;
    const double height = static_cast<double>(pile_rows(spec)) * spec.spacing;
    return std::max(width / 2.0, 2.0 * height);
}

double pile_extent(const PileSpec& spec) {
    const double width = static_cast<double>(pile_columns(spec)) * spec.spacing;
    const double height = static_cast<double>(pile_rows(spec)) * spec.spacing;
    return std::max(width / 2.0 + spec.wall_thickness, 2.0 * height);
}

SceneBody pile_body(bool circle, double size, double density) {
    SceneBody body;
    body.shape = circle ? make_circle(size) : make_box(size, size);
    const MassProperties properties = mass_properties(body.shape);
    body.mass = density * properties.area;
    body.inertia = body.mass * properties.inertia_per_unit_mass;
    body.rotation = true;
    return body;
}

std::vector<SceneBody> generate_pile(const PileSpec& spec) {
    const int k = pile_columns(spec);
    const double width = static_cast<double>(k) * spec.spacing; // W, the box's inner width
    const double height = static_cast<double>(pile_rows(spec)) * spec.spacing; // H, the lattice's
    const double half = width / 2.0;                                           // exact: a halving
    const double t = spec.wall_thickness / 2.0;

    std::vector<SceneBody> bodies;
    bodies.reserve(static_cast<std::size_t>(spec.count) + 3);
    // The floor's top is y = 0 and it runs under both walls; the walls stand on
    // it, inner faces at x = -W/2 and W/2, 2 H tall (twice the lattice).
    bodies.push_back(static_wall("floor", {0.0, -t}, half + spec.wall_thickness, t));
    bodies.push_back(static_wall("wall-left", {-(half + t), height}, t, height));
    bodies.push_back(static_wall("wall-right", {half + t, height}, t, height));

    SplitMix64 random(spec.seed);
    for (int n = 0; n < spec.count; ++n) {
        // Draws in this order, each one unit() (docs/formats.md): kind (mixed
        // only), size, density, angle (random_angles only).
        bool circle = spec.kinds == PileSpec::Kinds::circle;
        if (spec.kinds == PileSpec::Kinds::mixed) {
            circle = random.unit() < 0.5;
        }
        const double size = between(spec.size_min, spec.size_max, random.unit());
        const double density = between(spec.density_min, spec.density_max, random.unit());
        SceneBody body = pile_body(circle, size, density);
        body.name = "pile-" + std::to_string(n);
        // Row by row from the bottom left, column i fastest; row 0's sites are
        // half a spacing above the floor.
        const int i = n % k;
        const int j = n / k;
        body.position = {-half + spec.spacing * (static_cast<double>(i) + 0.5),
                         spec.spacing * (static_cast<double>(j) + 0.5)};
        if (spec.random_angles) {
            body.angle = pi * (2.0 * random.unit() - 1.0);
        }
        bodies.push_back(std::move(body));
    }
    return bodies;
}

} // namespace impulse::harness
