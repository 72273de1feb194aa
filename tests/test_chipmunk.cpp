// The Chipmunk2D 7.0.3 reference (harness/simulate/chipmunk_simulator.cpp,
// docs/references.md "Chipmunk2D 7.0.3"), through the real binary: its
// settings recorded, the physics its model must give (Newton's law on the
// arrival velocities, momentum, energy of a free flight and of an elastic
// head-on, apex heights within a bound derived from its step), refusals as
// skips with one sentence, and `check` of a project that names it.
#ifdef IMPULSE_WITH_CHIPMUNK

#include "support/files.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"
#include "trajectory.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using impulse::harness::read_trajectory;
using impulse::harness::Trajectory;
using impulse::harness::TrajectoryEvent;
using impulse::test::run_tool;
using impulse::test::run_tool_in;
using impulse::test::slurp;
using impulse::test::spit;
using impulse::test::TempDir;

namespace {

const fs::path source_scenes = fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes";

// The solver block's value for `key`, as JSON text; "" when absent.
std::string setting(const Trajectory& t, const std::string& key) {
    for (const auto& [k, v] : t.solver) {
        if (k == key) {
            return v;
        }
    }
    return "";
}

std::size_t column(const Trajectory& t, const std::string& name) {
    const auto it = std::find(t.columns.begin(), t.columns.end(), name);
    REQUIRE(it != t.columns.end());
    return static_cast<std::size_t>(it - t.columns.begin());
}

Trajectory run_chipmunk(const fs::path& scene, const TempDir& temp) {
    const fs::path out = temp.dir / "trajectory.json";
    const impulse::test::Outcome o =
        run_tool({"run", "--engine", "chipmunk", scene.string(), "--out", out.string()});
    INFO(o.err);
    // Exit 1 is allowed: the scene's exact expectations are the impulse
    // engine's, and Chipmunk misses them by its own errors.
    REQUIRE(o.exited);
    REQUIRE((o.exit_code == 0 || o.exit_code == 1));
    return read_trajectory(slurp(out), out.string());
}

// Two discs of radius 0.5 on the x axis, 2 m apart centre to centre, closing
// at 3 m/s, no gravity: they touch after 1/3 s.
std::string head_on_scene(double e) {
    return R"({"schema": "impulse/scene@1", "name": "discs", "gravity": [0, 0],
  "restitution": )" +
           std::to_string(e) + R"(, "dt": 0.016666666666666666, "duration": 1.0,
  "bodies": [
    {"name": "left", "shape": {"circle": 0.5}, "mass": 1, "position": [-1, 0], "velocity": [2, 0]},
    {"name": "right", "shape": {"circle": 0.5}, "mass": 3, "position": [1, 0], "velocity": [-1, 0]}
  ]})";
}

} // namespace

TEST_CASE("Chipmunk: run --engine chipmunk records its version and every fairness setting, and "
          "nothing but the trajectory on standard output",
          "[chipmunk]") {
    const TempDir temp;
    const Trajectory t = run_chipmunk(source_scenes / "drop-box.json", temp);
    CHECK(t.engine == "chipmunk 7.0.3");
    CHECK(setting(t, "friction") == "0");
    CHECK(setting(t, "iterations") == "10");
    CHECK(setting(t, "restitution") == "0.8");
    // Chipmunk multiplies the two shapes' elasticities.
    CHECK(setting(t, "elasticity_dynamic") == "0.8");
    CHECK(setting(t, "elasticity_static") == "1");
    CHECK(setting(t, "pair_restitution") == "0.8");
    // 1e-3 of the narrowest body: the 1 m box and the 1 m thick ground.
    CHECK(setting(t, "collision_slop") == "0.001");
    CHECK(setting(t, "sleeping") == "false");
    CHECK(setting(t, "damping") == "0");
    CHECK(setting(t, "polygon_radius") == "0");
    CHECK(setting(t, "precision") == "\"double\"");

    // Debian's Chipmunk prints a debug banner with printf on its first
    // space: the trajectory on standard output must still be JSON alone.
    const impulse::test::Outcome o =
        run_tool({"run", "--engine", "chipmunk", (source_scenes / "head-on.json").string()});
    REQUIRE(o.exited);
    CHECK(o.out.find("Chipmunk v") == std::string::npos);
    CHECK(read_trajectory(o.out, "stdout").engine == "chipmunk 7.0.3");
}

