// Chipmunk2D 7.0.3 behind the harness's Simulator interface, set up for a fair
// comparison (docs/references.md, "Chipmunk2D 7.0.3").
//
// Chipmunk's cpFloat is double in Debian's build (CP_USE_DOUBLES), so numbers
// cross the boundary unchanged and the settings say "precision": "double".
// Debian builds Chipmunk without NDEBUG: its debug checks (cpAssertHard,
// cpAssertSoft, the body sanity check after every integration) are on, and a
// failed one prints to stderr and calls abort(), taking the whole tool down.
// So everything that could trip them is refused before Chipmunk sees it.
#include "chipmunk_simulator.h"

#include "input_error.h"
#include "number_format.h"
#include "shape.h"
#include "text.h"

#include <algorithm>
#include <chipmunk/chipmunk.h>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fcntl.h>
#include <limits>
#include <mutex>
#include <type_traits>
#include <unistd.h>
#include <utility>
#include <vector>

static_assert(std::is_same_v<cpFloat, double>,
              "this adapter expects Chipmunk built with CP_USE_DOUBLES, as Debian builds it");

namespace impulse::harness {

namespace {

// Every quantity of the scene, and the few products of them Chipmunk forms
// (momentum, inverse mass, the farthest point reached), must lie within
// [smallest_magnitude, largest_magnitude]: their products of three or four then stay finite and
// non-zero in double, so no NaN or infinity reaches Chipmunk's sanity checks.
constexpr double largest_magnitude = 1e100;
constexpr double smallest_magnitude = 1e-100;

cpVect to_cp(Vec2 v) {
    return cpv(v.x, v.y);
}

Vec2 from_cp(cpVect v) {
    return {v.x, v.y};
}

// Debian's Chipmunk, built without NDEBUG, prints a two-line banner with
// printf the first time a process creates a space: on standard output, where
// `impulse run` writes the trajectory. So the first space is created, and
// freed, with standard output pointed at /dev/null for that moment. Nothing
// else writes there meanwhile: the workers of a parallel check print nothing,
// and call_once holds back any other thread's first space until it is done.
void swallow_debug_banner() {
    static std::once_flag once;
    std::call_once(once, [] {
        std::fflush(stdout);
        const int saved = ::dup(STDOUT_FILENO);
        const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved >= 0 && null >= 0 && ::dup2(null, STDOUT_FILENO) >= 0) {
            cpSpaceFree(cpSpaceNew());
            std::fflush(stdout);
            ::dup2(saved, STDOUT_FILENO);
        }
        for (int fd : {saved, null}) {
            if (fd >= 0) {
                ::close(fd);
            }
        }
    });
}

// ---------------------------------------------------------------- refusals

struct RangeJudge {
    const Scene& scene;

    // `zero_allowed`: 0 means "none" here (a velocity), not a divisor (a mass).
    void operator()(const std::string& path, const std::string& what, double value,
                    const std::string& unit, bool zero_allowed) const {
        const double size = std::fabs(value);
        if (!std::isfinite(value) || size > largest_magnitude) {
            fail(path, what + " " + significant_text(value, 3) + unit + " is over " +
                           significant_text(largest_magnitude, 3) +
                           ", beyond which Chipmunk2D's products of it overflow");
        }
        if (size == 0.0 && !zero_allowed) {
            fail(path, what + " is 0, which Chipmunk2D divides by");
        }
        if (size != 0.0 && size < smallest_magnitude) {
            fail(path, what + " " + significant_text(value, 3) + unit + " is under " +
                           significant_text(smallest_magnitude, 3) +
                           ", below which Chipmunk2D's products of it underflow");
        }
    }

