// The "pile" block (docs/formats.md, "The pile block"): read and validated here,
// its bodies made by generate_pile (pile.h).
#include "scene_pile_block.h"

#include "generated_bodies.h"
#include "manifold.h"
#include "overlap.h"
#include "pile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

// The gas block's bounds (scene_gas_block.cpp says why).
constexpr long long max_pile_count = 100000;
constexpr long long max_pile_seed = 9007199254740992;
// 2^960: 2^-64 of the largest double (check_energy says why).
constexpr double energy_limit = 0x1p960;

const std::vector<std::string> pile_keys = {"count",         "shape",   "size",
                                            "density",       "spacing", "columns",
                                            "random_angles", "seed",    "wall_thickness"};

PileSpec::Kinds read_kinds(const Node& node) {
    const std::vector<std::pair<std::string, PileSpec::Kinds>> names = {
        {"circle", PileSpec::Kinds::circle},
        {"box", PileSpec::Kinds::box},
        {"mixed", PileSpec::Kinds::mixed}};
    for (const auto& [name, kinds] : names) {
        if (node.json().is_string() && node.json().get<std::string>() == name) {
            return kinds;
        }
    }
    node.fail("must be one of \"circle\", \"box\" or \"mixed\", got " + shown(node));
}

// [min, max]: two positive numbers, min <= max.
std::pair<double, double> read_range(const Node& node, const std::string& unit) {
    require_array(node);
    if (node.json().size() != 2) {
        node.fail("must be [min, max] in " + unit + ", got " + std::to_string(node.json().size()) +
                  " values");
    }
    const double lo = read_positive(node.element(0));
    const double hi = read_positive(node.element(1));
    if (!(lo <= hi)) {
        node.fail("must be [min, max] with min <= max, got [" + number_text(lo) + ", " +
                  number_text(hi) + "]");
    }
    return {lo, hi};
}

// The spacing wide enough that no two bodies can overlap at any angle.
void check_spacing(const Node& node, const PileSpec& pile) {
    const double diameter = pile_largest_diameter(pile);
    if (!(pile.spacing > diameter)) {
        node.member("spacing").fail(
            "must be more than the largest body's bounding diameter " + number_text(diameter) +
            " m (twice size[1], times sqrt(2) when boxes are drawn), so that no two bodies "
            "overlap at any angle, got " +
            number_text(pile.spacing));
    }
}

// The box within reach of the contact tolerance (resolvable_extent.cpp),
// blamed on the walls when the lattice alone is within it.
void check_extent(const Node& node, const PileSpec& pile, double contact_tolerance) {
    const bool lattice = !(pile_lattice_extent(pile) <= resolvable_extent(contact_tolerance));
    refuse_unresolvable_extent(
        node, lattice ? "spacing" : "wall_thickness", "a box", pile_extent(pile), contact_tolerance,
        lattice ? "use a smaller spacing or count (or more columns for a tall pile), or a larger "
                  "solver.contact_tolerance"
                : "use thinner walls or a larger solver.contact_tolerance");
}

// What is wrong with a body's mass or moment of inertia: both must be finite
// and > 0.
std::optional<std::string> mass_problem(const SceneBody& body) {
    if (!(body.mass > 0.0 && std::isfinite(body.mass))) {
        return "a mass of " + number_text(body.mass) + " kg";
    }
    if (!(body.inertia > 0.0 && std::isfinite(body.inertia))) {
        return "a moment of inertia of " + number_text(body.inertia) + " kg m^2";
    }
    return std::nullopt;
}

// Mass and inertia grow with size and with density, so the lightest body the
// block can draw is (size[0], density[0]) and the heaviest (size[1],
// density[1]), of each kind it draws: when those are finite and > 0, every
// body is. The key blamed is the size when a body that size fails even at
// 1 kg/m^2 (its area or inertia per unit mass underflows or overflows), else
// the density.
void check_masses(const Node& node, const PileSpec& pile) {
    const auto check = [&](bool circle, std::size_t end, double size, double density) {
        const std::optional<std::string> problem = mass_problem(pile_body(circle, size, density));
        if (!problem) {
            return;
        }
        const bool shape = mass_problem(pile_body(circle, size, 1.0)).has_value();
        const std::string kind = circle ? "circle" : "square";
        const std::string which = end == 0 ? "lightest" : "heaviest";
        node.member(shape ? "size" : "density")
            .element(end)
            .fail("gives the " + which + " " + kind + " the block can draw (size " +
                  number_text(size) + " m, density " + number_text(density) + " kg/m^2) " +
                  *problem + "; a body's mass and moment of inertia must be finite and > 0, so " +
                  (end == 0 ? "a larger" : "a smaller") + " value is needed");
    };
    for (const bool circle : {true, false}) {
        const bool drawn = pile.kinds == PileSpec::Kinds::mixed ||
                           (pile.kinds == PileSpec::Kinds::circle) == circle;
        if (drawn) {
            check(circle, 0, pile.size_min, pile.density_min);
            check(circle, 1, pile.size_max, pile.density_max);
        }
    }
}