TEST_CASE("Chipmunk: drop-box at e = 0.8 bounces by Newton's law on the arrival speed, gains "
          "energy in free flight as its integrator must, and reaches each apex within a step's "
          "travel",
          "[chipmunk]") {
    const TempDir temp;
    const Trajectory t = run_chipmunk(source_scenes / "drop-box.json", temp);
    const double g = 9.81, e = 0.8, h0 = 1.0, m = 1.0, h = 1.0 / 60.0;
    const double v0 = std::sqrt(2.0 * g * h0); // the exact first impact speed
    REQUIRE(t.events.size() >= 4);
    for (const TrajectoryEvent& event : t.events) {
        CHECK(event.a == "box");
        CHECK(event.b == "ground");
        CHECK(event.normal[0] == 0.0);
        CHECK(event.normal[1] == 1.0);
        // Chipmunk's bounce target is e times the velocity the box arrived
        // with, reached by its solver: Eq. 3 to rounding.
        CHECK(std::fabs(event.vn_after + e * event.vn_before) <= 1e-9 * std::fabs(event.vn_before));
    }
    // The contact is found at the end of the step that crosses the surface:
    // the arrival speed g h k is within one step's gain g h of v0.
    CHECK(std::fabs(-t.events[0].vn_before - v0) <= g * h);

    // Free flight before the first impact: Chipmunk moves positions with the
    // previous step's velocity, then adds gravity (forward Euler in the
    // frames), so y + v^2 / 2g rises by g h^2 / 2 each step: the energy is
    // E(0) + m g^2 h t / 2.
    const std::size_t y = column(t, "box.y"), vy = column(t, "box.vy");
    const auto energy = [&](const std::vector<double>& f) {
        return 0.5 * m * f[vy] * f[vy] + m * g * f[y];
    };
    const double e0 = energy(t.frames.front());
    for (const std::vector<double>& f : t.frames) {
        if (f[0] >= t.events[0].t) {
            break;
        }
        INFO("t = " << f[0]);
        CHECK(std::fabs(energy(f) - (e0 + 0.5 * m * g * g * h * f[0])) <= 1e-9);
    }

    // Apex n is e^(2n) h0 exactly. Each impact is found at most one step
    // late, the box at most v0 h past the surface, so each bounce adds at
    // most v0 h of error to the apex: n v0 h after n impacts (12 cm at n = 3
    // at 60 Hz; measured: under 3 mm).
    const double contact_height = 0.5; // the box's centre when it touches
    for (std::size_t n = 1; n <= 3; ++n) {
        double highest = -1e300;
        for (const std::vector<double>& f : t.frames) {
            if (f[0] > t.events[n - 1].t && f[0] < t.events[n].t) {
                highest = std::max(highest, f[y] - contact_height);
            }
        }
        INFO("apex " << n << ": " << highest);
        CHECK(std::fabs(highest - std::pow(e, 2.0 * static_cast<double>(n)) * h0) <=
              static_cast<double>(n) * v0 * h);
    }
}

