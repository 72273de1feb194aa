// Box2D 2.4.1 behind the harness's Simulator interface, set up for a fair
// comparison (docs/physics.md, "Box2D, the second reference").
//
// Box2D is single precision: every number crosses the boundary through an
// explicit float conversion, and the settings say "precision": "single", so a
// reader of a Box2D trajectory knows its digits past about the seventh are noise.
#include "box2d_simulator.h"

#include "input_error.h"
#include "number_format.h"
#include "single_precision.h"
#include "text.h"

#include <box2d/box2d.h>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <utility>

namespace impulse::harness {

namespace {

// Box2D's skin: every polygon is rounded by this much (docs/physics.md).
constexpr double skin = static_cast<double>(b2_polygonRadius);

b2Vec2 to_b2(Vec2 v) {
    return {static_cast<float>(v.x), static_cast<float>(v.y)};
}

Vec2 from_b2(const b2Vec2& v) {
    return {static_cast<double>(v.x), static_cast<double>(v.y)};
}

// Four significant digits: warnings are read by people, not parsed.
std::string readable(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

std::string shape_path(std::size_t index) {
    return "bodies[" + std::to_string(index) + "].shape";
}

// ---------------------------------------------------------------- shapes

// true when the polygon is the box make_box(hx, hy) would give: SetAsBox then
// keeps Box2D's vertex order and normals exact, where Set would run its hull.
bool is_centred_box(const Polygon& polygon, double& hx, double& hy) {
    if (polygon.count != 4) {
        return false;
    }
    hx = std::fabs(polygon.vertices[0].x);
    hy = std::fabs(polygon.vertices[0].y);
    for (int i = 0; i < 4; ++i) {
        const Vec2 v = polygon.vertices[static_cast<std::size_t>(i)];
        if (std::fabs(v.x) != hx || std::fabs(v.y) != hy) {
            return false;
        }
    }
    // Four distinct corners of a convex polygon on |x| = hx, |y| = hy: a box.
    return hx > 0.0 && hy > 0.0;
}

// Moves every edge inward by r along its normal; vertex i, shared by edges
// i - 1 and i, goes to the intersection of the two offset edges:
// v - r (n0 + n1) / (1 + n0 . n1), which is v - r (n0 + n1) at a right angle.
std::vector<Vec2> offset_inward(const Polygon& polygon, double r) {
    const std::size_t count = static_cast<std::size_t>(polygon.count);
    std::vector<Vec2> out(count);
    for (std::size_t i = 0; i < count; ++i) {
        const Vec2 n0 = polygon.normals[(i + count - 1) % count];
        const Vec2 n1 = polygon.normals[i];
        out[i] = polygon.vertices[i] - (r / (1.0 + dot(n0, n1))) * (n0 + n1);
    }
    return out;
}

// A shrunk edge must keep its direction and stay longer than b2_linearSlop:
// shorter, Box2D's hull would weld its ends (closer than b2_linearSlop / 2),
// reversed, the offset polygon has turned inside out.
void check_shrunk(const Polygon& polygon, const std::vector<Vec2>& shrunk, const Scene& scene,
                  std::size_t index) {
    const std::size_t count = shrunk.size();
    const double min_edge = static_cast<double>(b2_linearSlop);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t j = (i + 1) % count;
        const Vec2 edge = polygon.vertices[j] - polygon.vertices[i];
        const double along = dot(shrunk[j] - shrunk[i], edge) / length(edge);
        if (along < min_edge) {
            const std::string left = along > 0.0 ? readable(along) + " m long" : "with no length";
            throw InputError(
                scene.file, shape_path(index),
                "too small for Box2D: shrunk by Box2D's skin b2_polygonRadius = " + readable(skin) +
                    " m, its edge " + std::to_string(i) + " is left " + left +
                    ", under b2_linearSlop = " + readable(min_edge) +
                    " m; make the polygon larger");
        }
    }
}

// The Box2D polygon whose skin surface (b2_polygonRadius outside it) is the
// scene's true surface (docs/physics.md: "correct heights for it").
b2PolygonShape box2d_polygon(const Polygon& polygon, const Scene& scene, std::size_t index) {
    if (polygon.count > b2_maxPolygonVertices) {
        throw InputError(scene.file, shape_path(index),
                         "a polygon Box2D cannot take: Box2D takes at most " +
                             std::to_string(b2_maxPolygonVertices) +
                             " polygon vertices, this one has " + std::to_string(polygon.count));
    }
    const std::vector<Vec2> shrunk = offset_inward(polygon, skin);
    check_shrunk(polygon, shrunk, scene, index);

    b2PolygonShape shape;
    double hx = 0.0;
    double hy = 0.0;
    if (is_centred_box(polygon, hx, hy)) {
        shape.SetAsBox(static_cast<float>(hx - skin), static_cast<float>(hy - skin));
        return shape;
    }
    std::vector<b2Vec2> points;
    points.reserve(shrunk.size());
    for (const Vec2& v : shrunk) {
        points.push_back(to_b2(v));
    }
    shape.Set(points.data(), static_cast<int32>(points.size()));
    return shape;
}

// One body's Box2D shape, built (and refused) before any Box2D object exists.
struct Box2dShape {
    bool is_circle = true;
    b2CircleShape circle;
    b2PolygonShape polygon;

