// The one first divergence (harness/gate/first_divergence.h): the earliest
// value over frames and events, its tie rule, its cause sentence, and every
// output of the real binary naming the same one.
#include "check_outcome.h"
#include "first_divergence.h"
#include "support/comparing.h"
#include "support/files.h"
#include "support/roots.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

using namespace impulse::harness;
using namespace impulse::test;
namespace fs = std::filesystem;

namespace {

using comparing::up;

// The sample's bounce, between box and ground.
TrajectoryEvent bounce(double t, double impulse) {
    return comparing::event(t, "box", "ground", impulse);
}

// One box, frames a quarter second apart, one bounce at t = 0.3 s.
Trajectory golden() {
    Trajectory t;
    t.scene = "drop";
    t.engine = "impulse 0.1.0";
    t.columns = {"t", "box.x", "box.y", "box.angle", "box.vx", "box.vy", "box.omega"};
    t.frames = {
        {0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 0.0},
        {0.25, 0.0, 2.75, 0.0, 0.0, -2.5, 0.0},
        {0.5, 0.0, 1.0, 0.0, 0.0, 1.5, 0.0},
        {0.75, 0.0, 1.25, 0.0, 0.0, 1.0, 0.0},
    };
    t.events = {bounce(0.3, 3.5)};
    return t;
}

// The golden with the bounce's impulse 1 ULP larger and every frame after
// the bounce moved: the new run a one-ULP change in Eq. 9 would give.
Trajectory one_ulp_impulse() {
    Trajectory t = golden();
    t.events[0].impulse = up(t.events[0].impulse);
    t.frames[2][5] = up(t.frames[2][5]); // box.vy at 0.5
    t.frames[3][2] = up(t.frames[3][2]); // box.y at 0.75
    return t;
}

// A throwaway project holding a copy of one canonical scene.
struct Project1 {
    TempDir temp;
    fs::path root;
    fs::path golden(const std::string& name) const { return root / "goldens" / (name + ".json"); }
    explicit Project1(const std::string& name) : root(make_root(temp, {name}, Goldens::none)) {}
};

} // namespace

TEST_CASE("The first divergence is the earliest over frames and events", "[first-divergence]") {
    const Comparison c = compare(golden(), one_ulp_impulse(), std::nullopt);
    const std::optional<FirstDivergence> first = first_divergence_of(c);
    REQUIRE(first);
    CHECK(first->divergence.column == "events[0].impulse");
    CHECK(first->divergence.t == 0.3);
    CHECK(first->is_event);
    CHECK(first->the_rest_follows);
    CHECK(first->divergence.ulp == 1);
    CHECK(first->cause ==
          "the first collision's impulse differs by 1 ULP; every later difference follows from it");
    CHECK(cause_key(c) == "events[0].impulse");
    CHECK_THAT(first_divergence_line(c),
               Catch::StartsWith("first divergence: events[0].impulse at t = 0.3 s (golden 3.5, "
                                 "new 3.5000000000000004): the first collision's impulse"));
}