    [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
        throw InputError(scene.file, path, reason + "; Chipmunk2D cannot run this scene");
    }
};

std::string body_path(const Scene& scene, std::size_t i) {
    if (i < scene.listed_bodies) {
        return "bodies[" + std::to_string(i) + "]";
    }
    return scene.gas ? std::string("gas") : std::string("pile");
}

void judge_body(const RangeJudge& judge, const Scene& scene, const SceneBody& body,
                const std::string& path) {
    judge(path + ".position", "its x", body.position.x, " m", true);
    judge(path + ".position", "its y", body.position.y, " m", true);
    judge(path + ".angle", "its angle", body.angle, " rad", true);
    judge(path + ".shape", "its size", circumradius(body.shape), " m", false);
    if (body.is_static) {
        return;
    }
    const double speed = length(body.velocity) + length(scene.gravity) * scene.duration;
    judge(path + ".velocity", "its speed of up to |v| + |g| duration =", speed, " m/s", true);
    judge(path + ".angular_velocity", "its angular velocity", body.angular_velocity, " rad/s",
          true);
    // cpBodyUpdateVelocity checks m > 0 and i > 0 (cpAssertSoft).
    judge(path + ".mass", "its mass", body.mass, " kg", false);
    judge(path + ".mass", "its inverse mass", 1.0 / body.mass, " 1/kg", false);
    judge(path + ".velocity", "its momentum of up to m (|v| + |g| duration) =", body.mass * speed,
          " kg m/s", true);
    if (body.rotation) {
        judge(path + ".inertia", "its rotational inertia", body.inertia, " kg m^2", false);
        judge(path + ".inertia", "its inverse rotational inertia", 1.0 / body.inertia,
              " 1/(kg m^2)", false);
    }
    const double farthest =
        length(body.position) + circumradius(body.shape) + speed * scene.duration;
    judge(path + ".position", "the farthest it can get from the origin", farthest, " m", true);
}

void refuse_what_chipmunk_cannot_run(const Scene& scene) {
    if (scene.solver.ccd) {
        throw InputError(scene.file, "solver.ccd",
                         "the scene asks for continuous collision, which Chipmunk2D 7.0.3 "
                         "does not have (a fast body would tunnel)");
    }
    const RangeJudge judge{scene};
    judge("gravity", "its x", scene.gravity.x, " m/s^2", true);
    judge("gravity", "its y", scene.gravity.y, " m/s^2", true);
    judge("dt", "the step", scene.dt, " s", false);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        judge_body(judge, scene, scene.bodies[i], body_path(scene, i));
    }
}

// The narrowest extent of a shape: a circle's diameter, a convex polygon's
// least width across any of its edge normals.
double width_of(const Shape& shape) {
    if (shape.type == ShapeType::circle) {
        return 2.0 * shape.radius;
    }
    const Polygon& p = shape.polygon;
    double width = std::numeric_limits<double>::infinity();
    for (int k = 0; k < p.count; ++k) {
        const Vec2 n = p.normals[static_cast<std::size_t>(k)];
        double low = std::numeric_limits<double>::infinity();
        double high = -low;
        for (int i = 0; i < p.count; ++i) {
            const double s = dot(p.vertices[static_cast<std::size_t>(i)], n);
            low = std::min(low, s);
            high = std::max(high, s);
        }
        width = std::min(width, high - low);
    }
    return width;
}

// ---------------------------------------------------------------- events

std::size_t index_of(const cpBody* body) {
    return static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(cpBodyGetUserData(body)));
}

// Records one event per pair in the step where Chipmunk first finds it
// touching (cpArbiterIsFirstContact), the velocities it arrived with from
// pre-solve, the impulse and the velocities it leaves with from post-solve.
class ArbiterRecorder {
  public:
    ArbiterRecorder(const Scene& scene, double restitution)
        : scene_(scene), restitution_(restitution) {}

    void begin_step(double t_end) { t_end_ = t_end; }

    // Closes pairs Chipmunk found touching but never solved (none are
    // expected): no impulse, velocities as they are now.
    void end_step() {
        for (const Pending& p : pending_) {
            events_[p.event].vn_after = relative_normal_velocity(p);
        }
        pending_.clear();
    }

    std::vector<TrajectoryEvent> take() { return std::exchange(events_, {}); }