// The energies the gate sums over a pile (energy-non-increasing, at-rest:
// sum m v^2 / 2 + I w^2 / 2 - m g . x) stay finite with room to spare. The
// bodies start at rest, and every position the box allows lies within its
// extent L of the origin; no collision adds energy, so each body's energy
// stays within m |g| L of its start and every sum within count m_max |g| L
// (m_max the heaviest body the block can draw). That must be at most 2^-64 of
// the largest double: rtol x scale and the sums over frames then stay finite
// for any rtol up to 2^60. Density 1e306 passed the mass check and every
// energy was inf (the gate then failed with "expected 0, got 0"). Blamed on
// density[1] unless the pile is too heavy even at 1 kg/m^2: then gravity.
void check_energy(const Node& node, const PileSpec& pile, Vec2 gravity) {
    // hypot, not length: |g| beyond 1e154 would square to inf.
    const double g = std::hypot(gravity.x, gravity.y);
    const auto bound = [&](double density) {
        double heaviest = 0.0;
        for (const bool circle : {true, false}) {
            const bool drawn = pile.kinds == PileSpec::Kinds::mixed ||
                               (pile.kinds == PileSpec::Kinds::circle) == circle;
            if (drawn) {
                heaviest = std::max(heaviest, pile_body(circle, pile.size_max, density).mass);
            }
        }
        return static_cast<double>(pile.count) * heaviest * g * pile_extent(pile);
    };
    const double energy = bound(pile.density_max);
    if (energy <= energy_limit) {
        return;
    }
    const bool density = bound(1.0) <= energy_limit;
    const std::string sentence =
        "gives the pile an energy scale of " + number_text(energy) +
        " J (count x the heaviest body's mass x |g| x the box's reach " +
        number_text(pile_extent(pile)) +
        " m: what its fall can release), but the energies the gate sums must stay within "
        "2^-64 of the largest double, " +
        number_text(energy_limit) + " J, so that they and rtol times them are finite; " +
        (density ? "use a smaller density[1]" : "use a smaller gravity");
    if (density) {
        node.member("density").element(1).fail(sentence);
    }
    json_fields::fail("gravity", sentence);
}

// A listed body in the pile's way. The loader's overlap check would name it
// at "gas", the gas block's path; here the sentence names the pile. Listed
// bodies are few, so every pair with one is tested: O(listed x count).
void reject_listed_overlaps(const Node& node, const Scene& scene,
                            const std::vector<SceneBody>& made) {
    const std::vector<Transform> listed = initial_poses(scene.bodies);
    const std::vector<Transform> poses = initial_poses(made);
    for (std::size_t i = 0; i < scene.listed_bodies; ++i) {
        for (std::size_t n = 0; n < made.size(); ++n) {
            if (scene.bodies[i].is_static && made[n].is_static) {
                continue;
            }
            const double gap =
                separation(scene.bodies[i].shape, listed[i], made[n].shape, poses[n]);
            if (gap < 0.0) {
                node.fail("makes '" + made[n].name + "', which overlaps bodies[" +
                          std::to_string(i) + "] '" + scene.bodies[i].name + "' at t = 0 by " +
                          number_text(-gap) + " m; move that body out of the pile's box");
            }
        }
    }
}

} // namespace

void read_pile(const Node& node, Scene& scene) {
    require_object(node);
    reject_unknown_keys(node, pile_keys);
    if (scene.gas) {
        node.fail("a scene has a gas block or a pile block, not both (both name walls "
                  "wall-left and wall-right)");
    }
    PileSpec pile;
    pile.count = static_cast<int>(read_whole(required_member(node, "count"), 1, max_pile_count));
    pile.kinds = read_kinds(required_member(node, "shape"));
    std::tie(pile.size_min, pile.size_max) = read_range(required_member(node, "size"), "m");
    if (const std::optional<Node> density = optional_member(node, "density")) {
        std::tie(pile.density_min, pile.density_max) = read_range(*density, "kg/m^2");
    }
    pile.spacing = read_positive(required_member(node, "spacing"));
    if (const std::optional<Node> columns = optional_member(node, "columns")) {
        pile.columns = static_cast<int>(read_whole(*columns, 1, max_pile_count));
    }
    pile.random_angles = read_bool_or(node, "random_angles", false);
    if (const std::optional<Node> seed = optional_member(node, "seed")) {
        pile.seed = static_cast<std::uint64_t>(read_whole(*seed, 0, max_pile_seed));
    }
    pile.wall_thickness = read_positive_or(node, "wall_thickness", pile.wall_thickness);
    check_spacing(node, pile);
    check_extent(node, pile, scene.solver.contact_tolerance);
    check_masses(node, pile);
    check_energy(node, pile, scene.gravity);
    for (std::size_t i = 0; i < scene.listed_bodies; ++i) {
        if (is_generated_name(scene.bodies[i].name, {"floor", "wall-left", "wall-right"}, "pile-",
                              pile.count)) {
            node.fail("makes a body named \"" + scene.bodies[i].name +
                      "\", which is already the name of bodies[" + std::to_string(i) +
                      "]; body names must be unique (the pile block's are floor, wall-left, "
                      "wall-right and pile-0 to pile-" +
                      std::to_string(pile.count - 1) + ")");
        }
    }
    std::vector<SceneBody> made = generate_pile(pile);
    reject_listed_overlaps(node, scene, made);
    scene.bodies.insert(scene.bodies.end(), std::make_move_iterator(made.begin()),
                        std::make_move_iterator(made.end()));
    scene.pile = pile;
}

} // namespace impulse::harness::scene_reading