TEST_CASE("Ties: an event before a frame at the same time, then column order",
          "[first-divergence]") {
    SECTION("an event and a frame at the same time: the event") {
        Trajectory gold = golden();
        gold.events[0].t = 0.5; // the bounce at the frame's time
        Trajectory value = gold;
        value.frames[2][5] = up(value.frames[2][5]);
        value.events[0].vn_after = up(value.events[0].vn_after);
        const Comparison c = compare(gold, value, std::nullopt);
        const Divergence* d = earliest_divergence(c);
        REQUIRE(d != nullptr);
        CHECK(d->column == "events[0].vn_after");
    }
    SECTION("an event stamped t0 + dt, a few ULP after the frame's k dt: still the event") {
        Trajectory gold = golden();
        gold.events[0].t = up(up(0.5)); // two ULP past the frame at 0.5
        Trajectory value = gold;
        value.frames[2][5] = up(value.frames[2][5]);
        value.events[0].impulse = up(value.events[0].impulse);
        const std::optional<FirstDivergence> first =
            first_divergence_of(compare(gold, value, std::nullopt));
        REQUIRE(first);
        CHECK(first->divergence.column == "events[0].impulse");
        CHECK(first->is_event);
    }
    SECTION("an event a millionth of a step after a frame: the frame comes first") {
        Trajectory gold = golden();
        gold.events[0].t = 0.5 + 0.25e-6;
        Trajectory value = gold;
        value.frames[2][5] = up(value.frames[2][5]);
        value.events[0].impulse = up(value.events[0].impulse);
        const Comparison c = compare(gold, value, std::nullopt);
        const Divergence* d = earliest_divergence(c);
        REQUIRE(d != nullptr);
        CHECK(d->column == "box.vy");
    }
    SECTION("two frame columns at the same time: the golden's column order") {
        Trajectory value = golden();
        value.frames[1][5] = up(value.frames[1][5]); // box.vy
        value.frames[1][2] = up(value.frames[1][2]); // box.y, an earlier column
        const Comparison c = compare(golden(), value, std::nullopt);
        const std::optional<FirstDivergence> first = first_divergence_of(c);
        REQUIRE(first);
        CHECK(first->divergence.column == "box.y");
        CHECK(first->divergence.t == 0.25);
        CHECK(first->cause == "box.y (the position channel) differs first, by 1 ULP; no collision "
                              "differs");
        CHECK(cause_key(c) == "the position channel");
    }
    SECTION("a frame earlier than the differing event: the frame, and it is said") {
        Trajectory value = one_ulp_impulse();
        value.frames[1][5] = up(value.frames[1][5]); // box.vy at 0.25, before the bounce
        const std::optional<FirstDivergence> first =
            first_divergence_of(compare(golden(), value, std::nullopt));
        REQUIRE(first);
        CHECK(first->divergence.column == "box.vy");
        CHECK_THAT(first->cause, Catch::EndsWith("before any collision differs"));
    }
    SECTION("a later event's field is named with its index") {
        Trajectory gold = golden();
        gold.events.push_back(bounce(0.6, 2.0));
        Trajectory value = gold;
        value.events[1].impulse = up(2.0);
        const std::optional<FirstDivergence> first =
            first_divergence_of(compare(gold, value, std::nullopt));
        REQUIRE(first);
        CHECK_THAT(first->cause, Catch::StartsWith("collision 2's (events[1]) impulse differs"));
    }
}

TEST_CASE("When the shapes differ too, the first divergence still comes first, then the shape",
          "[first-divergence]") {
    // A changed first impulse that also loses the second bounce: the event
    // counts differ, and the value that parted the runs is still events[0].
    Trajectory gold = golden();
    gold.events.push_back(bounce(0.6, 2.0));
    const Trajectory value = one_ulp_impulse();
    const Comparison c = compare(gold, value, std::nullopt);
    REQUIRE_FALSE(c.structural.empty());
    const std::string line = first_divergence_line(c);
    CHECK_THAT(line, Catch::StartsWith("first divergence: events[0].impulse at t = 0.3 s"));
    CHECK_THAT(line, Catch::Contains("; the trajectories also differ in shape: event counts "
                                     "differ: golden 2, new 1"));
    // summary.md and the page (outcome_line) name the same value and shape.
    SceneCheck check;
    check.status = SceneCheck::Status::failed;
    check.comparison = c;
    const std::string row = outcome_line(check);
    CHECK_THAT(row, Catch::StartsWith("events[0].impulse at t = 0.3 s"));
    CHECK_THAT(row, Catch::Contains("event counts differ: golden 2, new 1"));

    // With no compared value different, the shape is the whole line.
    Trajectory shorter = gold;
    shorter.events.pop_back();
    CHECK_THAT(first_divergence_line(compare(gold, shorter, std::nullopt)),
               Catch::StartsWith("event counts differ: golden 2, new 1"));
}

