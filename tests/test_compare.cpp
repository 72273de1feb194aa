// Comparing trajectories: the ULP metric, the tolerance rule and its
// command-line form, exact and tolerance comparisons with their reports, and
// the `impulse diff` verb.
#include "cli.h"
#include "compare.h"
#include "input_error.h"
#include "sha256.h"
#include "support/tool.h"
#include "tolerance.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace impulse::harness;
using Catch::Contains;
using impulse::test::Outcome;

namespace {

namespace fs = std::filesystem;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double quiet_nan = std::numeric_limits<double>::quiet_NaN();
constexpr double tiny = std::numeric_limits<double>::denorm_min();

double up(double value, int ulps = 1) {
    for (int i = 0; i < ulps; ++i) {
        value = std::nextafter(value, inf);
    }
    return value;
}

std::uint64_t bits_of(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

TrajectoryEvent event(double t, const std::string& a, const std::string& b, double impulse) {
    TrajectoryEvent e;
    e.t = t;
    e.a = a;
    e.b = b;
    e.point[0] = 0.25;
    e.point[1] = 0.0;
    e.normal[0] = 0.0;
    e.normal[1] = 1.0;
    e.impulse = impulse;
    e.vn_before = -2.0;
    e.vn_after = 1.5;
    return e;
}

// One body, four frames a quarter second apart, two events. Values are chosen
// so that differences can be worked out by hand.
Trajectory sample() {
    Trajectory t;
    t.scene = "drop";
    t.scene_sha256 = sha256_hex("drop scene");
    t.engine = "impulse 0.1.0";
    t.solver = {{"integrator", "\"verlet\""}, {"dt", "0.25"}};
    t.columns = {"t", "box.x", "box.y", "box.angle", "box.vx", "box.vy", "box.omega"};
    t.frames = {
        {0.0, 0.0, 3.0, 0.5, 0.0, 0.0, 0.0},
        {0.25, 0.5, 2.75, 0.5, 0.0, -2.5, 0.0},
        {0.5, 0.5, 1.0, 0.5, 0.0, -5.0, 0.0},
        {0.75, 0.5, 0.5, 0.5, 2.0, 4.0, 0.0},
    };
    t.events = {event(0.625, "box", "ground", 3.5), event(0.7, "box", "ground", 1.25)};
    return t;
}

ChannelTolerance tol(double atol, double rtol, std::uint64_t ulp) {
    ChannelTolerance t;
    t.atol = atol;
    t.rtol = rtol;
    t.ulp = ulp;
    return t;
}

Tolerances every_channel(ChannelTolerance t) {
    Tolerances tolerances;
    for (auto& slot : tolerances.channels) {
        slot = t;
    }
    return tolerances;
}

const ChannelSummary& summary(const Comparison& c, Channel channel) {
    return c.channels[static_cast<std::size_t>(channel)];
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

// A trajectory file that removes itself.
struct TempFile {
    fs::path path;
    TempFile(const std::string& name, const std::string& content) {
        static int counter = 0;
        path = fs::temp_directory_path() / ("impulse-compare-" + std::to_string(::getpid()) + "-" +
                                            std::to_string(counter++) + "-" + name);
        std::ofstream(path, std::ios::binary) << content;
    }
    ~TempFile() { fs::remove(path); }
    std::string str() const { return path.string(); }
};

Outcome diff(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    Outcome o;
    o.exited = true;
    o.exit_code = impulse::harness::cli::diff_verb(args, out, err);
    o.out = out.str();
    o.err = err.str();
    return o;
}

// The whole tool's entry point, for the exit code main() makes of exceptions.
Outcome impulse_main(std::vector<std::string> args) {
    args.insert(args.begin(), "impulse");
    std::vector<char*> argv;
    for (std::string& arg : args) {
        argv.push_back(arg.data());
    }
    std::ostringstream out, err;
    std::streambuf* old_out = std::cout.rdbuf(out.rdbuf());
    std::streambuf* old_err = std::cerr.rdbuf(err.rdbuf());
    Outcome o;
    o.exited = true;
    o.exit_code = impulse::harness::cli::main(static_cast<int>(argv.size()), argv.data());
    std::cout.rdbuf(old_out);
    std::cerr.rdbuf(old_err);
    o.out = out.str();
    o.err = err.str();
    return o;
}

} // namespace

TEST_CASE("ulp_distance counts representable doubles between two values", "[compare]") {
    CHECK(ulp_distance(1.0, 1.0) == 0);
    CHECK(ulp_distance(1.0, std::nextafter(1.0, 2.0)) == 1);
    CHECK(ulp_distance(std::nextafter(1.0, 2.0), 1.0) == 1);
    CHECK(ulp_distance(1.0, std::nextafter(1.0, 0.0)) == 1); // across a binade boundary
    CHECK(ulp_distance(-1.0, std::nextafter(-1.0, -2.0)) == 1);
    CHECK(ulp_distance(1.0, up(1.0, 5)) == 5);

    SECTION("across zero") {
        CHECK(ulp_distance(0.0, -0.0) == 0);
        CHECK(ulp_distance(-0.0, tiny) == 1);
        CHECK(ulp_distance(0.0, -tiny) == 1);
        CHECK(ulp_distance(-tiny, tiny) == 2);
        CHECK(ulp_distance(std::nextafter(0.0, -1.0), std::nextafter(0.0, 1.0)) == 2);
        CHECK(ulp_distance(-1.0, 1.0) == 2 * bits_of(1.0));
        const double max = std::numeric_limits<double>::max();
        CHECK(ulp_distance(-max, max) == 2 * bits_of(max));
    }
    SECTION("infinities sit one step beyond the largest double; NaN saturates") {
        CHECK(ulp_distance(std::numeric_limits<double>::max(), inf) == 1);
        CHECK(ulp_distance(quiet_nan, 1.0) == UINT64_MAX);
        CHECK(ulp_distance(1.0, quiet_nan) == UINT64_MAX);
        CHECK(ulp_distance(quiet_nan, quiet_nan) == UINT64_MAX);
    }
}

TEST_CASE("within passes at the bound and fails one ULP past it", "[compare]") {
    SECTION("atol") {
        CHECK(within(tol(0.5, 0.0, 0), 1.0, 1.5));
        CHECK(within(tol(0.5, 0.0, 0), 1.0, 0.5));
        CHECK_FALSE(within(tol(0.5, 0.0, 0), 1.0, up(1.5)));
    }
    SECTION("rtol scales with the golden value") {
        CHECK(within(tol(0.0, 0.25, 0), 2.0, 2.5));
        CHECK(within(tol(0.0, 0.25, 0), -2.0, -2.5));
        CHECK_FALSE(within(tol(0.0, 0.25, 0), 2.0, up(2.5)));
        CHECK(within(tol(0.25, 0.125, 0), 2.0, 2.5)); // atol + rtol * |gold|
        CHECK_FALSE(within(tol(0.25, 0.125, 0), 2.0, up(2.5)));
    }
    SECTION("ulp alone suffices") {
        CHECK(within(tol(0.0, 0.0, 2), 1.0, up(1.0, 2)));
        CHECK_FALSE(within(tol(0.0, 0.0, 2), 1.0, up(1.0, 3)));
        CHECK(within(tol(0.0, 0.0, 1), -tiny, 0.0));
        CHECK(within(tol(0.0, 0.0, 0), 0.0, -0.0)); // the zeros are equal values
    }
    SECTION("zero tolerance is exact equality of values") {
        CHECK(within(tol(0.0, 0.0, 0), 1.0, 1.0));
        CHECK_FALSE(within(tol(0.0, 0.0, 0), 1.0, up(1.0)));
    }
    SECTION("NaN never passes") {
        CHECK_FALSE(within(tol(inf, 0.0, UINT64_MAX), quiet_nan, 1.0));
        CHECK_FALSE(within(tol(inf, 0.0, UINT64_MAX), 1.0, quiet_nan));
    }
}

TEST_CASE("column_channel maps frame columns to channels", "[compare]") {
    CHECK(column_channel("t") == Channel::event_time);
    CHECK(column_channel("box.x") == Channel::position);
    CHECK(column_channel("box.y") == Channel::position);
    CHECK(column_channel("box.angle") == Channel::angle);
    CHECK(column_channel("box.vx") == Channel::velocity);
    CHECK(column_channel("box.vy") == Channel::velocity);
    CHECK(column_channel("box.omega") == Channel::angular_velocity);
    CHECK(column_channel("wheel.left.omega") == Channel::angular_velocity);
    CHECK_FALSE(column_channel("box.z"));
    CHECK_FALSE(column_channel(".x"));
    CHECK_FALSE(column_channel("x"));
}

TEST_CASE("parse_tolerance_option reads one value or channel=value pairs", "[compare]") {
    SECTION("one value for every channel") {
        const Tolerances t = parse_tolerance_option("--atol", "1e-9", Tolerances{});
        for (const auto& slot : t.channels) {
            REQUIRE(slot);
            CHECK(slot->atol == 1e-9);
            CHECK(slot->rtol == 0.0);
            CHECK(slot->ulp == 0);
        }
    }
    SECTION("pairs replace one field and keep the others") {
        Tolerances base;
        base[Channel::position] = tol(1.0, 0.125, 4);
        const Tolerances t = parse_tolerance_option("--atol", "position=1e-9,velocity=1e-6", base);
        REQUIRE(t[Channel::position]);
        CHECK(t[Channel::position]->atol == 1e-9);
        CHECK(t[Channel::position]->rtol == 0.125);
        CHECK(t[Channel::position]->ulp == 4);
        REQUIRE(t[Channel::velocity]);
        CHECK(t[Channel::velocity]->atol == 1e-6);
        CHECK(t[Channel::velocity]->rtol == 0.0);
        CHECK_FALSE(t[Channel::angle]);
        CHECK_FALSE(t[Channel::event_time]);
    }
    SECTION("rtol and ulp set their own fields") {
        Tolerances t = parse_tolerance_option("--rtol", "angular_velocity=0.5", Tolerances{});
        t = parse_tolerance_option("--ulp", "3", t);
        CHECK(t[Channel::angular_velocity]->rtol == 0.5);
        CHECK(t[Channel::angular_velocity]->ulp == 3);
        CHECK(t[Channel::event_time]->ulp == 3);
        CHECK(t[Channel::event_time]->rtol == 0.0);
        t = parse_tolerance_option("--ulp", "impulse=18446744073709551615", t);
        CHECK(t[Channel::impulse]->ulp == UINT64_MAX);
    }
    SECTION("a negative zero is stored as zero") {
        const Tolerances t = parse_tolerance_option("--atol", "-0", Tolerances{});
        CHECK_FALSE(std::signbit(t[Channel::position]->atol));
    }
    SECTION("bad text names the option and the bad part") {
        const Tolerances base;
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "x", base),
                          Contains("--atol") && Contains("'x'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "", base), Contains("--atol"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "-1e-9", base), Contains("'-1e-9'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "inf", base), Contains("'inf'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "nan", base), Contains("'nan'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--rtol", "1e-9 ", base), Contains("--rtol"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "positon=1e-9", base),
                          Contains("'positon'") && Contains("position, angle, velocity"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=", base),
                          Contains("''") && Contains("'position='"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=1e-9,", base),
                          Contains("not channel=value"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=1e-9,1e-6", base),
                          Contains("'1e-6'") && Contains("not channel=value"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=1,position=2", base),
                          Contains("twice"));
        CHECK_THROWS_WITH(parse_tolerance_option("--ulp", "1.5", base),
                          Contains("--ulp") && Contains("'1.5'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--ulp", "velocity=-1", base),
                          Contains("'-1'") && Contains("'velocity=-1'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--ulp", "18446744073709551616", base),
                          Contains("'18446744073709551616'"));
        CHECK_THROWS_AS(parse_tolerance_option("--atol", "x", base), std::invalid_argument);
        CHECK_THROWS_AS(parse_tolerance_option("--bogus", "1", base), std::invalid_argument);
    }
}

TEST_CASE("channels_without_tolerance lists what the golden needs", "[compare]") {
    const Trajectory gold = sample();
    Tolerances t;
    t[Channel::position] = tol(1e-9, 0.0, 0);
    t[Channel::velocity] = tol(1e-9, 0.0, 0);
    CHECK(channels_without_tolerance(gold, t) ==
          std::vector<Channel>{Channel::angle, Channel::angular_velocity, Channel::impulse,
                               Channel::event_time});
    CHECK(channels_without_tolerance(gold, every_channel(tol(0, 0, 0))).empty());

    Trajectory frames_only = gold;
    frames_only.events.clear();
    frames_only.columns = {"t", "box.x"};
    for (auto& frame : frames_only.frames) {
        frame.resize(2);
    }
    CHECK(channels_without_tolerance(frames_only, Tolerances{}) ==
          std::vector<Channel>{Channel::position, Channel::event_time});

    Trajectory empty = gold;
    empty.frames.clear();
    empty.events.clear();
    CHECK(channels_without_tolerance(empty, Tolerances{}).empty());
}

TEST_CASE("identical trajectories compare identical in both modes", "[compare]") {
    const Trajectory gold = sample();
    const Comparison exact = compare(gold, gold, std::nullopt);
    CHECK(exact.identical);
    CHECK(exact.passed);
    CHECK(exact.structural.empty());
    CHECK(exact.first_divergences.empty());
    // 4 frames x (t) + 2 events x (t) = 10 times; 4 x 2 + 2 x 2 positions.
    CHECK(summary(exact, Channel::event_time).compared == 6);
    CHECK(summary(exact, Channel::position).compared == 12);
    CHECK(summary(exact, Channel::impulse).compared == 2);
    CHECK(describe(exact) == "identical\n");

    const Comparison tolerant = compare(gold, gold, every_channel(tol(0, 0, 0)));
    CHECK(tolerant.identical);
    CHECK(tolerant.passed);
}

TEST_CASE("one value one ULP off", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.frames[2][2] = up(value.frames[2][2]); // box.y at t = 0.5: 1 -> 1 + 2^-52

    SECTION("exact mode fails naming the column, the frame time and ulp 1") {
        const Comparison c = compare(gold, value, std::nullopt);
        CHECK_FALSE(c.identical);
        CHECK_FALSE(c.passed);
        CHECK(c.structural.empty());
        REQUIRE(c.first_divergences.size() == 1);
        const Divergence& d = c.first_divergences.front();
        CHECK(d.column == "box.y");
        CHECK(d.channel == Channel::position);
        CHECK(d.frame == 2);
        CHECK(d.t == 0.5);
        CHECK(d.gold == 1.0);
        CHECK(d.value == up(1.0));
        CHECK(d.abs_diff == 0x1p-52);
        // Relative to the column's largest golden |y| (3); 1 ULP at that
        // scale's spacing 2^-51 rounds up to 1.
        CHECK(d.rel_diff == 0x1p-52 / 3.0);
        CHECK(d.ulp == 1);

        const std::string text = describe(c);
        CHECK_THAT(text, Contains("first divergence per body and channel:"));
        CHECK_THAT(text, Contains("box.y  t = 0.5  golden 1  new 1.0000000000000002  abs 2.2e-16  "
                                  "rel 7.4e-17  ulp 1"));
        CHECK_THAT(text, Contains("per channel:"));
        CHECK_THAT(text, Contains("1/12 values differ"));
    }
    SECTION("tolerance mode with ulp 1 passes") {
        const Comparison c = compare(gold, value, every_channel(tol(0, 0, 1)));
        CHECK_FALSE(c.identical);
        CHECK(c.passed);
        CHECK(c.first_divergences.empty());
        CHECK(summary(c, Channel::position).differing == 0);
        CHECK(summary(c, Channel::position).max_ulp == 1); // how close it came
    }
    SECTION("tolerance mode with ulp 0 and atol 0 fails") {
        const Comparison c = compare(gold, value, every_channel(tol(0, 0, 0)));
        CHECK_FALSE(c.passed);
        REQUIRE(c.first_divergences.size() == 1);
        CHECK(c.first_divergences.front().column == "box.y");
    }
    SECTION("a missing tolerance is refused, never defaulted") {
        Tolerances t = every_channel(tol(0, 0, 1));
        t[Channel::event_time].reset();
        CHECK_THROWS_AS(compare(gold, value, t), std::invalid_argument);
    }
}

TEST_CASE("Negative and positive zero are told apart in exact mode only", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.frames[1][6] = -0.0; // box.omega at t = 0.25

    const Comparison exact = compare(gold, value, std::nullopt);
    CHECK_FALSE(exact.identical);
    CHECK_FALSE(exact.passed);
    REQUIRE(exact.first_divergences.size() == 1);
    const Divergence& d = exact.first_divergences.front();
    CHECK(d.column == "box.omega");
    CHECK(d.channel == Channel::angular_velocity);
    CHECK(d.t == 0.25);
    CHECK(d.abs_diff == 0.0);
    CHECK(d.rel_diff == 0.0);
    CHECK(d.ulp == 0);
    CHECK_THAT(describe(exact), Contains("golden 0  new -0.0"));
    CHECK(summary(exact, Channel::angular_velocity).differing == 1);

    const Comparison tolerant = compare(gold, value, every_channel(tol(0, 0, 0)));
    CHECK_FALSE(tolerant.identical);
    CHECK(tolerant.passed);
}

TEST_CASE("a changed event impulse is the event's divergence", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.events[1].impulse = 1.5; // golden 1.25
    value.events[1].vn_after = 1.0;

    const Comparison c = compare(gold, value, std::nullopt);
    CHECK_FALSE(c.passed);
    CHECK(c.structural.empty());
    // Only the first divergent field of the first divergent event is listed.
    REQUIRE(c.first_divergences.size() == 1);
    const Divergence& d = c.first_divergences.front();
    CHECK(d.column == "events[1].impulse");
    CHECK(d.channel == Channel::impulse);
    CHECK(d.frame == 1);
    CHECK(d.t == 0.7);
    CHECK(d.gold == 1.25);
    CHECK(d.value == 1.5);
    CHECK(d.abs_diff == 0.25);
    CHECK(d.rel_diff == 0.25 / 3.5); // relative to the largest golden impulse, 3.5
    CHECK(summary(c, Channel::impulse).differing == 1);
    CHECK(summary(c, Channel::velocity).differing == 1);
    CHECK_THAT(describe(c), Contains("events[1].impulse  t = 0.7  golden 1.25  new 1.5"));

    CHECK(compare(gold, value, every_channel(tol(0.5, 0, 0))).passed);
}

TEST_CASE("per-channel counts and maxima", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.frames[1][1] = up(0.5);     // box.x: 0.5 + 2^-53, 1 ulp
    value.frames[2][2] = up(1.0, 3);  // box.y: 1 + 3 * 2^-52, 3 ulps
    value.frames[3][4] = 2.5;         // box.vx: 2 -> 2.5, 0.5 / 2^-51 = 2^50 ulps
    value.events[0].point[0] = 0.375; // events[0].point.x: 0.25 -> 0.375
    value.events[0].impulse = 3.5;    // unchanged
    value.frames[0][3] = up(0.5, 2);  // box.angle at t = 0

    const Comparison c = compare(gold, value, std::nullopt);
    const ChannelSummary& position = summary(c, Channel::position);
    CHECK(position.compared == 12); // box.x, box.y in 4 frames; point.x, point.y in 2 events
    CHECK(position.differing == 3);
    CHECK(position.max_abs == 0.125);
    // A contact point is measured at the scale of the bodies' positions too
    // (the largest |x| or |y| over the frames, 3), not only of the points' own.
    CHECK(position.max_rel == 0.125 / 3.0);
    CHECK(position.max_ulp == (std::uint64_t{1} << 48)); // 0.125 over the ULP of [2, 4), 2^-51

    const ChannelSummary& velocity = summary(c, Channel::velocity);
    CHECK(velocity.compared == 12);
    CHECK(velocity.differing == 1);
    CHECK(velocity.max_abs == 0.5);
    CHECK(velocity.max_rel == 0.25);
    CHECK(velocity.max_ulp == (std::uint64_t{1} << 50));

    const ChannelSummary& angle = summary(c, Channel::angle);
    CHECK(angle.compared == 8); // box.angle in 4 frames; normal.x, normal.y in 2 events
    CHECK(angle.differing == 1);
    CHECK(angle.max_abs == 0x1p-52);
    CHECK(angle.max_ulp == 2);

    CHECK(summary(c, Channel::impulse).differing == 0);
    CHECK(summary(c, Channel::impulse).max_abs == 0.0);
    CHECK(summary(c, Channel::angular_velocity).compared == 4);
    CHECK(summary(c, Channel::event_time).compared == 6);

    // In column order, then the event.
    REQUIRE(c.first_divergences.size() == 5);
    CHECK(c.first_divergences[0].column == "box.x");
    CHECK(c.first_divergences[1].column == "box.y");
    CHECK(c.first_divergences[2].column == "box.angle");
    CHECK(c.first_divergences[3].column == "box.vx");
    CHECK(c.first_divergences[4].column == "events[0].point.x");

    SECTION("tolerance mode counts only values outside the tolerance") {
        Tolerances t = every_channel(tol(0, 0, 0));
        t[Channel::position] = tol(0.0, 0.0, 3); // the frame ULPs pass, the event point does not
        const Comparison tc = compare(gold, value, t);
        CHECK_FALSE(tc.passed);
        CHECK(summary(tc, Channel::position).differing == 1);
        CHECK(summary(tc, Channel::position).max_abs == 0.125);
        CHECK(summary(tc, Channel::velocity).differing == 1);
    }
    SECTION("the description has one aligned line per divergent column") {
        const std::vector<std::string> lines = lines_of(describe(c));
        REQUIRE(lines.size() >= 6);
        CHECK(lines[0] == "first divergence per body and channel:");
        const std::size_t t_at = lines[1].find("t = ");
        const std::size_t golden_at = lines[1].find("golden ");
        for (std::size_t i = 1; i <= 5; ++i) {
            CHECK(lines[i].find("t = ") == t_at);
            CHECK(lines[i].find("golden ") == golden_at);
        }
        CHECK_THAT(describe(c), Contains("3/12 values differ  max abs 0.12 "));
    }
}

TEST_CASE("structural differences are listed and what is comparable is compared", "[compare]") {
    const Trajectory gold = sample();

    SECTION("different columns") {
        Trajectory value = gold;
        value.columns.back() = "box.spin";
        value.frames[3][1] = 0.75; // box.x still compared
        const Comparison c = compare(gold, value, std::nullopt);
        CHECK_FALSE(c.passed);
        CHECK_FALSE(c.identical);
        REQUIRE(c.structural.size() == 2);
        CHECK_THAT(c.structural[0], Contains("only in the golden: box.omega"));
        CHECK_THAT(c.structural[1], Contains("only in the new trajectory: box.spin"));
        REQUIRE(c.first_divergences.size() == 1);
        CHECK(c.first_divergences[0].column == "box.x");
        CHECK(summary(c, Channel::angular_velocity).compared == 0);
    }
    SECTION("the same columns in another order") {
        Trajectory value = gold;
        std::swap(value.columns[1], value.columns[2]);
        for (auto& frame : value.frames) {
            std::swap(frame[1], frame[2]);
        }
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK_THAT(c.structural[0], Contains("different order"));
        CHECK(c.first_divergences.empty()); // matched by name, every value equal
    }
    SECTION("fewer frames") {
        Trajectory value = gold;
        value.frames.pop_back();
        value.frames[1][2] = 2.5;
        const Comparison c = compare(gold, value, every_channel(tol(1, 0, 0)));
        CHECK_FALSE(c.passed); // within tolerance, but the shapes differ
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "frame counts differ: golden 4, new 3; the first 3 are compared");
        CHECK(summary(c, Channel::position).compared == 2 * 3 + 4);
    }
    SECTION("fewer events") {
        Trajectory value = gold;
        value.events.pop_back();
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "event counts differ: golden 2, new 1; the first 1 are compared");
        CHECK(summary(c, Channel::impulse).compared == 1);
        CHECK(c.first_divergences.empty());
        CHECK_THAT(describe(c), Contains("the trajectories differ in shape:\n  event counts"));
    }
    SECTION("an event between other bodies is not compared") {
        Trajectory value = gold;
        value.events[0].b = "wall";
        value.events[0].impulse = 9.0;
        value.events[1].a = "ball";
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "events[0] is between box and ground in the golden but between "
                                 "box and wall in the new trajectory, and 1 later event also "
                                 "pairs other bodies; events with other bodies are not compared");
        CHECK(summary(c, Channel::impulse).compared == 0);
    }
    SECTION("another scene") {
        Trajectory value = gold;
        value.scene = "spin";
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "the scene names differ: golden 'drop', new 'spin'");
        CHECK_FALSE(c.passed);
    }
}

TEST_CASE("a description of hundreds of divergent columns stays short", "[compare]") {
    Trajectory gold;
    gold.scene = "crowd";
    gold.columns = {"t"};
    gold.frames = {{0.0}, {0.5}};
    for (int body = 0; body < 100; ++body) {
        gold.columns.push_back("b" + std::to_string(body) + ".x");
        gold.frames[0].push_back(1.0);
        gold.frames[1].push_back(1.0);
    }
    Trajectory value = gold;
    for (std::size_t i = 1; i < value.columns.size(); ++i) {
        value.frames[1][i] = 2.0;
    }
    const Comparison c = compare(gold, value, std::nullopt);
    CHECK(c.first_divergences.size() == 100);
    const std::vector<std::string> lines = lines_of(describe(c));
    REQUIRE(lines.size() == 1 + 40 + 1 + 3);
    CHECK(lines[41] == "  ... and 60 more");
    CHECK(lines[42] == "per channel:");
    // 1 -> 2 is a difference of 1 at the spacing of doubles at 2, 2^-51.
    CHECK(lines[43] == "  position    100/200 values differ  max abs 1  max rel 1  max ulp " +
                           std::to_string(std::uint64_t{1} << 51));
    CHECK(lines[44] == "  event_time  0/2 values differ      max abs 0  max rel 0  max ulp 0");
}

TEST_CASE("impulse diff compares two trajectory files", "[compare]") {
    const Trajectory gold = sample();
    Trajectory moved = gold;
    moved.frames[2][2] = up(1.0);
    const TempFile a("a.json", write_trajectory(gold));
    const TempFile a_again("a-again.json", write_trajectory(gold));
    const TempFile b("b.json", write_trajectory(moved));

    SECTION("identical files: exit 0") {
        const Outcome o = diff({a.str(), a_again.str()});
        CHECK(o.exit_code == 0);
        CHECK(o.out == "identical\n");
    }
    SECTION("a 1-ULP change: exit 1 with the divergence") {
        const Outcome o = diff({a.str(), b.str()});
        CHECK(o.exit_code == 1);
        CHECK_THAT(o.out, Contains(b.str() + " differs from " + a.str() + ":\n"));
        CHECK_THAT(o.out, Contains("box.y  t = 0.5  golden 1  new 1.0000000000000002"));
        CHECK_THAT(o.out, Contains("ulp 1"));
    }
    SECTION("tolerance mode") {
        const Outcome pass = diff({a.str(), b.str(), "--tolerance", "--ulp", "1"});
        CHECK(pass.exit_code == 0);
        CHECK(pass.out.rfind("within tolerance\n", 0) == 0);
        CHECK_THAT(pass.out, Contains("0/12 values differ"));

        const Outcome fail =
            diff({a.str(), b.str(), "--tolerance", "--atol", "0", "--ulp=position=0"});
        CHECK(fail.exit_code == 1);
        CHECK_THAT(fail.out, Contains("box.y"));

        CHECK(diff({a.str(), b.str(), "--tolerance", "--atol",
                    "position=1e-15,angle=0,"
                    "velocity=0,angular_velocity=0,"
                    "impulse=0,event_time=0"})
                  .exit_code == 0);
    }
    SECTION("a different scene_sha256 is noted, not failed") {
        Trajectory other = gold;
        other.scene_sha256 = sha256_hex("edited drop scene");
        const TempFile c("c.json", write_trajectory(other));
        const Outcome o = diff({a.str(), c.str()});
        CHECK(o.exit_code == 0);
        CHECK_THAT(o.out, Contains("scene_sha256 differs"));
        CHECK_THAT(o.out, Contains("identical"));
    }
    SECTION("another scene is a difference") {
        Trajectory other = gold;
        other.scene = "spin";
        const TempFile c("c.json", write_trajectory(other));
        const Outcome o = diff({a.str(), c.str()});
        CHECK(o.exit_code == 1);
        CHECK_THAT(o.out, Contains("the scene names differ: golden 'drop', new 'spin'"));
    }
    SECTION("--help") {
        const Outcome o = diff({"--help"});
        CHECK(o.exit_code == 0);
        CHECK_THAT(o.out, Contains("usage: impulse diff A B"));
        CHECK_THAT(o.out, Contains("--tolerance"));
    }
    SECTION("bad input throws what main turns into exit 2") {
        using impulse::harness::cli::UsageError;
        const TempFile corrupt("corrupt.json", "{\"schema\": \"impulse/trajectory@1\",");
        CHECK_THROWS_WITH(diff({a.str(), corrupt.str()}), Contains(corrupt.str()));
        CHECK_THROWS_AS(diff({a.str(), corrupt.str()}), InputError);
        CHECK_THROWS_AS(diff({a.str(), "/nonexistent/impulse/b.json"}), InputError);
        CHECK_THROWS_AS(diff({a.str()}), UsageError);
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--ulp", "1"}), Contains("add --tolerance"));
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--tolerance", "--atol", "lots"}),
                          Contains("--atol") && Contains("'lots'"));
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--tolerance", "--atol", "position=1"}),
                          Contains("angle, velocity, angular_velocity, impulse, event_time") &&
                              Contains(a.str()));
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--tolerance"}), Contains("position"));
    }
    SECTION("through the tool's main: exit codes and one sentence") {
        const TempFile corrupt("corrupt.json", "<<<<<<< HEAD\n");
        const Outcome broken = impulse_main({"diff", a.str(), corrupt.str()});
        CHECK(broken.exit_code == 2);
        CHECK_THAT(broken.err, Contains(corrupt.str()));
        CHECK(impulse_main({"diff", a.str(), b.str(), "--tolerance"}).exit_code == 2);
        CHECK(impulse_main({"diff", a.str(), b.str(), "--tolerance", "--rtol", "x"}).exit_code ==
              2);
        CHECK(impulse_main({"diff", a.str(), b.str()}).exit_code == 1);
        CHECK(impulse_main({"diff", a.str(), a_again.str()}).exit_code == 0);
    }
}

TEST_CASE("a column that is no body channel is compared bit for bit, never by tolerance",
          "[compare]") {
    // Found by fuzz/fuzz_diff: such a column was always reported as a
    // difference, so a trajectory was not identical to itself.
    Trajectory gold = sample();
    gold.columns.push_back("box.spin_energy");
    for (std::size_t k = 0; k < gold.frames.size(); ++k) {
        gold.frames[k].push_back(0.5 * static_cast<double>(k));
    }
    const Comparison same = compare(gold, gold, std::nullopt);
    CHECK(same.identical);
    CHECK(same.structural.empty());

    Trajectory changed = gold;
    changed.frames[2].back() = 7.0;
    const Comparison differs = compare(gold, changed, std::nullopt);
    CHECK_FALSE(differs.identical);
    REQUIRE(differs.structural.size() == 1);
    CHECK(differs.structural[0].find("box.spin_energy") != std::string::npos);
}
