#include "conservative_advancement.h"

#include "integrator.h"
#include "separating_axis.h"
#include "shape.h"

#include <array>
#include <cmath>
#include <limits>

namespace impulse {

namespace {

constexpr double never = std::numeric_limits<double>::infinity();

// The acceleration advance_all() integrates body i with: gravity, or with
// solver.resting gravity plus this interval's contact forces.
Acceleration acceleration_of(const World& world, std::size_t i) {
    if (world.resting_contacts.any) {
        return world.resting_contacts.accelerations[i];
    }
    return {world.gravity, 0.0};
}

// The step samples a body where advance(start, u) puts it, so what bounds the
// motion between samples is the derivative in u of that function, taken from
// engine/integrator.cpp. Under a constant acceleration a (gravity, plus
// resting contact forces) and angular acceleration alpha (0 without resting
// contact, when omega is constant), each integrator moves the centre of mass
// to x0 + u v0 + (c / 2) u^2 a, at the rate v0 + c u a, and turns the body
// likewise, at the rate omega0 + c u alpha:
//   euler:            x0 + u v0                    c = 0 (the position ignores a)
//   symplectic-euler: x0 + u (v0 + u a)            c = 2
//   verlet:           x0 + u v0 + (u^2 / 2) a      c = 1
//   rk4:              x0 + (u / 6) (6 v0 + 3 u a)  c = 1
// With a = 0 every integrator takes the uniform-motion branch, x0 + u v0.
double rate_factor(Integrator integrator) {
    switch (integrator) {
    case Integrator::euler:
        return 0.0;
    case Integrator::symplectic_euler:
        return 2.0;
    case Integrator::verlet:
    case Integrator::rk4:
        return 1.0;
    }
    return 2.0; // the largest: conservative
}

// How far a point of the body's surface moves per radian it turns: its
// largest distance from the centre of mass. A circle's surface is the same set
// at every angle, so turning moves none of it.
double turning_radius(const Body& body) {
    if (!body.rotates() || body.shape.type == ShapeType::circle) {
        return 0.0;
    }
    double largest = 0.0;
    const Polygon& polygon = body.shape.polygon;
    for (int i = 0; i < polygon.count; ++i) {
        const double r2 = length_squared(polygon.vertices[i]);
        largest = r2 > largest ? r2 : largest;
    }
    return std::sqrt(largest);
}

} // namespace

SweepMotion sweep_motion_of(const World& world, const Configuration& start, const Pair& pair) {
    const std::size_t ia = static_cast<std::size_t>(pair.a);
    const std::size_t ib = static_cast<std::size_t>(pair.b);
    const Body& a = world.bodies[ia];
    const Body& b = world.bodies[ib];
    SweepMotion m;
    m.c = rate_factor(world.solver.integrator);
    const Acceleration acc_a = acceleration_of(world, ia);
    m.radius_a = turning_radius(a);
    m.omega_a = start[ia].angular_velocity;
    m.alpha_a = acc_a.angular;
    // a is dynamic (world.h, Pair); a static b is never advanced.
    if (b.is_static()) {
        m.w0 = start[ia].velocity;
        m.a_rel = acc_a.linear;
        return m;
    }
    const Acceleration acc_b = acceleration_of(world, ib);
    m.w0 = start[ia].velocity - start[ib].velocity;
    m.a_rel = acc_a.linear - acc_b.linear;
    m.radius_b = turning_radius(b);
    m.omega_b = start[ib].angular_velocity;
    m.alpha_b = acc_b.angular;
    return m;
}

namespace {

// The smallest d > 0 with a2 d^2 + b1 d >= m (m > 0), or never. Written to
// avoid cancellation: the root 2 m / (b1 + sqrt(b1^2 + 4 a2 m)) when b1 > 0.
double first_reach(double a2, double b1, double m) {
    if (b1 > 0.0) {
        const double discriminant = b1 * b1 + 4.0 * a2 * m;
        return discriminant < 0.0 ? never : 2.0 * m / (b1 + std::sqrt(discriminant));
    }
    if (a2 > 0.0) {
        return (std::sqrt(b1 * b1 + 4.0 * a2 * m) - b1) / (2.0 * a2);
    }
    return never;
}

// The first d in (0, limit] at which m + b1 d + (b2 / 2) d^2 - (j / 6) d^3
// reaches 0 (m > 0, j >= 0), or never. The cubic is split where its slope is
// 0, so each stretch is monotone; the first stretch that ends at or below 0
// holds the root, found by bisection keeping the end where the cubic is still
// positive: the answer is never past the root.
double first_cubic_reach(double m, double b1, double b2, double j, double limit) {
    const auto value = [&](double d) { return m + d * (b1 + d * (0.5 * b2 - d * j / 6.0)); };
    std::array<double, 3> ends{limit, limit, limit};
    // The slope b1 + b2 d - (j / 2) d^2 is 0 at (b2 -+ sqrt(b2^2 + 2 j b1)) / j,
    // taken in the form that does not cancel: with q = b2 + sign(b2) sqrt(...)
    // the roots are q / j and -2 b1 / q. The difference form lost the first
    // one to rounding when j was tiny (a box closing but slowing, turning at
    // 1e-6 rad/s: the stretch was taken for monotone, the root missed, and the
    // box went 3e-4 m into a ceiling; an outside review).
    if (j > 0.0) {
        const double discriminant = b2 * b2 + 2.0 * j * b1;
        if (discriminant >= 0.0) {
            const double root = std::sqrt(discriminant);
            const double q = b2 >= 0.0 ? b2 + root : b2 - root;
            if (q != 0.0) {
                const double r1 = q / j;
                const double r2 = -2.0 * b1 / q;
                ends[0] = r1 < r2 ? r1 : r2;
                ends[1] = r1 < r2 ? r2 : r1;
            }
        }
    } else if (b2 != 0.0) {
        ends[0] = -b1 / b2;
    }
    double lo = 0.0;
    for (double hi : ends) {
        if (!(hi > lo) || !(hi <= limit)) {
            continue;
        }
        if (value(hi) > 0.0) {
            lo = hi;
            continue;
        }
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (lo + hi);
            (value(mid) > 0.0 ? lo : hi) = mid;
        }
        return lo;
    }
    return never;
}

// The points whose motion bounds a body's side of the gap along a fixed n: a
// polygon's vertices, or a circle's centre with its radius as the offset. Each
// point's offset from the centre of mass, taken along n, the rate at which
// turning changes that (omega n . perp(R r)), and its second derivative
// (theta'' n . perp(R r) - omega^2 n . R r, theta'' = c alpha), at the sample.
struct SidePoint {
    double offset = 0.0;
    double rate = 0.0;
    double curvature = 0.0;
};

int side_points(const Shape& shape, Rotation q, double omega, double turn_acceleration, Vec2 n,
                double sign, std::array<SidePoint, max_polygon_vertices>& out) {
    if (shape.type == ShapeType::circle) {
        out[0] = {sign * shape.radius, 0.0, 0.0};
        return 1;
    }
    for (int i = 0; i < shape.polygon.count; ++i) {
        const Vec2 r = rotate(q, shape.polygon.vertices[static_cast<std::size_t>(i)]);
        const double along = dot(n, r);
        const double across = dot(n, perp(r));
        out[static_cast<std::size_t>(i)] = {along, omega * across,
                                            turn_acceleration * across - omega * omega * along};
    }
    return shape.polygon.count;
}

// Both bodies' points along n at the sample u, what the point-by-point bounds
// take pair by pair: the gap of a's point i and b's point j along n is
// centres + a[i].offset - b[j].offset, its rate rate + a[i].rate - b[j].rate,
// its second derivative curvature + a[i].curvature - b[j].curvature.
struct PointsAlong {
    std::array<SidePoint, max_polygon_vertices> a{};
    std::array<SidePoint, max_polygon_vertices> b{};
    int count_a = 0;
    int count_b = 0;
    double centres = 0.0;   // n . (x_a - x_b)
    double rate = 0.0;      // n . w(u)
    double curvature = 0.0; // c n . a_rel
    double omega_a = 0.0;   // each body's turning rate at u (0 if it does not turn)
    double omega_b = 0.0;
};

PointsAlong points_along(const World& world, const Pair& pair, const SweepMotion& m, double u,
                         const Transform& xa, const Transform& xb, Vec2 n) {
    PointsAlong pts;
    pts.omega_a = m.radius_a > 0.0 ? m.omega_a + m.c * u * m.alpha_a : 0.0;
    pts.omega_b = m.radius_b > 0.0 ? m.omega_b + m.c * u * m.alpha_b : 0.0;
    const double turn_a = m.radius_a > 0.0 ? m.c * m.alpha_a : 0.0;
    const double turn_b = m.radius_b > 0.0 ? m.c * m.alpha_b : 0.0;
    pts.count_a = side_points(world.bodies[static_cast<std::size_t>(pair.a)].shape, xa.q,
                              pts.omega_a, turn_a, n, -1.0, pts.a);
    pts.count_b = side_points(world.bodies[static_cast<std::size_t>(pair.b)].shape, xb.q,
                              pts.omega_b, turn_b, n, 1.0, pts.b);
    pts.centres = dot(n, xa.p - xb.p);
    pts.rate = dot(n, m.w0 + (m.c * u) * m.a_rel);
    pts.curvature = m.c * dot(n, m.a_rel);
    return pts;
}

// Calls visit(margin, p, q) for each pair of a's point p and b's point q, the
// margin being their gap along n plus margin_shift; false, with no further
// calls, as soon as one margin is not positive (the pair is already there).
template <class Visit>
bool each_point_pair(const PointsAlong& pts, double margin_shift, Visit&& visit) {
    for (int i = 0; i < pts.count_a; ++i) {
        for (int j = 0; j < pts.count_b; ++j) {
            const SidePoint& p = pts.a[static_cast<std::size_t>(i)];
            const SidePoint& q = pts.b[static_cast<std::size_t>(j)];
            const double margin = pts.centres + p.offset - q.offset + margin_shift;
            if (!(margin > 0.0)) {
                return false;
            }
            visit(margin, p, q);
        }
    }
    return true;
}

// A third bound along the separating axis n at u, point by point (docs/physics.md,
// "Tunnelling"): the gap along n is the least n . p over a's points minus the
// greatest over b's, and each point's n-coordinate is, over the next d
// seconds, at least its value plus its own rate times d, less (d^2 / 2) times
// a bound on its second derivative: the centres' part is exact,
// (c / 2) n . a_rel d^2, and turning at theta' with theta'' = c alpha adds at
// most R (theta'^2 + c |alpha|), theta' bounded by its largest over the rest
// of the step. Where the bounds above charge every point the fastest turning
// speed R |omega|, this charges each its own rate: a spinning box just off a
// wall (its corner receding after an impact, or passing the wall's line at
// its closest) is sampled after a fraction of a spin, not after d / (R |omega|)
// (a spinning box grazing a wall needed more than 200 samples per step).
double vertex_advance(const SweepMotion& m, const PointsAlong& pts, double margin_shift,
                      double left) {
    const auto turning = [&](double radius, double omega, double alpha) {
        const double fastest = std::fabs(omega) + m.c * std::fabs(alpha) * left;
        return radius * (fastest * fastest + m.c * std::fabs(alpha));
    };
    const double closing = 0.5 * (turning(m.radius_a, pts.omega_a, m.alpha_a) +
                                  turning(m.radius_b, pts.omega_b, m.alpha_b)) -
                           0.5 * pts.curvature;
    double shortest = never;
    const bool apart = each_point_pair(
        pts, margin_shift, [&](double margin, const SidePoint& p, const SidePoint& q) {
            const double reach = first_reach(closing, q.rate - p.rate - pts.rate, margin);
            shortest = reach < shortest ? reach : shortest;
        });
    return apart ? shortest : 0.0;
}

// A bound of third order along the separating axis n at u, point by point
// (docs/physics.md, "Tunnelling"): each pair of points' gap along n has, at
// the sample, an exact value, rate and second derivative (the centres'
// c n . a_rel, each turning point's theta'' n . perp(R r) - theta'^2 n . R r),
// and only turning gives it a third derivative (the centres move on
// parabolas): -theta'^3 n . perp(R r) - 3 theta' theta'' n . R r, at most
// R (theta'_max^3 + 3 theta'_max c |alpha|) per body. Where the bound above
// charges every point the largest second derivative, this one charges each
// its own: a box pivoting on a corner held by resting contact (the corner's
// rate and second derivative along the normal about 0) is sampled when the
// third-order term may have sunk the corner by the tolerance, not every
// sqrt(tolerance / (R alpha)) seconds.
double jerk_advance(const SweepMotion& m, const PointsAlong& pts, double margin_shift,
                    double left) {
    const auto turning = [&](double radius, double omega, double alpha) {
        const double fastest = std::fabs(omega) + m.c * std::fabs(alpha) * left;
        return radius * fastest * (fastest * fastest + 3.0 * m.c * std::fabs(alpha));
    };
    const double jerk =
        turning(m.radius_a, pts.omega_a, m.alpha_a) + turning(m.radius_b, pts.omega_b, m.alpha_b);
    double shortest = left;
    bool reached = false;
    const bool apart = each_point_pair(
        pts, margin_shift, [&](double margin, const SidePoint& p, const SidePoint& q) {
            const double rate = pts.rate + p.rate - q.rate;
            const double curvature = pts.curvature + p.curvature - q.curvature;
            // No root before `shortest` if the cubic cannot fall by its margin
            // even with every term against it.
            const double fall =
                shortest *
                (std::fabs(rate) + shortest * (0.5 * std::fabs(curvature) + shortest * jerk / 6.0));
            if (fall < margin) {
                return;
            }
            const double reach = first_cubic_reach(margin, rate, curvature, jerk, shortest);
            if (reach < shortest) {
                shortest = reach;
                reached = true;
            }
        });
    if (!apart) {
        return 0.0;
    }
    return reached ? shortest : never;
}

// A fourth bound along a face normal n of a turning body F, taken in F's frame
// (docs/physics.md, "Tunnelling"): the gap is the least over the other body's
// points q_j of d_j = n(t) . (q_j - x_F) - s_F, s_F the face's offset, and
// each d_j is, over the next d seconds, at least d_j + d_j' d - (M_j / 2) d^2.
// d_j' is q_j's approach to the face (its speed relative to F's material
// point there), and M_j bounds d_j'' = n'' . r + 2 n' . r' + n . r'' with
// r = q_j - x_F, n' = omega_F perp(n) and |r'| bounded over the step. Along
// a world-fixed n the face's far end approaches at R |omega_F| although it is
// beside the point, not over it: a slowly turning plank meeting a post's
// corner was sampled every (corner's speed / R omega) of the gap and stalled
// at every dt; in the plank's frame the corner is charged its own speed.
double frame_advance(const World& world, const Pair& pair, const SweepMotion& m, double u,
                     double floor, const Transform& xa, const Transform& xb, const Axis& axis,
                     double end) {
    const bool face_of_a = axis.owner == Face::a;
    const Shape& face_shape =
        world.bodies[static_cast<std::size_t>(face_of_a ? pair.a : pair.b)].shape;
    const Shape& other = world.bodies[static_cast<std::size_t>(face_of_a ? pair.b : pair.a)].shape;
    const Transform& xf = face_of_a ? xa : xb;
    const Transform& xo = face_of_a ? xb : xa;
    const std::size_t face = static_cast<std::size_t>(axis.face);
    const Vec2 n = rotate(xf.q, face_shape.polygon.normals[face]); // outward from F
    const double offset = dot(face_shape.polygon.normals[face], face_shape.polygon.vertices[face]);
    // The other's centre relative to F's: w and a_rel are a's relative to b's.
    const double sign = face_of_a ? -1.0 : 1.0;
    const Vec2 w = sign * (m.w0 + (m.c * u) * m.a_rel);
    const double accel = m.c * length(m.a_rel);
    const double left = end - u;
    const double radius_f = face_of_a ? m.radius_a : m.radius_b;
    const double radius_o = face_of_a ? m.radius_b : m.radius_a;
    const double alpha_f = m.c * std::fabs(face_of_a ? m.alpha_a : m.alpha_b);
    const double alpha_o = m.c * std::fabs(face_of_a ? m.alpha_b : m.alpha_a);
    const auto rate_at_u = [&](double omega0, double alpha0, double radius) {
        return radius > 0.0 ? omega0 + m.c * u * alpha0 : 0.0;
    };
    const double omega_f = face_of_a ? rate_at_u(m.omega_a, m.alpha_a, m.radius_a)
                                     : rate_at_u(m.omega_b, m.alpha_b, m.radius_b);
    const double omega_o = face_of_a ? rate_at_u(m.omega_b, m.alpha_b, m.radius_b)
                                     : rate_at_u(m.omega_a, m.alpha_a, m.radius_a);
    const double fastest_f = radius_f > 0.0 ? std::fabs(omega_f) + alpha_f * left : 0.0;
    const double fastest_o = radius_o > 0.0 ? std::fabs(omega_o) + alpha_o * left : 0.0;
    // |r'| over the rest of the step, and the other's own turning in n . r''.
    const double speed = length(w) + accel * left + fastest_o * radius_o;
    const double own_turning = accel + radius_o * (fastest_o * fastest_o + alpha_o);
    const bool circle = other.type == ShapeType::circle;
    const int count = circle ? 1 : other.polygon.count;
    const double tolerance = world.solver.contact_tolerance;
    double shortest = never;
    for (int j = 0; j < count; ++j) {
        const Vec2 arm =
            circle ? Vec2{} : rotate(xo.q, other.polygon.vertices[static_cast<std::size_t>(j)]);
        const Vec2 r = xo.p + arm - xf.p;
        const double gap = dot(n, r) - offset - (circle ? other.radius : 0.0);
        const double margin = gap - floor + tolerance;
        if (!(margin > 0.0)) {
            return 0.0;
        }
        const double rate = omega_f * dot(perp(n), r) + dot(n, w + omega_o * perp(arm));
        const double farthest = length(r) + speed * left;
        const double curvature =
            (alpha_f + fastest_f * fastest_f) * farthest + 2.0 * fastest_f * speed + own_turning;
        const double reach = first_reach(0.5 * curvature, -rate, margin);
        shortest = reach < shortest ? reach : shortest;
    }
    return shortest;
}

// A fifth, for a turning body near what it cannot reach at any angle: each
// turning body stands in for the disc it sweeps (its circumradius about its
// centre), whose gap along a fixed axis moves only with the centres. However
// fast it spins, a rod whose disc clears a wall is sampled once per step (the
// bounds above charge R |omega| d of turning, which passes any clearance once
// the rod turns far enough within a step).
double disc_advance(const World& world, const Pair& pair, const SweepMotion& m, double u,
                    double floor, const Transform& xa, const Transform& xb) {
    const Shape& a = world.bodies[static_cast<std::size_t>(pair.a)].shape;
    const Shape& b = world.bodies[static_cast<std::size_t>(pair.b)].shape;
    const Shape disc_a = make_circle(circumradius(a));
    const Shape disc_b = make_circle(circumradius(b));
    const Axis axis =
        separating_axis(m.radius_a > 0.0 ? disc_a : a, xa, m.radius_b > 0.0 ? disc_b : b, xb);
    const double margin = axis.gap - floor + world.solver.contact_tolerance;
    if (!(margin > 0.0)) {
        return 0.0;
    }
    const Vec2 w = m.w0 + (m.c * u) * m.a_rel;
    return first_reach(-0.5 * m.c * dot(axis.normal, m.a_rel), -dot(axis.normal, w), margin);
}

} // namespace