TEST_CASE("Scenes that start diverging at the same cause share one line", "[first-divergence]") {
    std::vector<SceneCheck> checks(3);
    const char* names[] = {"drop-box", "stack", "spin"};
    for (std::size_t i = 0; i < checks.size(); ++i) {
        checks[i].name = names[i];
        checks[i].status = SceneCheck::Status::failed;
    }
    checks[0].comparison = compare(golden(), one_ulp_impulse(), std::nullopt);
    checks[1].comparison = checks[0].comparison;
    Trajectory other = golden();
    other.frames[1][2] = up(other.frames[1][2]);
    checks[2].comparison = compare(golden(), other, std::nullopt);
    const std::vector<std::string> lines = shared_causes(checks);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0] == "2 scenes start diverging at events[0].impulse: drop-box, stack");
}

TEST_CASE("check, its JUnit and summary.md and diff all name the collision at t1",
          "[first-divergence]") {
    Project1 p("drop-box");
    const std::string root = p.root.string();
    REQUIRE(run_tool({"bless", "--root", root}).exit_code == 0);
    // A hand-made "engine change": the first bounce's impulse 1 ULP larger,
    // and the frames after it moved, in the golden itself.
    const Trajectory blessed = read_trajectory_file(p.golden("drop-box").string(), "a golden");
    REQUIRE(!blessed.events.empty());
    Trajectory moved = blessed;
    moved.events[0].impulse = up(moved.events[0].impulse);
    const double t1 = blessed.events[0].t;
    std::size_t later = 0;
    for (std::vector<double>& frame : moved.frames) {
        if (frame[0] > t1) {
            frame[5] = up(frame[5]); // box.vy
            ++later;
        }
    }
    REQUIRE(later > 0);
    spit(p.golden("drop-box"), write_trajectory(moved));
    const std::string cause = "the first collision's impulse differs by 1 ULP; every later "
                              "difference follows from it";

    const fs::path junit = p.temp.dir / "junit.xml";
    const fs::path report = p.temp.dir / "report";
    const Outcome o =
        run_tool({"check", "--root", root, "--junit", junit.string(), "--report", report.string()});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 1);
    CHECK(o.out.find("first divergence: events[0].impulse at t = ") != std::string::npos);
    CHECK(o.out.find(cause) != std::string::npos);
    const std::string xml = slurp(junit);
    CHECK(xml.find("events[0].impulse at t = ") != std::string::npos);
    // XML writes the apostrophe as &apos;.
    CHECK(xml.find("the first collision&apos;s impulse differs by 1 ULP; every later difference "
                   "follows from it") != std::string::npos);
    const std::string md = slurp(report / "summary.md");
    CHECK(md.find("events[0].impulse at t = ") != std::string::npos);
    CHECK(md.find(cause) != std::string::npos);
    CHECK(md.find("first divergence: box.") == std::string::npos);

    const fs::path fresh = p.temp.dir / "fresh.json";
    spit(fresh, write_trajectory(blessed));
    const Outcome d = run_tool({"diff", p.golden("drop-box").string(), fresh.string()});
    CHECK(d.exit_code == 1);
    CHECK(d.out.find("first divergence: events[0].impulse at t = ") != std::string::npos);
    CHECK(d.out.find("differs by 1 ULP") != std::string::npos);
}

TEST_CASE("check names a cause two scenes share in one line", "[first-divergence]") {
    TempDir temp;
    const fs::path root_dir = make_root(temp, {"drop-box", "drop-circle"}, Goldens::none);
    const std::string root = root_dir.string();
    REQUIRE(run_tool({"bless", "--root", root}).exit_code == 0);
    // The same "engine change" in both: the first bounce's impulse 1 ULP off.
    for (const char* name : {"drop-box", "drop-circle"}) {
        const fs::path golden = root_dir / "goldens" / (std::string(name) + ".json");
        Trajectory t = read_trajectory_file(golden.string(), "a golden");
        REQUIRE(!t.events.empty());
        t.events[0].impulse = up(t.events[0].impulse);
        spit(golden, write_trajectory(t));
    }
    const fs::path report = temp.dir / "report";
    const Outcome o = run_tool({"check", "--root", root, "--report", report.string()});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 1);
    const std::string line = "2 scenes start diverging at events[0].impulse: drop-box, drop-circle";
    CHECK(o.out.find(line) != std::string::npos);
    CHECK(slurp(report / "summary.md").find(line) != std::string::npos);
}