TEST_CASE("Chipmunk: a zero-gravity head-on of two discs conserves momentum, and at e = 1 "
          "energy, to rounding, with the exact velocities after",
          "[chipmunk]") {
    for (const double e : {1.0, 0.8}) {
        INFO("e = " << e);
        const TempDir temp;
        spit(temp.dir / "discs.json", head_on_scene(e));
        const Trajectory t = run_chipmunk(temp.dir / "discs.json", temp);
        REQUIRE(t.events.size() == 1);
        const std::size_t lx = column(t, "left.vx"), rx = column(t, "right.vx");
        const double m1 = 1.0, m2 = 3.0, u1 = 2.0, u2 = -1.0;
        const double p0 = m1 * u1 + m2 * u2;
        const double k0 = 0.5 * m1 * u1 * u1 + 0.5 * m2 * u2 * u2;
        // One contact point: Chipmunk's first solver iteration reaches
        // vn = -e vn_before and the later ones apply nothing, so only
        // rounding remains (a few ulps of 1e-16 per operation).
        for (const std::vector<double>& f : t.frames) {
            CHECK(std::fabs(m1 * f[lx] + m2 * f[rx] - p0) <= 1e-12 * std::fabs(m1 * u1));
        }
        const std::vector<double>& last = t.frames.back();
        const double v1 = ((m1 - e * m2) * u1 + (1.0 + e) * m2 * u2) / (m1 + m2);
        const double v2 = ((m2 - e * m1) * u2 + (1.0 + e) * m1 * u1) / (m1 + m2);
        CHECK(std::fabs(last[lx] - v1) <= 1e-12);
        CHECK(std::fabs(last[rx] - v2) <= 1e-12);
        const double k1 = 0.5 * m1 * last[lx] * last[lx] + 0.5 * m2 * last[rx] * last[rx];
        if (e == 1.0) {
            CHECK(std::fabs(k1 - k0) <= 1e-12 * k0);
        }
        // The normal points toward body a, the lower scene index: left.
        CHECK(t.events[0].a == "left");
        CHECK(t.events[0].normal[0] == -1.0);
        CHECK(t.events[0].vn_before == -3.0);
    }
}

TEST_CASE("Chipmunk: a scene it cannot run is refused with one sentence naming the JSON path, "
          "before Chipmunk's debug checks can abort, and nothing is written",
          "[chipmunk]") {
    const TempDir temp;
    std::string tiny = head_on_scene(1.0);
    tiny.replace(tiny.find("\"mass\": 3"), 9, "\"mass\": 1e-120");
    spit(temp.dir / "tiny.json", tiny);
    const struct {
        fs::path scene;
        std::string path;
    } cases[] = {{source_scenes / "bullet.json", "solver.ccd"},
                 {temp.dir / "tiny.json", "bodies[1].mass"}};
    for (const auto& c : cases) {
        INFO(c.scene);
        const fs::path out = temp.dir / "out.json";
        const impulse::test::Outcome o =
            run_tool({"run", "--engine", "chipmunk", c.scene.string(), "--out", out.string()});
        REQUIRE(o.exited);
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("unsupported by chipmunk: ") != std::string::npos);
        CHECK(o.err.find(c.path + ": ") != std::string::npos);
        CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
        CHECK(!fs::exists(out));
    }
}

TEST_CASE("Chipmunk: a project naming the builtin chipmunk blesses and checks its goldens, and a "
          "scene it refuses is a skip",
          "[chipmunk]") {
    const TempDir temp;
    const fs::path dir = temp.dir / "project";
    spit(dir / "impulse.json", R"({"schema": "impulse/project@1", "scenes": ["scenes"],
  "engines": [{"name": "impulse", "builtin": "impulse"},
              {"name": "chipmunk", "builtin": "chipmunk"}]})");
    spit(dir / "scenes" / "discs.json", head_on_scene(1.0));
    spit(dir / "scenes" / "bullet.json", slurp(source_scenes / "bullet.json"));

    const impulse::test::Outcome blessed = run_tool_in(dir, {"bless", "--engine", "chipmunk"});
    INFO(blessed.out << blessed.err);
    REQUIRE(blessed.exited);
    CHECK(blessed.exit_code == 0);
    CHECK(fs::exists(dir / "goldens" / "chipmunk" / "discs.json"));
    CHECK(!fs::exists(dir / "goldens" / "chipmunk" / "bullet.json"));

    // The same bits again: Chipmunk runs deterministically in process.
    const impulse::test::Outcome checked = run_tool_in(dir, {"check", "--engine", "chipmunk"});
    INFO(checked.out << checked.err);
    REQUIRE(checked.exited);
    CHECK(checked.exit_code == 0);
    CHECK(checked.out.find("chipmunk/discs") != std::string::npos);
    CHECK(checked.out.find("SKIPPED") != std::string::npos);
    CHECK(checked.out.find("solver.ccd") != std::string::npos);
}

#endif // IMPULSE_WITH_CHIPMUNK