// How long after a free sample at u (separation s) the pair certainly stays
// above the test's floor less contact_tolerance (conservative advancement).
// Over the next d seconds a's centre moves relative to b's by exactly
//   D(d) = w(u) d + (c / 2) a_rel d^2,
// and each body's surface by at most R (|omega(u)| d + (c / 2) |alpha| d^2)
// more by turning (a chord is shorter than its arc). Two bounds for every
// pair, and three more for a turning one (vertex_advance, frame_advance,
// disc_advance above), the longest wins, each sound:
// - Any direction: the signed distance changes by at most the largest
//   displacement of a point, |D(d)| plus the turning, and s bounds it from
//   below while the pair is apart and equals it once they interpenetrate.
// - Along the separating axis n at u: the gap along a fixed n falls by at most
//   -(n . D(d)) plus the turning. This one lets a pair that slides along, or
//   moves away from, what it touches go on in long steps instead of steps of
//   contact_tolerance / speed.
// A pair closing at constant speed is thus sampled again just as it is
// contact_tolerance past the floor; one at rest on the ground under gravity,
// when gravity has pulled it that far (the quadratic term, where the largest
// speed over the rest of the step would make it crawl).
double safe_advance(const World& world, const Pair& pair, const SweepMotion& m, double u, double s,
                    double floor, const BodyState& at_a, const BodyState& at_b, double end) {
    const double tolerance = world.solver.contact_tolerance;
    // The pair may close by what is left above the floor (none if already
    // below it: only possible at u = 0) and contact_tolerance more.
    const double margin = (s > floor ? s - floor : 0.0) + tolerance;
    const Vec2 w = m.w0 + (m.c * u) * m.a_rel;
    const double half_c = 0.5 * m.c;
    const double turn_rate = m.radius_a * std::fabs(m.omega_a + m.c * u * m.alpha_a) +
                             m.radius_b * std::fabs(m.omega_b + m.c * u * m.alpha_b);
    const double turn_growth =
        half_c * (m.radius_a * std::fabs(m.alpha_a) + m.radius_b * std::fabs(m.alpha_b));
    const double any_direction =
        first_reach(half_c * length(m.a_rel) + turn_growth, length(w) + turn_rate, margin);
    if (u + any_direction >= end) {
        return any_direction;
    }
    const Axis axis =
        separating_axis(world.bodies[static_cast<std::size_t>(pair.a)].shape, transform_of(at_a),
                        world.bodies[static_cast<std::size_t>(pair.b)].shape, transform_of(at_b));
    const double axis_margin = axis.gap - floor + tolerance;
    if (!(axis_margin > 0.0)) {
        return any_direction;
    }
    const double along_axis = first_reach(-half_c * dot(axis.normal, m.a_rel) + turn_growth,
                                          turn_rate - dot(axis.normal, w), axis_margin);
    double longest = along_axis > any_direction ? along_axis : any_direction;
    if (turn_rate == 0.0 && turn_growth == 0.0) {
        return longest; // without turning, the point bound is the axis bound
    }
    const auto reaches_end = [&](double advance) {
        longest = advance > longest ? advance : longest;
        return u + longest >= end;
    };
    if (reaches_end(longest)) {
        return longest;
    }
    const Transform xa = transform_of(at_a);
    const Transform xb = transform_of(at_b);
    const PointsAlong points = points_along(world, pair, m, u, xa, xb, axis.normal);
    const double margin_shift = tolerance - floor;
    if (reaches_end(vertex_advance(m, points, margin_shift, end - u)) ||
        reaches_end(jerk_advance(m, points, margin_shift, end - u))) {
        return longest;
    }
    const bool face_turns =
        (axis.owner == Face::a && m.radius_a > 0.0) || (axis.owner == Face::b && m.radius_b > 0.0);
    if (face_turns && reaches_end(frame_advance(world, pair, m, u, floor, xa, xb, axis, end))) {
        return longest;
    }
    reaches_end(disc_advance(world, pair, m, u, floor, xa, xb));
    return longest;
}

} // namespace impulse
