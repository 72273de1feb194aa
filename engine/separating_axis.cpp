#include "separating_axis.h"

#include <cmath>

namespace impulse {

namespace {

void consider_axis(Axis& best, Vec2 n, const Shape& a, const Transform& xa, const Shape& b,
                   const Transform& xb, Face owner = Face::none, int face = -1) {
    const double gap = -support(a, xa, -n) - support(b, xb, n);
    if (gap > best.gap) {
        best = {n, gap, owner, face};
    }
}

} // namespace

double support(const Shape& shape, const Transform& xf, Vec2 d) {
    if (shape.type == ShapeType::circle) {
        return dot(d, xf.p) + shape.radius * length(d);
    }
    double best = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < shape.polygon.count; ++i) {
        const double s = dot(d, apply(xf, shape.polygon.vertices[i]));
        best = s > best ? s : best;
    }
    return best;
}

Axis separating_axis(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
    Axis best;
    if (a.type == ShapeType::polygon) {
        for (int i = 0; i < a.polygon.count; ++i) {
            consider_axis(best, -rotate(xa.q, a.polygon.normals[i]), a, xa, b, xb, Face::a, i);
        }
    }
    if (b.type == ShapeType::polygon) {
        for (int i = 0; i < b.polygon.count; ++i) {
            consider_axis(best, rotate(xb.q, b.polygon.normals[i]), a, xa, b, xb, Face::b, i);
        }
    }
    const auto towards = [](Vec2 from, Vec2 to) {
        const Vec2 d = to - from;
        const double norm = length(d);
        return norm > 0.0 ? (1.0 / norm) * d : Vec2{0.0, 1.0};
    };
    if (a.type == ShapeType::circle && b.type == ShapeType::circle) {
        consider_axis(best, towards(xb.p, xa.p), a, xa, b, xb);
    } else if (a.type == ShapeType::circle) {
        for (int i = 0; i < b.polygon.count; ++i) {
            consider_axis(best, towards(apply(xb, b.polygon.vertices[i]), xa.p), a, xa, b, xb);
        }
    } else if (b.type == ShapeType::circle) {
        for (int i = 0; i < a.polygon.count; ++i) {
            consider_axis(best, towards(xb.p, apply(xa, a.polygon.vertices[i])), a, xa, b, xb);
        }
    }
    return best;
}

} // namespace impulse
