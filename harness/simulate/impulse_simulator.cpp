// The impulse engine behind the harness's Simulator interface.
#include "input_error.h"
#include "memory_budget.h"
#include "number_format.h"
#include "progress.h"
#include "simulator.h"
#include "text.h"
#include "world.h"

#include <cmath>
#include <optional>
#include <unistd.h>
#include <utility>

namespace impulse::harness {

namespace {

// The mass ratio within one island beyond which a failure of its contact
// problem names the masses (ImpulseSimulator::mass_span): 1e8, two decades
// below the largest ratio measured to run, so the clause appears wherever
// rounding may be the cause and nowhere near the 1:100 of the canonical piles.
constexpr double resolvable_mass_ratio = 1e8;

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
        if (s.resting_method != RestingMethod::automatic) {
            settings.emplace_back("resting_method",
                                  double_quoted(resting_method_name(s.resting_method)));
        }
        return settings;
    }

    void step(double t0, double dt) override {
        const bool time_stepping_before = world_.work.time_stepping_from_step >= 0;
        const std::optional<StepError> error = impulse::step(world_, t0, dt, events_);
        // From the first step by the engine's rule for a pile (docs/engine.md)
        // is not a switch; a switch is noted at whatever step it happens, the
        // first included, when the step it redid went on (a failure is the one
        // sentence then).
        if (!error && !time_stepping_before && world_.work.time_stepping_switched != 0 &&
            scene_.solver.resting_method == RestingMethod::automatic) {
            note_switch(t0);
        }
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

    // The contact model a step failure comes from, for the setting its
    // sentence names: each model's cure is the next one up.
    enum class ContactModel { collisions_only, events, automatic_events, time_stepping };
    ContactModel model_in_use() const {
        const SolverSettings& s = scene_.solver;
        if (!s.resting) {
            return ContactModel::collisions_only;
        }
        if (s.resting_method == RestingMethod::events) {
            return ContactModel::events;
        }
        // "auto" keeps time-stepping once it has switched to it (the engine
        // records the step before it tries it, so a failure of that very
        // step is time-stepping's).
        if (time_stepping_from_start(s) || s.resting_method == RestingMethod::time_stepping ||
            world_.work.time_stepping_from_step >= 0) {
            return ContactModel::time_stepping;
        }
        return ContactModel::automatic_events;
    }

    std::string dt_and_tolerance() const {
        return "a smaller dt (now " + format_double(scene_.dt) +
               " s) or a larger solver.contact_tolerance (now " +
               format_double(scene_.solver.contact_tolerance) + " m)";
    }

    // Why a step's collisions did not end. Bounces that each separate the pair
    // (vn_after > 0) and come back are a Zeno cascade. An impulse that leaves
    // it still approaching changed nothing: after an impact with e = 0 in free
    // space the pair moves on touching, and its approach of rounding size
    // (1e-16 m/s) is below what an impulse can change (found by an outside
    // review: 4097 collisions with vn_before = vn_after = -1.4e-16 m/s).
    std::string cascade_kind() const {
        if (events_.empty() || events_.back().vn_after > 0.0) {
            return "the bounces no longer end (a Zeno cascade)";
        }
        return "the impulses no longer separate them (the last left them approaching at " +
               format_double(events_.back().vn_after) +
               " m/s, a speed of rounding size: the two stay in contact, as after an impact with "
               "e = 0)";
    }

    // What carries a scene on past a Zeno cascade or a resting contact.
    std::string carry_on(ContactModel model) const {
        switch (model) {
        case ContactModel::collisions_only:
            return "set \"resting\": true in the solver block (contact forces then end the "
                   "cascade and hold resting bodies), or end the scene earlier";
        case ContactModel::events:
            return "use \"resting_method\": \"auto\" or \"time-stepping\" in the solver block "
                   "(time-stepping holds every contact at every step, with no event search and no "
                   "cascade)";
        case ContactModel::automatic_events:
            return "set \"resting_method\": \"time-stepping\" in the solver block to use "
                   "time-stepping from the start";
        case ContactModel::time_stepping:
            break;
        }
        return "use " + dt_and_tolerance();
    }

    // The island's masses when they span more than resolvable_mass_ratio:
    // ": its masses span ...; bring those masses closer, or use ", else
    // "; use ".
    // The impulse a light body passes on between heavy ones is rounded at
    // the heavy ones' scale, and its velocity (impulse over its mass) then
    // carries that rounding times the ratio: measured on the canonical
    // 20-disc pile with one disc's mass times r and another's over r, the
    // run completes at a ratio of 1e10 and stops from 1e12 on at dt = 1/60 s,
    // from 1e14 on at 1/240 s (docs/engine.md, "Mass ratios in one island").
    std::string mass_span(const StepError& error) const {
        if (const std::optional<std::string> spin = spin_dominated(error)) {
            return *spin;
        }
        if (error.heaviest < 0 || error.lightest < 0) {
            return "; use ";
        }
        const SceneBody& heavy = scene_.bodies[static_cast<std::size_t>(error.heaviest)];
        const SceneBody& light = scene_.bodies[static_cast<std::size_t>(error.lightest)];
        if (!(heavy.mass > resolvable_mass_ratio * light.mass)) {
            return "; use ";
        }
        return ": its masses span a ratio of " + format_double(heavy.mass / light.mass) + " (" +
               body_named(error.heaviest) + ", " + format_double(heavy.mass) + " kg, to " +
               body_named(error.lightest) + ", " + format_double(light.mass) +
               " kg), and the impulses a light body passes on are rounded at the heavy ones' "
               "scale, which can take more digits than a double holds; bring those masses closer, "
               "or use ";
    }

    // A body of the failure whose moment of inertia is far below m R^2 (R its
    // farthest point from its centre): a contact's response to an impulse,
    // 1/m + (r x n)^2 / I (Eq. 9's denominator), is then nearly all spin, and
    // its 1/m is rounded away as a light body's velocity is between heavy
    // ones, past the same resolvable_mass_ratio. An outside review's 1 kg box
    // of inertia 1e-20 kg m^2 was told to change dt or the tolerance, neither
    // of which helps; measured on that box, the island is solved at
    // I = 1e-14 kg m^2 (m R^2 / I = 6e13) and unsolved from 1e-16 on.
    std::optional<std::string> spin_dominated(const StepError& error) const {
        for (const int index : {error.body_a, error.body_b, error.lightest, error.heaviest}) {
            if (index < 0 || static_cast<std::size_t>(index) >= scene_.bodies.size()) {
                continue;
            }
            const SceneBody& body = scene_.bodies[static_cast<std::size_t>(index)];
            const double reach = circumradius(body.shape);
            const double spread = body.mass * reach * reach;
            if (body.is_static || !body.rotation ||
                !(spread > resolvable_mass_ratio * body.inertia)) {
                continue;
            }
            const double uniform = body.mass * mass_properties(body.shape).inertia_per_unit_mass;
            return ": the moment of inertia of " + body_named(index) + ", " +
                   format_double(body.inertia) + " kg m^2, is " +
                   significant_text(body.inertia / spread, 2) +
                   " of m R^2 = " + significant_text(spread, 3) +
                   " kg m^2 (R its farthest point from its centre), so an impulse on it is "
                   "nearly all spin and its 1/m is lost in rounding; give it a larger \"inertia\" "
                   "(a uniform body of its shape and mass has " +
                   significant_text(uniform, 3) + " kg m^2), or use ";
        }
        return std::nullopt;
    }

    // `around`: " around 'a' and 'b'", or "" when the engine named no pair.
    std::string unsolved(const StepError& error, const std::string& around, const std::string& at,
                         ContactModel model) const {
        if (model == ContactModel::time_stepping) {
            return "the contact problem of the island" + around + " at " + at +
                   " has no solution the solver could find (docs/engine.md, \"Dense contact\")" +
                   mass_span(error) + dt_and_tolerance();
        }
        const bool simultaneous = scene_.solver.contacts == ContactMode::simultaneous;
        std::string cure;
        if (model == ContactModel::events || model == ContactModel::automatic_events) {
            cure = model == ContactModel::events
                       ? "\"resting_method\": \"auto\" or \"time-stepping\", "
                       : "\"resting_method\": \"time-stepping\", ";
        }
        if (simultaneous) {
            cure += "contacts \"single\", ";
        }
        return std::string("the ") + (simultaneous ? "simultaneous " : "") + "contact problem" +
               around + " at " + at + " has no solution the solver could find (docs/engine.md, \"" +
               (simultaneous ? "Simultaneous contact" : "Resting contact") + "\"); use " + cure +
               dt_and_tolerance();
    }

    // 'name', or "a body" when the engine could not say which (an island's
    // failure need not name one pair).
    std::string body_named(int index) const {
        const bool known = index >= 0 && static_cast<std::size_t>(index) < scene_.bodies.size();
        return known ? single_quoted(scene_.bodies[static_cast<std::size_t>(index)].name)
                     : std::string("a body");
    }

    std::string describe(const StepError& error) const {
        const std::string a = body_named(error.body_a);
        const std::string b = body_named(error.body_b);
        const std::string at = "t = " + format_double(error.time) + " s";
        const ContactModel model = model_in_use();
        switch (error.failure) {
        case StepFailure::toi_not_converged:
            return "the time-of-impact search between " + a + " and " + b + " at " + at +
                   " did not reach solver.toi_tolerance = " +
                   format_double(scene_.solver.toi_tolerance) + " s within " +
                   std::to_string(scene_.solver.max_search_iterations) +
                   " iterations; raise the tolerance";
        case StepFailure::too_many_collisions:
            return "more than " + std::to_string(scene_.solver.max_collisions_per_step) +
                   " collisions between " + a + " and " + b + " within one step at " + at + ": " +
                   cascade_kind() + "; " + carry_on(model);
        case StepFailure::resting_contact:
            return a + " and " + b + " are in resting contact at " + at +
                   " (touching, not approaching, interpenetrating just after), which " +
                   (model == ContactModel::collisions_only
                        ? "collisions alone (\"resting\": false) cannot hold"
                        : "the event model cannot hold (a contact that comes to rest within a "
                          "step)") +
                   "; " + carry_on(model);
        case StepFailure::contact_problem_unsolved:
            return unsolved(error,
                            error.body_a >= 0 && error.body_b >= 0 ? " around " + a + " and " + b
                                                                   : std::string(),
                            at, model);
        case StepFailure::contact_pass_through:
            return "the contact problem of the island around " + a + " and " + b + " at " + at +
                   " could not be solved within its product cap closely enough to keep " + a +
                   " from closing into " + b +
                   " by more than the two are thick, where they could "
                   "cross unseen (docs/engine.md, \"Dense contact\")" +
                   mass_span(error) + "a smaller dt (now " + format_double(scene_.dt) + " s)";
        case StepFailure::swept_crossing:
            return a + " passes through " + b + " at " + at +
                   " within one time step: the step holds the contact points its start sees, "
                   "and ccd's sweep of the step's motion found the pair crossing where none "
                   "held it (a body turning or moving far within a step; docs/engine.md, "
                   "\"Tunnelling\"); use a smaller dt (now " +
                   format_double(scene_.dt) + " s)";
        case StepFailure::sweep_not_converged:
            return "the swept test between " + a + " and " + b + " at " + at +
                   " needed more than " + std::to_string(scene_.solver.max_search_iterations) +
                   " advancement steps: the pair moves or spins too fast for its distance to"
                   " be bounded (a tunnel the engine cannot rule out); use a smaller dt";
        }
        return "the simulation stopped at " + at;
    }

    // Once per run, when "auto" leaves the event model for time-stepping in
    // the middle of a run: the trajectory then differs from an events run from
    // that step on, and a user comparing the two should know where. Standard
    // error only, so no output file and no stdout changes; on a terminal the
    // progress bar's line is erased first (it is redrawn below).
    void note_switch(double t) const {
        // A pass-through is caught by ccd's sweeps, which keep the event
        // model; "events" would be refused at load for it (tunnelling.h).
        const bool speed = world_.work.time_stepping_for_speed != 0;
        std::string text =
            "note: " + scene_.file +
            ": \"resting_method\": \"auto\" switched from events to time-stepping at t = " +
            format_double(t) +
            (speed ? " s, where two bodies could pass through each other within one step unseen "
                     "by the event model, and keeps it to the end; set \"ccd\": true to keep the "
                     "event model (its sweeps see such a pass), or \"resting_method\": "
                     "\"time-stepping\" to use time-stepping from the start\n"
                   : " s, where the event model could not go on, and keeps it to the end; set "
                     "\"resting_method\": \"time-stepping\" to use it from the start, or "
                     "\"events\" to stop there instead\n");
        if (::isatty(STDERR_FILENO) != 0) {
            text = "\r\x1b[K" + text;
        }
        // One write, so lines of scenes run side by side (check -j) never mix.
        [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text.data(), text.size());
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
