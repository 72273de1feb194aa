// The "gas" block (docs/formats.md, "The gas block"): read and validated here,
// its bodies made by generate_gas (gas.h).
#include "gas.h"
#include "generated_bodies.h"
#include "scene_reading.h"
#include "shape.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

// Far more than a scale scene needs; a bound keeps a typo from asking for a
// billion bodies.
constexpr long long max_gas_count = 100000;
// 2^53: the largest whole number a JSON reader is sure to hold exactly.
constexpr long long max_gas_seed = 9007199254740992;

const std::vector<std::string> gas_keys = {"count",
                                           "shape",
                                           "mass",
                                           "density",
                                           "spacing",
                                           "max_speed",
                                           "max_angular_speed",
                                           "random_angles",
                                           "seed",
                                           "wall_thickness"};

// The gas's mass and inertia, from mass or density (default 1) as for a body.
void read_gas_mass(const Node& node, GasSpec& gas) {
    const MassProperties shape = mass_properties(gas.shape);
    std::optional<double> mass;
    if (const std::optional<Node> given = optional_member(node, "mass")) {
        mass = read_positive(*given);
    }
    double density = 1.0;
    if (const std::optional<Node> given = optional_member(node, "density")) {
        density = read_positive(*given);
        if (mass) {
            given->fail("give mass or density, not both");
        }
    }
    gas.mass = mass ? *mass : density * shape.area;
    if (!std::isfinite(gas.mass) || !(gas.mass > 0.0)) {
        node.fail("its shape and density give each body a mass of " + number_text(gas.mass) +
                  " kg; it must be finite and > 0");
    }
    gas.inertia = gas.mass * shape.inertia_per_unit_mass;
    if (!std::isfinite(gas.inertia) || !(gas.inertia > 0.0)) {
        node.fail("its shape and mass give each body a moment of inertia of " +
                  number_text(gas.inertia) + " kg m^2; it must be finite and > 0");
    }
}

} // namespace

// "gas": reads and validates the block, then appends its walls and bodies
// (gas.h) after the listed ones. The names it gives must not be taken.
void read_gas(const Node& node, Scene& scene) {
    require_object(node);
    reject_unknown_keys(node, gas_keys);
    GasSpec gas;
    gas.count = static_cast<int>(read_whole(required_member(node, "count"), 1, max_gas_count));
    const Node shape = required_member(node, "shape");
    gas.shape = read_shape(shape);
    // Each body's centre of mass sits on its site, so there is no position to
    // move: only the vertices are recentred.
    if (const std::optional<Vec2> centroid = recentre_on_centroid(gas.shape)) {
        scene.warnings.push_back(centroid_warning(
            scene.file, shape.path(), *centroid,
            "vertices recentred; each gas body's centroid sits on its lattice site"));
    }
    read_gas_mass(node, gas);
    refuse_infinite_weight(node, "each gas body", gas.mass, scene.gravity);
    const Node spacing = required_member(node, "spacing");
    gas.spacing = read_positive(spacing);
    // Closer sites could let two bodies overlap at some angles; the room is
    // checked for overlaps below, but this says what to change.
    const double diameter = 2.0 * circumradius(gas.shape);
    if (!(gas.spacing > diameter)) {
        spacing.fail("must be more than the shape's bounding diameter " + number_text(diameter) +
                     " m (twice its furthest point from the centroid), so that no two bodies "
                     "overlap at any angle, got " +
                     number_text(gas.spacing));
    }
    gas.max_speed = read_non_negative(required_member(node, "max_speed"));
    if (const std::optional<Node> given = optional_member(node, "max_angular_speed")) {
        gas.max_angular_speed = read_non_negative(*given);
    }
    gas.random_angles = read_bool_or(node, "random_angles", false);
    if (const std::optional<Node> given = optional_member(node, "seed")) {
        gas.seed = static_cast<std::uint64_t>(read_whole(*given, 0, max_gas_seed));
    }
    gas.wall_thickness = read_positive_or(node, "wall_thickness", gas.wall_thickness);
    const double side = static_cast<double>(gas_lattice_side(gas.count)) * gas.spacing;
    if (!std::isfinite(side)) {
        spacing.fail("gives a room " + number_text(side) + " m wide; it must be finite");
    }
    if (!std::isfinite(side + 2.0 * gas.wall_thickness)) {
        node.member("wall_thickness")
            .fail("gives a room " + number_text(side + 2.0 * gas.wall_thickness) +
                  " m wide with its walls; it must be finite");
    }
    // The room reaches side / 2 + wall_thickness from the origin (its walls,
    // docs/formats.md, the gas block's step 2).
    const bool lattice = !(side / 2.0 <= resolvable_extent(scene.solver.contact_tolerance));
    refuse_unresolvable_extent(
        node, lattice ? "spacing" : "wall_thickness", "a room", side / 2.0 + gas.wall_thickness,
        scene.solver.contact_tolerance,
        lattice ? "use a smaller spacing or count, or a larger solver.contact_tolerance"
                : "use thinner walls or a larger solver.contact_tolerance");
    for (std::size_t i = 0; i < scene.listed_bodies; ++i) {
        if (is_generated_name(scene.bodies[i].name,
                              {"wall-bottom", "wall-top", "wall-left", "wall-right"}, "gas-",
                              gas.count)) {
            node.fail("makes a body named \"" + scene.bodies[i].name +
                      "\", which is already the name of bodies[" + std::to_string(i) +
                      "]; body names must be unique (the gas block's are wall-bottom, wall-top, "
                      "wall-left, wall-right and gas-0 to gas-" +
                      std::to_string(gas.count - 1) + ")");
        }
    }
    std::vector<SceneBody> made = generate_gas(gas);
    scene.bodies.insert(scene.bodies.end(), std::make_move_iterator(made.begin()),
                        std::make_move_iterator(made.end()));
    scene.gas = gas;
}

} // namespace impulse::harness::scene_reading
