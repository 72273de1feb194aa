// The "pile" block's generator: bodies of mixed sizes and densities at rest on
// a lattice in an open box of three static walls, for the dense-contact scale
// scenes (docs/formats.md, "The pile block", states the rule exactly).
//
// Like the gas block, the same block gives the same bodies, bit for bit, on
// every platform: the draws come from gas.h's SplitMix64, mapped to doubles by
// stated IEEE operations, and no library trigonometry is used.
#pragma once

#include "scene.h"

#include <vector>

namespace impulse::harness {

// The lattice's columns: spec.columns, or the smallest k with k * k >= count.
int pile_columns(const PileSpec& spec);
// Its rows: ceil(count / columns), in integers.
int pile_rows(const PileSpec& spec);

// The bounding diameter of the largest body the block can draw: 2 size_max
// for circles, 2 sqrt(2) size_max when boxes may be drawn (a square's
// diagonal). Sites further apart than this never overlap at any angle.
double pile_largest_diameter(const PileSpec& spec);

// How far from the origin the box reaches: the inner half width W / 2 and
// the walls' height 2 H (the lattice), and with the walls, max(W / 2 +
// wall_thickness, 2 H). Computed as generate_pile computes the walls.
double pile_lattice_extent(const PileSpec& spec);
double pile_extent(const PileSpec& spec);

// One body of the block at the origin, at rest: a circle of radius `size` or
// a square of half side `size`, mass = density x area, inertia from the shape.
SceneBody pile_body(bool circle, double size, double density);

// The bodies the block stands for: floor, wall-left, wall-right, then
// pile-0 ... pile-(count - 1). The caller has validated the spec.
std::vector<SceneBody> generate_pile(const PileSpec& spec);

} // namespace impulse::harness