    // Called by Chipmunk for every touching pair, each step, before the
    // solve (velocities are still those the bodies arrived with).
    void pre_solve(cpArbiter* arb) {
        // Chipmunk sets a pair's restitution to the product of its shapes'
        // elasticities (cpArbiterUpdate: arb->e = a->e * b->e). The shapes
        // carry e (dynamic) and 1 (static), so a body on the ground gets e,
        // but two dynamic bodies would get e^2: the pair's own value is set
        // here, every step, as cpArbiterUpdate recomputes it.
        cpArbiterSetRestitution(arb, restitution_);
        if (!cpArbiterIsFirstContact(arb)) {
            return; // touching already: its event was recorded when it began
        }
        CP_ARBITER_GET_BODIES(arb, first, second);
        const bool first_is_a = is_body_a(index_of(first), index_of(second));
        const cpContactPointSet set = cpArbiterGetContactPointSet(arb);

        Pending p;
        p.arbiter = arb;
        p.a = first_is_a ? first : second;
        p.b = first_is_a ? second : first;
        Vec2 sum;
        for (int k = 0; k < set.count; ++k) {
            sum += 0.5 * (from_cp(set.points[k].pointA) + from_cp(set.points[k].pointB));
        }
        p.point = (1.0 / static_cast<double>(set.count)) * sum;
        // Chipmunk's normal points from the arbiter's first body to its
        // second; the protocol's points toward body a.
        const Vec2 normal = from_cp(set.normal);
        p.normal = first_is_a ? -normal : normal;
        p.event = events_.size();

        events_.push_back(contact_event(t_end_, scene_.bodies[index_of(p.a)].name,
                                        scene_.bodies[index_of(p.b)].name, p.point, p.normal,
                                        relative_normal_velocity(p)));
        pending_.push_back(p);
    }

    // Called after the solver's last iteration for every solved pair.
    void post_solve(cpArbiter* arb) {
        for (std::size_t k = 0; k < pending_.size(); ++k) {
            if (pending_[k].arbiter != arb) {
                continue;
            }
            TrajectoryEvent& event = events_[pending_[k].event];
            // Friction is 0, so the total impulse is the normal one.
            event.impulse = cpvlength(cpArbiterTotalImpulse(arb));
            event.vn_after = relative_normal_velocity(pending_[k]);
            pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(k));
            return;
        }
    }

  private:
    struct Pending {
        const cpArbiter* arbiter = nullptr;
        std::size_t event = 0;
        cpBody* a = nullptr;
        cpBody* b = nullptr;
        Vec2 point;
        Vec2 normal; // toward a
    };

    // The engine's pair convention (docs/engine.md, "Body A and the normal"):
    // the dynamic body when the other is static, else the lower scene index.
    bool is_body_a(std::size_t i, std::size_t j) const {
        if (scene_.bodies[i].is_static != scene_.bodies[j].is_static) {
            return !scene_.bodies[i].is_static;
        }
        return i < j;
    }

    // v_a - v_b at the contact point along the normal toward a: negative
    // while approaching. Chipmunk computes its bounce target e vn from these
    // same pre-solve velocities, before the step's gravity kick, and its
    // solver drives vn to -e vn_before, so vn_after + e vn_before is zero to
    // the solver's convergence.
    static double relative_normal_velocity(const Pending& p) {
        const cpVect point = to_cp(p.point);
        const Vec2 v = from_cp(cpBodyGetVelocityAtWorldPoint(p.a, point)) -
                       from_cp(cpBodyGetVelocityAtWorldPoint(p.b, point));
        return dot(v, p.normal);
    }

    const Scene& scene_;
    double restitution_ = 1.0;
    double t_end_ = 0.0;
    std::vector<TrajectoryEvent> events_;
    std::vector<Pending> pending_; // begun this step, waiting for post-solve
};

cpBool pre_solve_callback(cpArbiter* arb, cpSpace*, cpDataPointer data) {
    static_cast<ArbiterRecorder*>(data)->pre_solve(arb);
    return cpTrue;
}

void post_solve_callback(cpArbiter* arb, cpSpace*, cpDataPointer data) {
    static_cast<ArbiterRecorder*>(data)->post_solve(arb);
}