    const b2Shape& get() const {
        return is_circle ? static_cast<const b2Shape&>(circle)
                         : static_cast<const b2Shape&>(polygon);
    }
};

Box2dShape box2d_shape(const SceneBody& spec, const Scene& scene, std::size_t index) {
    Box2dShape out;
    if (spec.shape.type == ShapeType::circle) {
        // Box2D resolves contacts to b2_linearSlop (it lets bodies overlap by
        // that much): a smaller circle would sink into what it lands on.
        const double min_radius = static_cast<double>(b2_linearSlop);
        if (spec.shape.radius < min_radius) {
            throw InputError(scene.file, shape_path(index),
                             "too small for Box2D: its radius " + readable(spec.shape.radius) +
                                 " m is under b2_linearSlop = " + readable(min_radius) +
                                 " m, the overlap Box2D tolerates; make the circle larger");
        }
        // Circles carry no skin in Box2D: their radius is the surface.
        out.circle.m_radius = static_cast<float>(spec.shape.radius);
        return out;
    }
    out.is_circle = false;
    out.polygon = box2d_polygon(spec.shape.polygon, scene, index);
    return out;
}

std::vector<Box2dShape> box2d_shapes(const Scene& scene) {
    std::vector<Box2dShape> shapes;
    shapes.reserve(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        shapes.push_back(box2d_shape(scene.bodies[i], scene, i));
    }
    return shapes;
}

// ---------------------------------------------------------------- clamps

// Box2D silently scales down a velocity that would move a body more than
// b2_maxTranslation, or turn it more than b2_maxRotation, in one step
// (docs/physics.md). The largest speed a body can reach is estimated as
// |v0| + |g| duration (free fall; collisions with e <= 1 do not add speed).
void warn_about_clamps(const Scene& scene, std::vector<std::string>& warnings) {
    const double dt_sub = scene.dt / static_cast<double>(scene.box2d.substeps);
    const double max_translation = static_cast<double>(b2_maxTranslation);
    const double max_rotation = static_cast<double>(b2_maxRotation);
    const std::string per_step =
        " per Box2D step of " + readable(dt_sub) + " s; Box2D will clamp it";
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& body = scene.bodies[i];
        if (body.is_static) {
            continue;
        }
        const std::string who = "bodies[" + std::to_string(i) + "] '" + body.name + "': ";
        const double speed = length(body.velocity) + length(scene.gravity) * scene.duration;
        if (speed * dt_sub > max_translation) {
            warnings.push_back(who + "speed up to " + readable(speed) +
                               " m/s moves more than b2_maxTranslation = " +
                               readable(max_translation) + " m" + per_step);
        }
        const double spin = std::fabs(body.angular_velocity);
        if (spin * dt_sub > max_rotation) {
            warnings.push_back(who + "angular speed " + readable(spin) +
                               " rad/s turns more than b2_maxRotation = pi/2 rad" + per_step);
        }
    }
}

// ---------------------------------------------------------------- events

// GetUserData has no const overload in 2.4.1.
std::size_t index_of(b2Body* body) {
    return static_cast<std::size_t>(body->GetUserData().pointer);
}

// Velocity of a point fixed to the body, in double.
Vec2 point_velocity(const b2Body* body, Vec2 point) {
    const Vec2 r = point - from_b2(body->GetWorldCenter());
    return from_b2(body->GetLinearVelocity()) +
           static_cast<double>(body->GetAngularVelocity()) * perp(r);
}

// Records one event per contact in the sub-step where it begins touching, in
// the order Box2D finds them (deterministic: Box2D runs single-threaded).
class ContactRecorder final : public b2ContactListener {
  public:
    explicit ContactRecorder(const Scene& scene) : scene_(scene) {}

    // Called before each world.Step with the end time of that sub-step.
    void begin_substep(double t_end) { t_end_ = t_end; }

    // Closes contacts Box2D found touching but never solved (none are
    // expected): no impulse, velocities as they are now.
    void end_substep() {
        for (const Pending& p : pending_) {
            events_[p.event].vn_after = relative_normal_velocity(p);
        }
        pending_.clear();
    }

