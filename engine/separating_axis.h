// A separating axis of two convex shapes (used by the sweep's bounds,
// docs/engine.md, "Tunnelling"): the direction along which their gap is
// largest among the candidates separation() itself takes, with that gap and,
// when it is a face normal, whose face.
#pragma once

#include "rotation.h"
#include "shape.h"

#include <limits>

namespace impulse {

// max over the shape's points p of d . p.
double support(const Shape& shape, const Transform& xf, Vec2 d);

// When n is a face normal, which body's face (Face::a, Face::b) and which
// face: that axis turns with its body, and a bound can follow it.
enum class Face { none, a, b };

// A direction n (unit, toward a) and the pair's gap along it: the least n . p
// over a minus the greatest n . q over b. For convex shapes the signed distance
// is the largest such gap over all directions, so any n's gap bounds it from
// below, and bounds separation() from below where that is negative (then it
// is minus the depth, the signed distance).
struct Axis {
    Vec2 normal;
    double gap = -std::numeric_limits<double>::infinity();
    Face owner = Face::none; // whose face normal n is, if any
    int face = -1;
};

// The candidates among which separation() finds its value: every polygon
// face normal and, for a circle against a polygon, the line from each vertex
// to the centre (the vertex regions); for two circles, the line of centres.
// So the best gap is separation() up to rounding.
Axis separating_axis(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb);

} // namespace impulse
