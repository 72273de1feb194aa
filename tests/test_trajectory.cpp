// The impulse/trajectory@1 reader and writer: doubles come back with the same
// bits, the layout is fixed, the digest is host-independent, and every broken
// file is an InputError naming the file and the JSON path.
#include "input_error.h"
#include "number_format.h"
#include "sha256.h"
#include "support/trajectories.h"
#include "trajectory.h"

#include <array>
#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace impulse::harness;
using impulse::test::make_event;

namespace {

const std::string golden_file = "goldens/drop-tilted.json";

// The solver line sample_trajectory() writes.
const std::string solver_line =
    "\"solver\": {\"integrator\": \"verlet\", \"toi\": \"bisection\", \"dt\": "
    "0.016666666666666666, \"toi_tolerance\": 1e-04, \"iterations\": 4, \"tolerances\": "
    "{\"toi\":1e-09,\"position\":0.0}},";

std::uint64_t bits_of(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

double from_bits(std::uint64_t bits) {
    double value = 0.0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

std::array<double, 8> event_numbers(const TrajectoryEvent& e) {
    return {e.t,         e.point[0], e.point[1],  e.normal[0],
            e.normal[1], e.impulse,  e.vn_before, e.vn_after};
}

// A box dropped on the ground, with a -0.0, a tiny and a denormal value among
// the frames. Solver numbers are written as the simulator writes them, with
// format_double ("1e-04", where nlohmann would write "0.0001"), nested values
// in nlohmann's compact form: the reader keeps both as they are, so a
// write-read-write cycle is byte-identical.
Trajectory sample_trajectory() {
    Trajectory trajectory;
    trajectory.scene = "drop-tilted";
    trajectory.scene_sha256 = sha256_hex("drop-tilted scene");
    trajectory.engine = "impulse 0.1.0";
    trajectory.solver = {{"integrator", "\"verlet\""},
                         {"toi", "\"bisection\""},
                         {"dt", format_double(1.0 / 60.0)},
                         {"toi_tolerance", format_double(1e-4)},
                         {"iterations", "4"},
                         {"tolerances", "{\"toi\":1e-09,\"position\":0.0}"}};
    trajectory.columns = {"t", "box.x", "box.y", "box.angle", "box.vx", "box.vy", "box.omega"};
    trajectory.frames = {
        {0.0, 0.0, 3.0, 0.5235987755982988, 0.0, 0.0, 0.0},
        {0.016666666666666666, 0.0, 2.9986375, 0.5235987755982988, 0.0, -0.1635, 0.0},
        {0.03333333333333333, -0.0, 2.99455, 0.5235987755982988, 1e-300, -0.327, 5e-324},
        {0.05, 0.125, 2.9877375, 0.52, -1.5, -0.4905, -2.5},
    };
    trajectory.events = {
        make_event(0.7601, "box", "ground", 0.616, 0.0, 0.0, 1.0, 3.21, -7.45, 5.96),
        make_event(1.5, "box", "wall", -0.0, 2.5, -1.0, 0.0, 0.001, -0.5, 0.25),
    };
    return trajectory;
}

// One column of values after "t", written and read back.
std::vector<double> round_trip_values(const std::vector<double>& values) {
    Trajectory trajectory;
    trajectory.scene = "numbers";
    trajectory.scene_sha256 = std::string(64, '0');
    trajectory.engine = "test";
    trajectory.columns = {"t", "value"};
    for (std::size_t i = 0; i < values.size(); ++i) {
        trajectory.frames.push_back({static_cast<double>(i), values[i]});
    }
    const Trajectory back = read_trajectory(write_trajectory(trajectory), "numbers.json");
    std::vector<double> out;
    for (const std::vector<double>& frame : back.frames) {
        out.push_back(frame.at(1));
    }
    return out;
}

void check_bits_survive(const std::vector<double>& values) {
    const std::vector<double> back = round_trip_values(values);
    REQUIRE(back.size() == values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        INFO("value " << format_double(values[i]) << " (bits " << std::hex << bits_of(values[i])
                      << ") came back as " << format_double(back[i]));
        CHECK(same_bits(back[i], values[i]));
    }
}

// Replaces the one occurrence of `from`; fails the test if it is not exactly
// one, so that a change to the writer cannot make a bad-input test vacuous.
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(text.find(from, at + 1) == std::string::npos);
    return text.replace(at, from.size(), to);
}

// The message of the InputError that reading `text` throws ("" if none).
std::string input_error_of(const std::string& text) {
    try {
        read_trajectory(text, golden_file);
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

// Reading fails with an InputError that names the file and the JSON path.
void check_rejected(const std::string& text, const std::string& path,
                    const std::string& words_in_message) {
    const std::string message = input_error_of(text);
    INFO("message: " << message);
    const std::string where = path.empty() ? golden_file + ": " : golden_file + ": " + path + ": ";
    CHECK(message.rfind(where, 0) == 0);
    CHECK(message.find(words_in_message) != std::string::npos);
}

} // namespace

TEST_CASE("format_double writes std::to_chars' shortest form and -0.0", "[trajectory]") {
    CHECK(format_double(0.0) == "0");
    CHECK(format_double(-0.0) == "-0.0");
    CHECK(format_double(3.0) == "3");
    CHECK(format_double(-42.0) == "-42");
    CHECK(format_double(0.1) == "0.1");
    CHECK(format_double(1e22) == "1e+22");
    CHECK(format_double(5e-324) == "5e-324");
    CHECK(format_double(0.016666666666666666) == "0.016666666666666666");
    // Above 2^53 to_chars writes every digit of the integer, which is exact.
    CHECK(format_double(std::ldexp(1.0, 60)) == "1152921504606846976");

    CHECK_THROWS_AS(format_double(std::numeric_limits<double>::quiet_NaN()), std::logic_error);
    CHECK_THROWS_AS(format_double(std::numeric_limits<double>::infinity()), std::logic_error);
    CHECK_THROWS_AS(format_double(-std::numeric_limits<double>::infinity()), std::logic_error);
}

TEST_CASE("parse_double reads JSON numbers back to the same bits", "[trajectory]") {
    for (const double value :
         {-0.0, 0.0, 0.1, 1.0 / 3.0, 5e-324, DBL_MIN, DBL_MAX, -DBL_MAX, 1e22, 3.0}) {
        double back = 1.0;
        REQUIRE(parse_double(format_double(value), back));
        CHECK(same_bits(back, value));
    }
    double untouched = 7.0;
    for (const char* bad : {"", "-", "1.", ".5", "+1", " 1", "1 ", "01", "1e", "0x10", "inf", "nan",
                            "1e999", "1e-400", "1,5"}) {
        INFO("text: '" << bad << "'");
        CHECK_FALSE(parse_double(bad, untouched));
    }
    CHECK(untouched == 7.0);
}

TEST_CASE("special doubles keep their bits through write and read", "[trajectory]") {
    const double largest_denormal = std::nextafter(DBL_MIN, 0.0);
    const std::vector<double> values = {
        -0.0, 0.0,
        5e-324, // the smallest denormal
        -5e-324, largest_denormal, DBL_MIN, DBL_MAX, -DBL_MAX, 0.1, 1.0 / 3.0, -2.0 / 3.0,
        0.016666666666666666, 1e22, 1e-7, 123456.789,
        // to_chars writes these with neither '.' nor 'e'; the reader gets them
        // as JSON integers and must turn them back into the same doubles.
        3.0, -42.0, 100.0,
        9007199254740992.0, // 2^53
        9007199254740994.0, // 2^53 + 2, the next double
        std::ldexp(1.0, 60),
        123456789012345664.0,     // 1.2345678901234566e17, 18 digits
        -123456789012345664.0,    // negative: read as int64
        18446744073709549568.0,   // the largest double below 2^64
        123456789012345683968.0}; // beyond uint64: nlohmann reads it as a float
    for (const double value :
         {3.0, -42.0, 100.0, 9007199254740994.0, std::ldexp(1.0, 60), 123456789012345683968.0}) {
        const std::string text = format_double(value);
        INFO(text);
        CHECK(text.find_first_of(".e") == std::string::npos);
    }
    check_bits_survive(values);
}

TEST_CASE("random bit patterns keep their bits through write and read", "[trajectory]") {
    std::mt19937_64 random(20240611); // fixed seed: the same patterns every run
    std::vector<double> values;
    while (values.size() < 20000) {
        const double value = from_bits(random());
        if (std::isfinite(value)) {
            values.push_back(value);
        }
    }
    check_bits_survive(values);
}

TEST_CASE("a trajectory written, read and written again is identical", "[trajectory]") {
    const Trajectory original = sample_trajectory();
    const std::string first = write_trajectory(original);
    const Trajectory back = read_trajectory(first, golden_file);
    const std::string second = write_trajectory(back);
    CHECK(second == first);

    CHECK(back.scene == original.scene);
    CHECK(back.scene_sha256 == original.scene_sha256);
    CHECK(back.engine == original.engine);
    CHECK(back.solver == original.solver);
    CHECK(back.columns == original.columns);
    REQUIRE(back.frames.size() == original.frames.size());
    for (std::size_t i = 0; i < original.frames.size(); ++i) {
        REQUIRE(back.frames[i].size() == original.frames[i].size());
        CHECK(std::memcmp(back.frames[i].data(), original.frames[i].data(),
                          original.frames[i].size() * sizeof(double)) == 0);
    }
    REQUIRE(back.events.size() == original.events.size());
    for (std::size_t i = 0; i < original.events.size(); ++i) {
        const TrajectoryEvent& a = back.events[i];
        const TrajectoryEvent& b = original.events[i];
        CHECK(a.a == b.a);
        CHECK(a.b == b.b);
        const std::array<double, 8> x = event_numbers(a);
        const std::array<double, 8> y = event_numbers(b);
        CHECK(std::memcmp(x.data(), y.data(), sizeof x) == 0);
    }
    CHECK(digest_of(back) == digest_of(original));
}

// Pins the layout and the digest. The digest 559de980c3836d2d was computed
// independently of this code, with Python:
//   h = 0xcbf29ce484222325
//   for v in [0, 1.5, 0.25, -0.0,  0.5, 1, 2, 0, 1, 3, -2, 1.5]:
//       for byte in struct.pack('<d', v): h = ((h ^ byte) * 0x100000001b3) % 2**64
// so it holds on any host, whatever its byte order.
TEST_CASE("the writer's layout and digest are fixed", "[trajectory]") {
    Trajectory trajectory;
    trajectory.scene = "tiny";
    trajectory.scene_sha256 = sha256_hex("");
    trajectory.engine = "impulse 0.1.0";
    trajectory.solver = {{"integrator", "\"verlet\""}, {"dt", "0.25"}};
    trajectory.columns = {"t", "box.x"};
    trajectory.frames = {{0.0, 1.5}, {0.25, -0.0}};
    trajectory.events = {make_event(0.5, "box", "ground", 1.0, 2.0, 0.0, 1.0, 3.0, -2.0, 1.5)};

    CHECK(digest_of(trajectory) == 0x559de980c3836d2dULL);
    CHECK(write_trajectory(trajectory) ==
          "{\n"
          "  \"schema\": \"impulse/trajectory@1\",\n"
          "  \"scene\": \"tiny\",\n"
          "  \"scene_sha256\": "
          "\"e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855\",\n"
          "  \"engine\": \"impulse 0.1.0\",\n"
          "  \"solver\": {\"integrator\": \"verlet\", \"dt\": 0.25},\n"
          "  \"digest\": \"559de980c3836d2d\",\n"
          "  \"columns\": [\"t\", \"box.x\"],\n"
          "  \"frames\": [\n"
          "    [0, 1.5],\n"
          "    [0.25, -0.0]\n"
          "  ],\n"
          "  \"events\": [\n"
          "    {\"t\": 0.5, \"a\": \"box\", \"b\": \"ground\", \"point\": [1, 2], \"normal\": [0, "
          "1], \"impulse\": 3, \"vn_before\": -2, \"vn_after\": 1.5}\n"
          "  ]\n"
          "}\n");
}

TEST_CASE("empty frames and events are written as []", "[trajectory]") {
    Trajectory trajectory;
    trajectory.scene = "still";
    trajectory.scene_sha256 = std::string(64, 'a');
    trajectory.engine = "impulse 0.1.0";
    trajectory.columns = {"t"};
    const std::string text = write_trajectory(trajectory);
    CHECK(text.find("  \"solver\": {},\n") != std::string::npos);
    CHECK(text.find("  \"frames\": [],\n  \"events\": []\n}\n") != std::string::npos);
    // No data: the digest is the FNV-1a offset basis.
    CHECK(text.find("\"digest\": \"cbf29ce484222325\"") != std::string::npos);
    CHECK(write_trajectory(read_trajectory(text, "still.json")) == text);
}

TEST_CASE("names are JSON-escaped", "[trajectory]") {
    Trajectory trajectory = sample_trajectory();
    trajectory.scene = "quote\" backslash\\ tab\t nul" + std::string(1, '\0') + " end";
    trajectory.events[0].a = "line\nbreak";
    const std::string text = write_trajectory(trajectory);
    CHECK(text.find("\"quote\\\" backslash\\\\ tab\\t nul\\u0000 end\"") != std::string::npos);
    // Read back, a control character is refused: names are printed, and a
    // newline or an escape in one would forge lines on the terminal.
    CHECK_THROWS_WITH(read_trajectory(text, golden_file),
                      Catch::Contains("scene: holds the control character 0x09 at byte 21"));
    trajectory.scene = "quote\" backslash\\ end";
    CHECK_THROWS_WITH(read_trajectory(write_trajectory(trajectory), golden_file),
                      Catch::Contains("events[0].a: holds the control character 0x0A at byte 4"));
    trajectory.events[0].a = "box";
    const Trajectory back = read_trajectory(write_trajectory(trajectory), golden_file);
    CHECK(back.scene == trajectory.scene);
}

TEST_CASE("a stopped run's partial.t is its last frame's time", "[trajectory]") {
    Trajectory trajectory = sample_trajectory();
    trajectory.partial = TrajectoryPartial{"a Zeno cascade", trajectory.frames.back().front()};
    CHECK(read_trajectory(write_trajectory(trajectory), golden_file).partial);
    trajectory.partial->t = -1.0;
    CHECK_THROWS_WITH(read_trajectory(write_trajectory(trajectory), golden_file),
                      Catch::Contains("partial.t: is -1, but the last frame is at t = "));
}

TEST_CASE("digest_hex is 16 zero-padded lowercase digits", "[trajectory]") {
    CHECK(digest_hex(0) == "0000000000000000");
    CHECK(digest_hex(1) == "0000000000000001");
    CHECK(digest_hex(0xcbf29ce484222325ULL) == "cbf29ce484222325");
    CHECK(digest_hex(0xFFFFFFFFFFFFFFFFULL) == "ffffffffffffffff");
}

TEST_CASE("the solver block keeps document order; numbers as format_double writes them",
          "[trajectory]") {
    std::string text = write_trajectory(sample_trajectory());
    text = replace_once(text, solver_line,
                        "\"solver\": { \"zeta\" : 1.50, \"alpha\": [ true, null ],\n"
                        "    \"dt\": 1e-3, \"tolerance\": 0.0001, \"zero\": -0.0, \"n\": 2.0,\n"
                        "    \"seed\": 12345678901234567890 },");
    const Trajectory back = read_trajectory(text, golden_file);
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"zeta", "1.5"},
        {"alpha", "[true,null]"},
        {"dt", "0.001"},
        {"tolerance", "1e-04"},
        {"zero", "-0.0"},
        {"n", "2"},
        {"seed", "12345678901234567890"}};
    CHECK(back.solver == expected);
}

TEST_CASE("broken trajectory files are InputErrors naming file and path", "[trajectory]") {
    const std::string good = write_trajectory(sample_trajectory());
    REQUIRE(input_error_of(good).empty());
    const std::string frame_1 =
        "[0.016666666666666666, 0, 2.9986375, 0.5235987755982988, 0, -0.1635, 0]";
    const std::string digest_line =
        "\"digest\": \"" + digest_hex(digest_of(sample_trajectory())) + "\"";

    SECTION("not JSON") {
        check_rejected("this is not a trajectory", "", "not valid JSON: line 1");
    }
    SECTION("empty file") {
        check_rejected("", "", "not valid JSON");
    }
    SECTION("truncated file") {
        check_rejected(good.substr(0, good.size() / 2), "", "not valid JSON");
    }
    SECTION("merge-conflict marker") {
        const std::string conflicted = replace_once(
            good, "  " + digest_line + ",\n",
            "<<<<<<< HEAD\n  " + digest_line + ",\n=======\n  \"digest\": \"0123456789abcdef\",\n" +
                ">>>>>>> other\n");
        check_rejected(conflicted, "", "merge-conflict marker at line 7");
    }
    SECTION("a number too large for a double") {
        check_rejected(replace_once(good, frame_1, "[1e999, 0, 0, 0, 0, 0, 0]"), "",
                       "not valid JSON: number overflow");
    }
    SECTION("top level not an object") {
        check_rejected("[1, 2]", "", "must be a JSON object");
    }
    SECTION("nesting deep enough to exhaust a recursive parser") {
        check_rejected(std::string(100000, '[') + std::string(100000, ']'), "",
                       "nested too deeply");
    }
    SECTION("wrong schema") {
        check_rejected(replace_once(good, "\"impulse/trajectory@1\"", "\"impulse/scene@1\""),
                       "schema", "must be \"impulse/trajectory@1\"");
    }
    SECTION("unsupported version") {
        check_rejected(replace_once(good, "\"impulse/trajectory@1\"", "\"impulse/trajectory@2\""),
                       "schema", "version 2 of the trajectory format is not supported");
    }
    SECTION("missing key") {
        check_rejected(replace_once(good, "  \"engine\": \"impulse 0.1.0\",\n", ""), "engine",
                       "is required but missing");
    }
    SECTION("missing key in an event") {
        check_rejected(replace_once(good, "\"impulse\": 3.21, ", ""), "events[0].impulse",
                       "is required but missing");
    }
    SECTION("unknown key at the top level") {
        check_rejected(replace_once(good, "  \"engine\"", "  \"comment\": \"hi\",\n  \"engine\""),
                       "comment", "unknown key");
    }
    SECTION("unknown key in an event") {
        check_rejected(replace_once(good, "\"vn_after\": 5.96", "\"vn_after\": 5.96, \"color\": 1"),
                       "events[0].color", "unknown key");
    }
    SECTION("duplicate key") {
        check_rejected(replace_once(good, "\"dt\": 0.016666666666666666",
                                    "\"dt\": 0.016666666666666666, \"dt\": 0.01"),
                       "solver.dt", "appears more than once");
    }
    SECTION("string where a number belongs") {
        check_rejected(replace_once(good, frame_1,
                                    "[0.016666666666666666, 0, \"2.9986375\", 0.5235987755982988, "
                                    "0, -0.1635, 0]"),
                       "frames[1][2]", "must be a number, got \"2.9986375\"");
    }
    SECTION("boolean where a number belongs") {
        check_rejected(replace_once(good, "\"impulse\": 3.21", "\"impulse\": true"),
                       "events[0].impulse", "must be a number, got true");
    }
    SECTION("integer a double cannot hold exactly") {
        check_rejected(replace_once(good, frame_1,
                                    "[0.016666666666666666, 0, 9007199254740993, "
                                    "0.5235987755982988, 0, -0.1635, 0]"),
                       "frames[1][2]", "cannot be held exactly by a double");
    }
    SECTION("frame of the wrong length") {
        check_rejected(
            replace_once(good, frame_1,
                         "[0.016666666666666666, 0, 2.9986375, 0.5235987755982988, 0, -0.1635]"),
            "frames[1]", "has 6 values but there are 7 columns");
    }
    SECTION("contact point of the wrong length") {
        check_rejected(replace_once(good, "\"point\": [0.616, 0]", "\"point\": [0.616]"),
                       "events[0].point", "exactly 2 numbers");
    }
    SECTION("solver not an object") {
        check_rejected(replace_once(good, solver_line, "\"solver\": \"verlet\","), "solver",
                       "must be an object, got \"verlet\"");
    }
    SECTION("first column not t") {
        check_rejected(replace_once(good, "[\"t\", \"box.x\"", "[\"time\", \"box.x\""), "columns",
                       "first column must be \"t\"");
    }
    SECTION("repeated column") {
        check_rejected(replace_once(good, "\"box.y\", \"box.angle\"", "\"box.x\", \"box.angle\""),
                       "columns[2]", "repeats columns[1]");
    }
    SECTION("scene_sha256 not hex") {
        check_rejected(replace_once(good, sample_trajectory().scene_sha256, "abc"), "scene_sha256",
                       "64 lowercase hex digits");
    }
    SECTION("digest not hex") {
        check_rejected(replace_once(good, digest_line, "\"digest\": \"0123456789ABCDEF\""),
                       "digest", "16 lowercase hex digits");
    }
    SECTION("one number edited by hand") {
        const std::string edited =
            replace_once(good, frame_1,
                         "[0.016666666666666666, 0, 2.9986376, 0.5235987755982988, 0, -0.1635, 0]");
        Trajectory changed = sample_trajectory();
        changed.frames[1][2] = 2.9986376;
        check_rejected(edited, "digest",
                       "stored digest " + digest_hex(digest_of(sample_trajectory())) +
                           " does not match the data (" + digest_hex(digest_of(changed)) +
                           "): the file was edited by hand or is corrupt");
    }
}

// Whatever is cut off or garbled, the reader answers with an InputError (or
// the data, when the damage is harmless): never a crash or another exception.
TEST_CASE("damaged files never escape as anything but InputError", "[trajectory]") {
    const std::string good = write_trajectory(sample_trajectory());
    std::size_t accepted = 0;
    for (std::size_t length = 0; length <= good.size(); ++length) {
        try {
            read_trajectory(good.substr(0, length), golden_file);
            ++accepted;
        } catch (const InputError&) {
        }
    }
    CHECK(accepted == 2); // the whole file, and the file without its final newline
    for (std::size_t at = 0; at < good.size(); ++at) {
        for (const char replacement : {'0', '"', ']', 'x', '-', '\xff'}) {
            std::string damaged = good;
            damaged[at] = replacement;
            try {
                read_trajectory(damaged, golden_file);
            } catch (const InputError&) {
            }
        }
    }
}