    std::vector<TrajectoryEvent> take() { return std::exchange(events_, {}); }

    void PreSolve(b2Contact* contact, const b2Manifold* old_manifold) override {
        if (old_manifold->pointCount != 0 || contact->GetManifold()->pointCount == 0) {
            return; // touching already: its event was recorded when it began
        }
        b2Body* body_a = contact->GetFixtureA()->GetBody();
        b2Body* body_b = contact->GetFixtureB()->GetBody();
        const bool a_first = fixture_a_is_body_a(index_of(body_a), index_of(body_b));

        b2WorldManifold world_manifold;
        contact->GetWorldManifold(&world_manifold);
        Pending p;
        p.contact = contact;
        p.a = a_first ? body_a : body_b;
        p.b = a_first ? body_b : body_a;
        p.point = mean_point(world_manifold, contact->GetManifold()->pointCount);
        // Box2D's normal points from fixture A to fixture B; ours toward body A.
        const Vec2 normal = from_b2(world_manifold.normal);
        p.normal = a_first ? -normal : normal;
        p.event = events_.size();

        events_.push_back(contact_event(t_end_, scene_.bodies[index_of(p.a)].name,
                                        scene_.bodies[index_of(p.b)].name, p.point, p.normal,
                                        relative_normal_velocity(p)));
        pending_.push_back(p);
    }

    void PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) override {
        for (std::size_t k = 0; k < pending_.size(); ++k) {
            if (pending_[k].contact != contact) {
                continue;
            }
            TrajectoryEvent& event = events_[pending_[k].event];
            double total = 0.0;
            for (int32 j = 0; j < impulse->count; ++j) {
                total += static_cast<double>(impulse->normalImpulses[j]);
            }
            event.impulse = total;
            event.vn_after = relative_normal_velocity(pending_[k]);
            pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(k));
            return;
        }
    }

  private:
    struct Pending {
        b2Contact* contact = nullptr;
        std::size_t event = 0;
        b2Body* a = nullptr;
        b2Body* b = nullptr;
        Vec2 point;
        Vec2 normal; // toward a
    };

    // The engine's pair convention (docs/engine.md, "Body A and the normal"):
    // the dynamic body when the other is static, else the lower scene index.
    bool fixture_a_is_body_a(std::size_t i, std::size_t j) const {
        if (scene_.bodies[i].is_static != scene_.bodies[j].is_static) {
            return !scene_.bodies[i].is_static;
        }
        return i < j;
    }

    static Vec2 mean_point(const b2WorldManifold& manifold, int32 count) {
        Vec2 sum;
        for (int32 k = 0; k < count; ++k) {
            sum += from_b2(manifold.points[k]);
        }
        return (1.0 / static_cast<double>(count)) * sum;
    }

    // v_a - v_b at the contact point, along the normal toward a: negative while
    // approaching. In PreSolve these are the velocities the bodies arrived
    // with; Box2D's solver then adds the step's gravity kick g h before it
    // applies restitution, so a Box2D bounce leaves faster than e times the
    // arrival speed by e g h (0.13 m/s at 60 Hz, e = 0.8). vn_after + e vn_before
    // shows that error rather than hiding it.
    static double relative_normal_velocity(const Pending& p) {
        const Vec2 v = point_velocity(p.a, p.point) - point_velocity(p.b, p.point);
        return dot(v, p.normal);
    }

    const Scene& scene_;
    double t_end_ = 0.0;
    std::vector<TrajectoryEvent> events_;
    std::vector<Pending> pending_; // begun this sub-step, waiting for PostSolve
};

// ---------------------------------------------------------------- simulator

