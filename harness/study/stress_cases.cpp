// The stress matrix's cases (stress.h): each scene at an edge of what the
// engine is asked to do, with the invariants it checks.
#include "exact_answers.h"
#include "stress.h"
#include "stress_rows.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

namespace impulse::harness {

namespace {

using Json = nlohmann::json;

Json pair_of(Vec2 v) {
    return Json::array({v.x, v.y});
}

Json disc(const std::string& name, double radius, double mass, Vec2 position, Vec2 velocity = {}) {
    return {{"name", name},
            {"shape", {{"circle", radius}}},
            {"mass", mass},
            {"position", pair_of(position)},
            {"velocity", pair_of(velocity)}};
}

Json box(const std::string& name, Vec2 half, double mass, Vec2 position, double angle,
         Vec2 velocity = {}) {
    return {{"name", name},   {"shape", {{"box", pair_of(half)}}},
            {"mass", mass},   {"position", pair_of(position)},
            {"angle", angle}, {"velocity", pair_of(velocity)}};
}

Json wall(const std::string& name, Vec2 half, Vec2 position) {
    return {{"name", name},
            {"static", true},
            {"shape", {{"box", pair_of(half)}}},
            {"position", pair_of(position)}};
}

struct Setting {
    double e = 1.0;
    Vec2 gravity{0.0, -9.81};
    double dt = 1.0 / 60.0;
    double duration = 1.0;
    bool ccd = false;
    bool resting = false;
    std::string contacts = "single";
    std::string vertex_normal = "reference-face";
    // Written only when set, as a user would: the seed's cases never name them.
    std::string resting_method; // "time-stepping" for the pile rows
    std::string stepping;       // "local" for the pile of 1000
};

// Through the scene format and its loader, so every case is a valid scene
// (no overlap at t = 0, every default filled in) like any file.
Scene scene_of(const std::string& name, const std::string& description, const Setting& s,
               Json bodies) {
    Json solver = {{"integrator", "verlet"}, {"toi", "secant"}};
    solver["ccd"] = s.ccd;
    solver["resting"] = s.resting;
    solver["contacts"] = s.contacts;
    solver["vertex_normal"] = s.vertex_normal;
    if (!s.resting_method.empty()) {
        solver["resting_method"] = s.resting_method;
    }
    if (!s.stepping.empty()) {
        solver["stepping"] = s.stepping;
    }
    const Json document = {
        {"schema", scene_schema},        {"name", name},       {"description", description},
        {"gravity", pair_of(s.gravity)}, {"restitution", s.e}, {"dt", s.dt},
        {"duration", s.duration},        {"solver", solver},   {"bodies", std::move(bodies)}};
    return parse_scene(document.dump(), "stress/" + name);
}

StressCase make_case(const std::string& name, const std::string& description, const Setting& s,
                     Json bodies, StressChecks checks, std::string expected_refusal = "") {
    return {name, description, scene_of(name, description, s, std::move(bodies)), std::move(checks),
            std::move(expected_refusal)};
}

// Halfway between impacts n and n + 1 of a drop from h0: a run that long sees exactly n.
double drop_duration(double h0, double e, int n) {
    const DropLadder ladder{h0, 9.81, e};
    return ladder.impact_time(n) + 0.5 * (ladder.impact_time(n + 1) - ladder.impact_time(n));
}

// A disc of radius r dropped from 1 m above static ground (its top at y = 0),
// everything shifted by `offset`: the drop docs/physics.md's ladder answers.
StressCase drop_case(const std::string& name, const std::string& description, double r, double e,
                     double dt, Vec2 offset, int impacts, double duration = 0.0) {
    Setting s;
    s.e = e;
    s.dt = dt;
    s.resting = e == 0.0; // e = 0 ends in contact, which the seed's model refuses
    s.duration = duration > 0.0 ? duration : drop_duration(1.0, e, impacts);
    StressChecks checks;
    checks.sides = {{1, 0, {0.0, 1.0}}};
    checks.energy_drift = e == 1.0;
    checks.drop = DropCheck{1, impacts};
    checks.offset = std::max(std::abs(offset.x), std::abs(offset.y));
    return make_case(
        name, description, s,
        Json::array({wall("ground", {std::max(5.0, 2.0 * r), 0.5}, offset + Vec2{0.0, -0.5}),
                     disc("ball", r, 1.0, offset + Vec2{0.0, r + 1.0})}),
        checks);
}

// Two discs of radius 0.5 closing head-on at 2 m/s in free space, masses
// `ratio` kg and 1 kg.
StressCase mass_case(double ratio, const std::string& ratio_text, double e) {
    Setting s;
    s.e = e;
    s.gravity = {0.0, 0.0};
    s.duration = 3.0;
    s.resting = e == 0.0; // they leave touching at the same speed: contact, not a collision
    StressChecks checks;
    checks.sides = {{1, 0, {1.0, 0.0}}};
    checks.momentum = true;
    checks.energy_drift = e == 1.0;
    checks.head_on = HeadOnCheck{0, 1};
    const std::string e_text = e == 0.0 ? "0" : "1";
    return make_case("mass-" + ratio_text + "-e" + e_text,
                     "mass ratio " + ratio_text + ": a " + ratio_text +
                         " kg disc meets a 1 kg disc head-on at 2 m/s, no gravity, e = " + e_text,
                     s,
                     Json::array({disc("heavy", 0.5, ratio, {-2.0, 0.0}, {1.0, 0.0}),
                                  disc("light", 0.5, 1.0, {2.0, 0.0}, {-1.0, 0.0})}),
                     checks);
}

// A 0.05 m disc of 10 g at speed v against a static wall 0.02 m thick, no
// gravity, e = 1; it hits at t = 0.4 s and the run ends at 1 s.
StressCase speed_case(const std::string& name, double v, double dt, bool ccd,
                      std::string expected_refusal = "") {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.dt = dt;
    s.ccd = ccd;
    s.duration = 1.0;
    StressChecks checks;
    checks.sides = {{1, 0, {-1.0, 0.0}}};
    checks.energy_drift = true;
    const double start = -(0.06 + 0.4 * v);
    std::string description = "a 0.05 m disc at " + short_number(v) +
                              " m/s into a 0.02 m static wall, dt = " + short_number(dt) + " s" +
                              (ccd ? ", ccd" : "");
    if (!expected_refusal.empty()) {
        description += ": would tunnel without ccd, so it must be refused up front";
    }
    return make_case(name, description, s,
                     Json::array({wall("wall", {0.01, 1.0}, {0.0, 0.0}),
                                  disc("disc", 0.05, 0.01, {start, 0.0}, {v, 0.0})}),
                     checks, std::move(expected_refusal));
}

// A 2 x 0.5 m box tilted by 1e-9 rad dropped 1 m onto the ground, e = 0.5:
// its bottom face meets the ground's top face all but parallel, the corners
// 2e-9 m apart in height (twice the contact tolerance), so it lands on three
// collisions within 1e-9 s and rocks from corner to corner. The run ends at
// 0.9 s, after the second landing's rocking and before its bounces die out,
// where the seed's model stops as resting contact (as drop-flat ends early).
StressCase tilt_case(const std::string& name, const std::string& contacts) {
    Setting s;
    s.e = 0.5;
    s.contacts = contacts;
    s.duration = 0.9;
    StressChecks checks;
    checks.sides = {{1, 0, {0.0, 1.0}}};
    return make_case(name,
                     "near-parallel edges: a 2 x 0.5 m box at 1e-9 rad dropped 1 m lands and "
                     "rocks on the ground for 0.9 s, e = 0.5, contacts " +
                         contacts,
                     s,
                     Json::array({wall("ground", {5.0, 0.5}, {0.0, -0.5}),
                                  box("box", {1.0, 0.25}, 1.0, {0.0, 1.25 + 1e-9}, 1e-9)}),
                     checks);
}

// Two unit squares at 45 degrees meet corner to corner on the x axis, no
// gravity, e = 1.
StressCase corner_case(const std::string& vertex_normal) {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.vertex_normal = vertex_normal;
    s.duration = 1.5;
    StressChecks checks;
    checks.sides = {{1, 0, {1.0, 0.0}}};
    checks.momentum = true;
    checks.angular_momentum = true;
    checks.energy_drift = true;
    const double quarter = 0.7853981633974483;
    return make_case("corner-" + vertex_normal,
                     "vertex/vertex: two unit squares at 45 degrees meet corner to corner at 2 "
                     "m/s, no gravity, e = 1, vertex_normal " +
                         vertex_normal,
                     s,
                     Json::array({box("left", {0.5, 0.5}, 1.0, {-1.5, 0.0}, quarter, {1.0, 0.0}),
                                  box("right", {0.5, 0.5}, 1.0, {1.5, 0.0}, quarter, {-1.0, 0.0})}),
                     checks);
}

// A closed 10 x 6 m room (walls 1 to 4) with `mover` (body 0) bouncing around
// it for 1e4 s at dt 1/30 (300,000 steps), no gravity, e = 1.
StressCase room_case(const std::string& name, const std::string& description, Json mover) {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.dt = 1.0 / 30.0;
    s.duration = 1e4;
    StressChecks checks;
    checks.sides = {
        {0, 1, {1.0, 0.0}}, {0, 2, {-1.0, 0.0}}, {0, 3, {0.0, 1.0}}, {0, 4, {0.0, -1.0}}};
    checks.energy_drift = true;
    return make_case(
        name, description, s,
        Json::array({std::move(mover), wall("left", {0.5, 3.5}, {-5.5, 0.0}),
                     wall("right", {0.5, 3.5}, {5.5, 0.0}), wall("floor", {6.0, 0.5}, {0.0, -3.5}),
                     wall("ceiling", {6.0, 0.5}, {0.0, 3.5})}),
        checks);
}

// A 0.7 kg disc in the room: thousands of collisions, each rounding the
// velocity (0.7 kg is not a power of two).
StressCase disc_room_case() {
    return room_case("long-room",
                     "1e4 s: a 0.25 m disc of 0.7 kg bounces around a closed 10 x 6 m room at "
                     "3.2 m/s for 1e4 s, dt = 1/30 s (300,000 steps), no gravity, e = 1",
                     disc("ball", 0.25, 0.7, {0.0, 0.0}, {2.9, 1.3}));
}

// The same room with a spinning 0.6 x 0.4 m box instead: every collision is
// a corner's, through Eq. 9 with its rotational terms, and rounds more.
StressCase box_room_case() {
    Json spinning = box("box", {0.3, 0.2}, 0.7, {0.0, 0.0}, 0.3, {2.9, 1.3});
    spinning["angular_velocity"] = 1.1;
    return room_case("long-room-box",
                     "1e4 s: the room of long-room with a spinning 0.6 x 0.4 m box of 0.7 kg "
                     "(1.1 rad/s) instead of the disc",
                     std::move(spinning));
}

// A disc dropped 1 m with e = 0.5 and resting on: its cascade ends, and it
// then rests for the rest of 1e4 s at dt 1/30.
StressCase rest_case() {
    Setting s;
    s.e = 0.5;
    s.dt = 1.0 / 30.0;
    s.duration = 1e4;
    s.resting = true;
    StressChecks checks;
    checks.sides = {{1, 0, {0.0, 1.0}}};
    return make_case(
        "long-rest",
        "1e4 s: a disc dropped 1 m, e = 0.5, resting: its bounces end at t_inf and "
        "it rests for 1e4 s at dt = 1/30 s (300,000 steps)",
        s,
        Json::array({wall("ground", {5.0, 0.5}, {0.0, -0.5}), disc("ball", 0.5, 1.0, {0.0, 1.5})}),
        checks);
}

// ---------------------------------------------------------------- piles (issue 14)

// What a column of n bodies at rest may be off by per step (docs/physics.md, "A
// stack solved iteratively"): the solver stops once no point would move by
// more than the contact tolerance d within the step, a residual of r = d / h,
// and the impulses then lie within |A^-1| r of the exact ones. For a column,
// |A^-1| is of order m n^2 / 2 (the stiffness Laplacian of the column over m),
// so against the top body's weight m |g| h the impulse through each contact is
// the weight above times h within (n^2 / 2) d / (|g| h^2) (n = 1 or 2: d /
// (|g| h^2), 3.7e-7 at 60 Hz; n = 50 at 64 Hz: 5.2e-4). A pivoting solve (an
// island of at most 16 points) is exact to rounding, far inside it.
double support_rtol(const Scene& scene, int n) {
    const double spread = std::max(1.0, 0.5 * static_cast<double>(n) * static_cast<double>(n));
    return spread * scene.solver.contact_tolerance / (length(scene.gravity) * scene.dt * scene.dt);
}

// The potential energy of the dynamic bodies above the height `ground`: the
// energy scale of a pile at rest there (StressChecks::energy_scale_floor).
double potential_above(const Scene& scene, double ground) {
    double energy = 0.0;
    for (const SceneBody& body : scene.bodies) {
        energy +=
            body.is_static ? 0.0 : body.mass * length(scene.gravity) * (body.position.y - ground);
    }
    return energy;
}

// 50 boxes 1.0 x 0.25 m (dyadic, so the faces touch exactly), masses 1 to 1.98
// kg, stacked on the ground at rest for 3 s: nothing moves sideways, nothing
// sinks (so nothing overlaps or passes through: no side rules), and each
// contact carries exactly the weight above it.
StressCase column_case() {
    Setting s;
    s.e = 0.5;
    // 1/64 s rather than 1/60: the up-front tunnelling refusal (tunnelling.h)
    // bounds closing speeds by a fall through the column's 12.5 m, and at 1/60
    // s that bound just passes the boxes' 0.5 m thickness in a step.
    s.dt = 1.0 / 64.0;
    s.duration = 3.0;
    s.resting = true;
    s.resting_method = "time-stepping";
    Json bodies = Json::array({wall("ground", {5.0, 0.5}, {0.0, -0.5})});
    StressChecks checks;
    SupportCheck support;
    for (int i = 0; i < 50; ++i) {
        const double y = 0.125 + 0.25 * static_cast<double>(i);
        bodies.push_back(box("box-" + std::to_string(i), {0.5, 0.125},
                             1.0 + 0.02 * static_cast<double>(i), {0.0, y}, 0.0));
        support.column.push_back(i + 1);
    }
    checks.overlap_bound = 1e-6;
    checks.drifts = {{{1.0, 0.0}, 1e-6}, {{0.0, 1.0}, 1e-6}};
    StressCase c =
        make_case("pile-column-50",
                  "dense contact: a column of 50 boxes 1 x 0.25 m (1 to 1.98 kg) at rest "
                  "on the ground for 3 s at dt = 1/64 s, time-stepping",
                  s, std::move(bodies), checks);
    support.rtol = support_rtol(c.scene, static_cast<int>(support.column.size()));
    c.checks.supports = {support};
    c.checks.energy_scale_floor = potential_above(c.scene, 0.0);
    return c;
}

// Two stacks on one ground, 1000 kg on 1 kg and 1 kg on 1000 kg (boxes 1 x
// 0.5 m), at rest for 3 s: both hold, and the lower contact of each carries
// 1001 |g| h per step, the upper one 1000 |g| h or |g| h.
StressCase mass_stack_case() {
    Setting s;
    s.e = 0.5;
    s.duration = 3.0;
    s.resting = true;
    s.resting_method = "time-stepping";
    const Vec2 half{0.5, 0.25};
    Json bodies = Json::array({wall("ground", {5.0, 0.5}, {0.0, -0.5}),
                               box("light-under", half, 1.0, {-2.0, 0.25}, 0.0),
                               box("heavy-on-top", half, 1e3, {-2.0, 0.75}, 0.0),
                               box("heavy-under", half, 1e3, {2.0, 0.25}, 0.0),
                               box("light-on-top", half, 1.0, {2.0, 0.75}, 0.0)});
    StressChecks checks;
    checks.sides = {{2, 1, {0.0, 1.0}}, {4, 3, {0.0, 1.0}}};
    checks.overlap_bound = 1e-6;
    checks.drifts = {{{1.0, 0.0}, 1e-6}, {{0.0, 1.0}, 1e-6}};
    StressCase c =
        make_case("pile-mass-1e3",
                  "dense contact, mass ratio 1:1000: a 1000 kg box resting on a 1 kg box "
                  "and a 1 kg box on a 1000 kg box, 3 s, time-stepping",
                  s, std::move(bodies), checks);
    const double rtol = support_rtol(c.scene, 2);
    c.checks.supports = {{{1, 2}, rtol}, {{3, 4}, rtol}};
    c.checks.energy_scale_floor = potential_above(c.scene, 0.0);
    return c;
}

// The scale scene pile-discs-1000's block: 1000 discs of radius 0.05 to 0.25 m
// and density 1 to 4 kg/m^2 released at rest on a 0.55 m lattice into an open
// box, e = 0.5, local stepping, 8 s. It must come to rest by 6 s (kinetic
// energy below 1e-9 of what the fall released), never overlap beyond 1e-6 m,
// and never gain energy.
StressCase pile_discs_case() {
    const std::string name = "pile-discs-1000";
    const std::string description =
        "dense contact at scale: 1000 discs of mixed sizes (1:5) and masses (1:100) poured into "
        "an open box, e = 0.5, resting with local stepping (time-stepping), at rest by 6 s";
    const Json solver = {{"integrator", "symplectic-euler"},
                         {"toi", "secant"},
                         {"resting", true},
                         {"stepping", "local"}};
    const Json pile = {{"count", 1000},     {"shape", "circle"}, {"size", {0.05, 0.25}},
                       {"density", {1, 4}}, {"spacing", 0.55},   {"random_angles", false},
                       {"seed", 1}};
    const Json document = {{"schema", scene_schema},     {"name", name},
                           {"description", description}, {"restitution", 0.5},
                           {"dt", 1.0 / 60.0},           {"duration", 8.0},
                           {"solver", solver},           {"pile", pile}};
    StressCase c;
    c.name = name;
    c.description = description;
    c.scene = parse_scene(document.dump(), "stress/" + name);
    c.checks.overlap_bound = 1e-6;
    c.checks.at_rest = AtRestCheck{6.0, 1e-9};
    c.slow = true;
    return c;
}

} // namespace

std::vector<StressCase> stress_cases() {
    std::vector<StressCase> cases;
    for (const double e : {1.0, 0.0}) {
        cases.push_back(mass_case(1.0, "1", e));
        cases.push_back(mass_case(1e3, "1e3", e));
        cases.push_back(mass_case(1e6, "1e6", e));
    }
    cases.push_back(speed_case("speed-0.01", 0.01, 1.0 / 60.0, false));
    cases.push_back(speed_case("speed-1", 1.0, 1.0 / 60.0, false));
    cases.push_back(speed_case("speed-100", 100.0, 1e-3, false));
    cases.push_back(speed_case("speed-1000-ccd", 1000.0, 1.0 / 30.0, true));
    cases.push_back(speed_case("speed-1000", 1000.0, 1.0 / 30.0, false, "tunnelling"));
    const Vec2 origin{};
    cases.push_back(drop_case("size-0.05", "size: a 0.05 m disc dropped 1 m, e = 0.8, dt = 1/60 s",
                              0.05, 0.8, 1.0 / 60.0, origin, 4));
    cases.push_back(drop_case("size-1", "size: a 1 m disc dropped 1 m, e = 0.8, dt = 1/60 s", 1.0,
                              0.8, 1.0 / 60.0, origin, 4));
    cases.push_back(drop_case("size-50", "size: a 50 m disc dropped 1 m, e = 0.8, dt = 1/60 s",
                              50.0, 0.8, 1.0 / 60.0, origin, 4));
    cases.push_back(drop_case("offset-1e4",
                              "position: size-1 with everything 1e4 m from the origin in x and y",
                              1.0, 0.8, 1.0 / 60.0, {1e4, 1e4}, 4));
    cases.push_back(drop_case("dt-1e-4", "dt: size-1 at dt = 1e-4 s (24,000 steps)", 1.0, 0.8, 1e-4,
                              origin, 4));
    cases.push_back(
        drop_case("dt-1_30", "dt: size-1 at dt = 1/30 s", 1.0, 0.8, 1.0 / 30.0, origin, 4));
    cases.push_back(drop_case("e-0",
                              "e = 0: a 1 m disc dropped 1 m stops dead and rests (resting: true)",
                              1.0, 0.0, 1.0 / 60.0, origin, 1, 3.0));
    cases.push_back(drop_case("e-1", "e = 1: a 1 m disc dropped 1 m bounces back to 1 m every time",
                              1.0, 1.0, 1.0 / 60.0, origin, 4));
    cases.push_back(disc_room_case());
    cases.push_back(box_room_case());
    cases.push_back(rest_case());
    cases.push_back(tilt_case("tilt-single", "single"));
    cases.push_back(tilt_case("tilt-simultaneous", "simultaneous"));
    cases.push_back(corner_case("reference-face"));
    cases.push_back(corner_case("bisector"));
    cases.push_back(column_case());
    cases.push_back(mass_stack_case());
    cases.push_back(pile_discs_case());
    return cases;
}

} // namespace impulse::harness
