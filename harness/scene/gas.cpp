// The "gas" block's generator (gas.h; docs/formats.md, "The gas block").
//
// Every number is produced by a stated sequence of IEEE double operations, so
// another implementation following docs/formats.md gets the same bits.
#include "gas.h"

#include "generated_bodies.h"
#include "trig.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

namespace impulse::harness {

namespace {

// u in [0, 1) to 2 u - 1 in [-1, 1). Exact: 2 u is a multiple of 2^-52 below
// 2, and subtracting 1 from it needs no rounding.
double symmetric(double u) {
    return 2.0 * u - 1.0;
}

} // namespace

std::uint64_t SplitMix64::next() {
    state_ += 0x9e3779b97f4a7c15u;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

double SplitMix64::unit() {
    return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

int gas_lattice_side(int count) {
    int k = 0;
    while (static_cast<long long>(k) * k < count) {
        ++k;
    }
    return k;
}

std::vector<SceneBody> generate_gas(const GasSpec& gas) {
    const int k = gas_lattice_side(gas.count);
    const double side = static_cast<double>(k) * gas.spacing; // L, the room's inner side
    const double h = side / 2.0;                              // exact: a halving
    const double t = gas.wall_thickness / 2.0;
    const double centre = h + t; // of each wall, from the origin

    std::vector<SceneBody> bodies;
    bodies.reserve(static_cast<std::size_t>(gas.count) + 4);
    // The side walls span the outer height, h + w each way, so the corners are
    // closed; they overlap the bottom and top walls there, which static bodies may.
    bodies.push_back(static_wall("wall-bottom", {0.0, -centre}, h, t));
    bodies.push_back(static_wall("wall-top", {0.0, centre}, h, t));
    bodies.push_back(static_wall("wall-left", {-centre, 0.0}, t, h + gas.wall_thickness));
    bodies.push_back(static_wall("wall-right", {centre, 0.0}, t, h + gas.wall_thickness));

    SplitMix64 random(gas.seed);
    for (int n = 0; n < gas.count; ++n) {
        SceneBody body;
        body.name = "gas-" + std::to_string(n);
        body.shape = gas.shape;
        body.mass = gas.mass;
        body.inertia = gas.inertia;
        body.rotation = true;
        // Row by row from the bottom left, column i fastest.
        const int i = n % k;
        const int j = n / k;
        body.position = {-h + gas.spacing * (static_cast<double>(i) + 0.5),
                         -h + gas.spacing * (static_cast<double>(j) + 0.5)};
        // Uniform in the disc by rejection. The test is on the unit square's
        // values, not the scaled ones, so whether a draw is kept does not depend
        // on max_speed's rounding (the same seed gives the same directions at
        // any speed) and cannot overflow.
        double a = 0.0;
        double b = 0.0;
        do {
            a = symmetric(random.unit());
            b = symmetric(random.unit());
        } while (!(a * a + b * b <= 1.0));
        body.velocity = {gas.max_speed * a, gas.max_speed * b};
        if (gas.random_angles) {
            body.angle = pi * symmetric(random.unit());
        }
        if (gas.max_angular_speed > 0.0) {
            body.angular_velocity = gas.max_angular_speed * symmetric(random.unit());
        }
        bodies.push_back(std::move(body));
    }
    return bodies;
}

} // namespace impulse::harness