class Box2dSimulator final : public Simulator {
  public:
    Box2dSimulator(const Scene& scene, const std::vector<Box2dShape>& shapes)
        : scene_(scene), recorder_(scene_), world_(to_b2(scene.gravity)) {
        world_.SetContactListener(&recorder_);
        world_.SetAllowSleeping(false);
        // Box2D would otherwise always sweep dynamic bodies against static
        // ones; the impulse engine does so only when the scene says ccd.
        world_.SetContinuousPhysics(scene.solver.ccd);
        for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
            bodies_.push_back(create_body(i, shapes[i]));
        }
    }

    std::string engine() const override { return box2d_version(); }

    std::vector<std::pair<std::string, std::string>> settings() const override {
        const Box2dSettings& b = scene_.box2d;
        return {
            {"dt", format_double(scene_.dt)},
            {"substeps", std::to_string(b.substeps)},
            {"velocity_iterations", std::to_string(b.velocity_iterations)},
            {"position_iterations", std::to_string(b.position_iterations)},
            {"friction", "0"},
            {"restitution", format_double(scene_.restitution)},
            {"restitution_threshold", "0"},
            {"sleeping", "false"},
            {"damping", "0"},
            {"skin", format_double(skin)},
            {"continuous", scene_.solver.ccd ? "true" : "false"},
            {"precision", double_quoted("single")},
        };
    }

    void step(double t0, double dt) override {
        const int n = scene_.box2d.substeps;
        const double h = dt / static_cast<double>(n);
        for (int k = 1; k <= n; ++k) {
            const double t_end = k == n ? t0 + dt : t0 + static_cast<double>(k) * h;
            recorder_.begin_substep(t_end);
            world_.Step(static_cast<float>(h), scene_.box2d.velocity_iterations,
                        scene_.box2d.position_iterations);
            recorder_.end_substep();
        }
    }

    BodyState state(int index) const override {
        const b2Body* body = bodies_[static_cast<std::size_t>(index)];
        return {from_b2(body->GetWorldCenter()), static_cast<double>(body->GetAngle()),
                from_b2(body->GetLinearVelocity()),
                static_cast<double>(body->GetAngularVelocity())};
    }

    std::vector<TrajectoryEvent> take_events() override { return recorder_.take(); }

  private:
    b2Body* create_body(std::size_t index, const Box2dShape& shape) {
        const SceneBody& spec = scene_.bodies[index];
        b2BodyDef def;
        def.userData.pointer = static_cast<std::uintptr_t>(index);
        def.position = to_b2(spec.position); // the centre of mass: shapes are centred on it
        def.angle = static_cast<float>(spec.angle);
        if (!spec.is_static) {
            def.type = b2_dynamicBody;
            def.linearVelocity = to_b2(spec.velocity);
            def.angularVelocity = static_cast<float>(spec.angular_velocity);
            def.linearDamping = 0.0f; // docs/physics.md: no damping
            def.angularDamping = 0.0f;
            def.fixedRotation = !spec.rotation;
            def.allowSleep = false; // docs/physics.md: sleeping off
        }
        b2Body* body = world_.CreateBody(&def);
        const b2FixtureDef fixture = fixture_def(shape);
        body->CreateFixture(&fixture);
        if (!spec.is_static) {
            set_mass(body, spec);
        }
        return body;
    }

    b2FixtureDef fixture_def(const Box2dShape& shape) const {
        b2FixtureDef def;
        def.shape = &shape.get();
        def.friction = 0.0f; // docs/physics.md: friction 0 on every fixture
        // Box2D mixes restitutions with max; every fixture has the scene's e.
        def.restitution = static_cast<float>(scene_.restitution);
        // The default (1 m/s) silently turns slower bounces into e = 0.
        def.restitutionThreshold = 0.0f;
        def.density = 0.0f; // the mass is set explicitly below
        return def;
    }

    // Box2D would compute the mass from the shrunken polygon's area; the
    // scene's mass and inertia are the true body's.
    static void set_mass(b2Body* body, const SceneBody& spec) {
        b2MassData mass;
        mass.mass = static_cast<float>(spec.mass);
        mass.center = b2Vec2(0.0f, 0.0f);
        mass.I = spec.rotation ? static_cast<float>(spec.inertia) : 0.0f;
        body->SetMassData(&mass);
    }

    Scene scene_;
    ContactRecorder recorder_; // declared before world_: the world holds a pointer to it
    b2World world_;
    std::vector<b2Body*> bodies_; // scene order; owned by world_
};

} // namespace

// From b2_version, with one correction: Box2D v2.4.1 shipped with b2_version
// still {2, 4, 0} (its successor v2.4.2 likewise says 2.4.1, erincatto/box2d#778).
// This file uses b2FixtureDef::restitutionThreshold, new in 2.4.1, so a
// library that says 2.4.0 here is 2.4.1.
std::string box2d_version() {
    b2Version v = b2_version;
    if (v.major == 2 && v.minor == 4 && v.revision == 0) {
        v.revision = 1;
    }
    return "box2d " + std::to_string(v.major) + "." + std::to_string(v.minor) + "." +
           std::to_string(v.revision);
}

std::unique_ptr<Simulator> make_box2d_simulator(const Scene& scene,
                                                std::vector<std::string>& warnings) {
    // Before any float conversion: what single precision cannot hold makes
    // Box2D assert (m_I > 0 for a mass of 1e39 kg) or compute nonsense.
    require_single_precision(scene, "Box2D", scene.dt / static_cast<double>(scene.box2d.substeps));
    const std::vector<Box2dShape> shapes = box2d_shapes(scene);
    warn_about_clamps(scene, warnings);
    return std::make_unique<Box2dSimulator>(scene, shapes);
}

} // namespace impulse::harness
