// The impulse engine behind the harness's Simulator interface.
#include "input_error.h"
#include "memory_budget.h"
#include "number_format.h"
#include "progress.h"
#include "simulator.h"
#include "text.h"
#include "world.h"

#include <cmath>
#include <utility>

namespace impulse::harness {

namespace {

Body body_from(const SceneBody& spec) {
    Body body;
    body.shape = spec.shape;
    body.state = {spec.position, spec.angle, spec.velocity, spec.angular_velocity};
    if (!spec.is_static) {
        body.inv_mass = 1.0 / spec.mass;
        body.inv_inertia = spec.rotation ? 1.0 / spec.inertia : 0.0;
    }
    return body;
}

class ImpulseSimulator final : public Simulator {
  public:
    explicit ImpulseSimulator(const Scene& scene) : scene_(scene) {
        std::vector<Body> bodies;
        bodies.reserve(scene.bodies.size());
        std::uint64_t dynamic = 0;
        for (const SceneBody& spec : scene.bodies) {
            bodies.push_back(body_from(spec));
            dynamic += spec.is_static ? 0 : 1;
        }
        // World stepping's pair list grows as N^2 (docs/memory.md): refused
        // here, before it is built, when it would not fit.
        if (scene.solver.stepping == Stepping::world) {
            require_world_pairs_within_limit(dynamic, scene.bodies.size() - dynamic, scene.file);
        }
        world_ = make_world(std::move(bodies), scene.gravity, scene.restitution, scene.solver);
    }

    std::string engine() const override { return std::string("impulse ") + IMPULSE_VERSION; }

    std::vector<std::pair<std::string, std::string>> settings() const override {
        const SolverSettings& s = scene_.solver;
        std::vector<std::pair<std::string, std::string>> settings = {
            {"integrator", double_quoted(integrator_name(s.integrator))},
            {"toi", double_quoted(toi_method_name(s.toi))},
            {"dt", format_double(scene_.dt)},
            {"toi_tolerance", format_double(s.toi_tolerance)},
            {"contact_tolerance", format_double(s.contact_tolerance)},
            {"contacts", double_quoted(contact_mode_name(s.contacts))},
            {"ccd", s.ccd ? "true" : "false"},
            {"resting", s.resting ? "true" : "false"},
        };
        // Keys added after the format's first release are written only when
        // they differ from the seed's value: a run with the seed's setting then
        // writes the same bytes as before the key existed, so every golden
        // blessed earlier stays byte-identical (docs/formats.md).
        if (s.stepping != Stepping::world) {
            settings.emplace_back("stepping", double_quoted(stepping_name(s.stepping)));
        }
        if (s.vertex_normal != VertexNormal::reference_face) {
            settings.emplace_back("vertex_normal",
                                  double_quoted(vertex_normal_name(s.vertex_normal)));
        }
        return settings;
    }

    void step(double t0, double dt) override {
        const std::optional<StepError> error = impulse::step(world_, t0, dt, events_);
        // A NaN is named first: it is the cause of whatever else went wrong.
        refuse_non_finite(t0 + dt);
        if (error) {
            throw InputError(scene_.file, "", describe(*error));
        }
    }

    WorkCounters work() const override { return world_.work; }

    BodyState state(int index) const override { return world_.bodies[index].state; }

    std::vector<TrajectoryEvent> take_events() override {
        std::vector<TrajectoryEvent> out;
        out.reserve(events_.size());
        for (const CollisionEvent& e : events_) {
            out.push_back({e.time,
                           scene_.bodies[e.body_a].name,
                           scene_.bodies[e.body_b].name,
                           {e.point.x, e.point.y},
                           {e.normal.x, e.normal.y},
                           e.impulse,
                           e.vn_before,
                           e.vn_after});
        }
        events_.clear();
        return out;
    }

  private:
    // The NaN guard. Finite inputs of sensible size stay finite, but a
    // scene's numbers can overflow (a gravity of 1e308, a speed of 1e300 over
    // a long step), and a NaN then passes every "< 0" test unseen: nothing
    // would interpenetrate again and the trajectory could not be written as
    // JSON. So every dynamic body's state is checked after every step, and the
    // first value that is not finite stops the run, named with its time.
    void refuse_non_finite(double t) const {
        for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
            const Body& body = world_.bodies[i];
            if (body.is_static()) {
                continue;
            }
            const BodyState& s = body.state;
            const std::pair<const char*, double> values[] = {
                {"x", s.position.x},  {"y", s.position.y},  {"angle", s.angle},
                {"vx", s.velocity.x}, {"vy", s.velocity.y}, {"omega", s.angular_velocity}};
            for (const auto& [quantity, value] : values) {
                if (std::isfinite(value)) {
                    continue;
                }
                const std::string what = std::isnan(value) ? "NaN" : value > 0 ? "+inf" : "-inf";
                throw InputError(scene_.file, "",
                                 "'" + scene_.bodies[i].name + "'." + quantity + " became " + what +
                                     " at t = " + format_double(t) +
                                     " s: the scene's numbers overflow double precision (its "
                                     "gravity, speeds, sizes, dt or duration are too large)");
            }
        }
    }

    std::string describe(const StepError& error) const {
        const std::string a = "'" + scene_.bodies[error.body_a].name + "'";
        const std::string b = "'" + scene_.bodies[error.body_b].name + "'";
        const std::string at = "t = " + format_double(error.time) + " s";
        switch (error.failure) {
        case StepFailure::toi_not_converged:
            return "the time-of-impact search between " + a + " and " + b + " at " + at +
                   " did not reach solver.toi_tolerance = " +
                   format_double(scene_.solver.toi_tolerance) + " s within " +
                   std::to_string(scene_.solver.max_search_iterations) +
                   " iterations; raise the tolerance";
        case StepFailure::too_many_collisions:
            return "more than " + std::to_string(scene_.solver.max_collisions_per_step) +
                   " collisions between " + a + " and " + b + " within one step at " + at +
                   ": the bounces no longer end (a Zeno cascade); end the scene earlier";
        case StepFailure::resting_contact:
            return a + " and " + b + " are in resting contact at " + at +
                   " (touching, not approaching, interpenetrating just after), which the"
                   " seed's collision-only model cannot resolve; end the scene before the"
                   " bounces die out";
        case StepFailure::contact_problem_unsolved:
            return "the simultaneous contact problem around " + a + " and " + b + " at " + at +
                   " has no solution the solver could find (docs/engine.md, \"Simultaneous"
                   " contact\"); use contacts \"single\" for this scene";
        case StepFailure::sweep_not_converged:
            return "the swept test between " + a + " and " + b + " at " + at +
                   " needed more than " + std::to_string(scene_.solver.max_search_iterations) +
                   " advancement steps: the pair moves or spins too fast for its distance to"
                   " be bounded (a tunnel the engine cannot rule out); use a smaller dt";
        }
        return "the simulation stopped at " + at;
    }

    Scene scene_;
    World world_;
    std::vector<CollisionEvent> events_;
};

} // namespace

std::unique_ptr<Simulator> make_impulse_simulator(const Scene& scene) {
    return std::make_unique<ImpulseSimulator>(scene);
}

} // namespace impulse::harness