// ---------------------------------------------------------------- simulator

// The space and what this adapter added to it: cpSpaceFree frees neither
// bodies nor shapes, and must run while they still exist (it wakes every
// body), so they are freed after it.
class Space {
  public:
    Space() : space_(cpSpaceNew()) {}
    ~Space() {
        cpSpaceFree(space_);
        for (cpShape* shape : shapes_) {
            cpShapeFree(shape);
        }
        for (cpBody* body : bodies_) {
            cpBodyFree(body);
        }
    }
    Space(const Space&) = delete;
    Space& operator=(const Space&) = delete;

    cpSpace* get() const { return space_; }
    void add(cpBody* body) {
        bodies_.push_back(body);
        cpSpaceAddBody(space_, body);
    }
    void add(cpShape* shape) {
        shapes_.push_back(shape);
        cpSpaceAddShape(space_, shape);
    }

  private:
    cpSpace* space_;
    std::vector<cpBody*> bodies_;
    std::vector<cpShape*> shapes_;
};

class ChipmunkSimulator final : public Simulator {
  public:
    ChipmunkSimulator(const Scene& scene, const ChipmunkSettings& settings)
        : scene_(scene), settings_(settings), recorder_(scene_, scene.restitution), space_() {
        cpSpace* space = space_.get();
        cpSpaceSetGravity(space, to_cp(scene.gravity));
        cpSpaceSetIterations(space, settings.iterations);
        cpSpaceSetDamping(space, 1.0); // the fraction of velocity kept per second: no damping
        cpSpaceSetSleepTimeThreshold(space, INFINITY); // sleeping off
        cpSpaceSetCollisionSlop(space, settings.collision_slop);
        cpSpaceSetCollisionBias(space, settings.collision_bias);
        cpSpaceSetCollisionPersistence(space,
                                       static_cast<cpTimestamp>(settings.collision_persistence));
        cpCollisionHandler* handler = cpSpaceAddDefaultCollisionHandler(space);
        handler->preSolveFunc = pre_solve_callback;
        handler->postSolveFunc = post_solve_callback;
        handler->userData = &recorder_;
        for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
            bodies_.push_back(add_body(i));
        }
    }

    std::string engine() const override { return chipmunk_version(); }

    std::vector<std::pair<std::string, std::string>> settings() const override {
        const std::string e = format_double(scene_.restitution);
        return {
            {"dt", format_double(scene_.dt)},
            {"iterations", std::to_string(settings_.iterations)},
            {"friction", "0"},
            {"restitution", e},
            {"elasticity_dynamic", e},
            {"elasticity_static", "1"},
            {"pair_restitution", e},
            {"collision_slop", format_double(settings_.collision_slop)},
            {"collision_bias", format_double(settings_.collision_bias)},
            {"collision_persistence", std::to_string(settings_.collision_persistence)},
            {"polygon_radius", "0"},
            {"sleeping", "false"},
            {"damping", "0"},
            {"continuous", "false"},
            {"precision", double_quoted("double")},
        };
    }

    void step(double t0, double dt) override {
        require_finite_state(t0);
        recorder_.begin_step(t0 + dt);
        cpSpaceStep(space_.get(), dt);
        recorder_.end_step();
    }

    BodyState state(int index) const override {
        const cpBody* body = bodies_[static_cast<std::size_t>(index)];
        return {from_cp(cpBodyGetPosition(body)), cpBodyGetAngle(body),
                from_cp(cpBodyGetVelocity(body)), cpBodyGetAngularVelocity(body)};
    }

    std::vector<TrajectoryEvent> take_events() override { return recorder_.take(); }

  private:
    cpBody* add_body(std::size_t index) {
        const SceneBody& spec = scene_.bodies[index];
        // The scene's mass and inertia, not Chipmunk's density helpers; a
        // body that cannot rotate has infinite inertia (cpBodySetMoment
        // accepts INFINITY: its inverse is 0).
        cpBody* body = spec.is_static
                           ? cpBodyNewStatic()
                           : cpBodyNew(spec.mass, spec.rotation ? spec.inertia : INFINITY);
        cpBodySetUserData(body,
                          reinterpret_cast<cpDataPointer>(static_cast<std::uintptr_t>(index)));
        // The centre of mass is the body's origin (cpBodySetCenterOfGravity's
        // default): the scene's shapes are centred on it.
        cpBodySetPosition(body, to_cp(spec.position));
        cpBodySetAngle(body, spec.angle);
        if (!spec.is_static) {
            cpBodySetVelocity(body, to_cp(spec.velocity));
            cpBodySetAngularVelocity(body, spec.angular_velocity);
        }
        space_.add(body);
        cpShape* shape = make_shape(body, spec.shape);
        cpShapeSetFriction(shape, 0.0);
        // Chipmunk multiplies the two shapes' elasticities: e here and 1 on
        // static bodies gives e against the ground (see pre_solve for pairs of
        // dynamic bodies).
        cpShapeSetElasticity(shape, spec.is_static ? 1.0 : scene_.restitution);
        space_.add(shape);
        return body;
    }

    // Shapes carry no mass (their density stays 0), so adding one leaves the
    // body's mass and moment as set.
    static cpShape* make_shape(cpBody* body, const Shape& shape) {
        if (shape.type == ShapeType::circle) {
            return cpCircleShapeNew(body, shape.radius, cpvzero);
        }
        // Raw: the scene's vertices as they are (convex, counter-clockwise,
        // which Chipmunk 7 expects), no hull and radius 0, so the polygon's
        // surface is the scene's.
        std::vector<cpVect> vertices;
        for (int i = 0; i < shape.polygon.count; ++i) {
            vertices.push_back(to_cp(shape.polygon.vertices[static_cast<std::size_t>(i)]));
        }
        return cpPolyShapeNewRaw(body, shape.polygon.count, vertices.data(), 0.0);
    }

    // A state past `largest_magnitude` would soon overflow to the infinity or NaN that
    // Chipmunk's sanity check aborts on: the run stops with a sentence first.
    void require_finite_state(double t) const {
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            if (scene_.bodies[i].is_static) {
                continue;
            }
            const BodyState s = state(static_cast<int>(i));
            const double largest = std::max(
                {std::fabs(s.position.x), std::fabs(s.position.y), std::fabs(s.angle),
                 std::fabs(s.velocity.x), std::fabs(s.velocity.y), std::fabs(s.angular_velocity)});
            if (!(largest <= largest_magnitude)) {
                throw InputError(scene_.file, body_path(scene_, i),
                                 "Chipmunk2D cannot go on at t = " + format_double(t) + " s: '" +
                                     scene_.bodies[i].name + "' reached " +
                                     significant_text(largest, 3) + " in position or velocity");
            }
        }
    }

    Scene scene_;
    ChipmunkSettings settings_;
    ArbiterRecorder recorder_; // declared before space_: the space points to it
    Space space_;
    std::vector<cpBody*> bodies_; // scene order; owned by space_
};

} // namespace

ChipmunkSettings chipmunk_settings_for(const Scene& scene) {
    ChipmunkSettings settings;
    double narrowest = std::numeric_limits<double>::infinity();
    for (const SceneBody& body : scene.bodies) {
        narrowest = std::min(narrowest, width_of(body.shape));
    }
    settings.collision_slop = chipmunk_slop_fraction * narrowest;
    settings.collision_bias = std::pow(1.0 - 0.1, 60.0);
    return settings;
}

std::string chipmunk_version() {
    return std::string("chipmunk ") + cpVersionString;
}

std::unique_ptr<Simulator> make_chipmunk_simulator(const Scene& scene,
                                                   const ChipmunkSettings& settings) {
    refuse_what_chipmunk_cannot_run(scene);
    swallow_debug_banner();
    return std::make_unique<ChipmunkSimulator>(scene, settings);
}

std::unique_ptr<Simulator> make_chipmunk_simulator(const Scene& scene) {
    return make_chipmunk_simulator(scene, chipmunk_settings_for(scene));
}

} // namespace impulse::harness
