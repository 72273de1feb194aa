// Trajectories, tolerances and tool calls the comparison tests share
// (test_compare.cpp, test_compare_reports.cpp, test_first_divergence.cpp,
// test_ulp_scale.cpp): a hand-made sample whose
// differences can be worked out by hand, ULP steps, and the diff verb and the
// whole tool run in-process.
#pragma once

#include "cli.h"
#include "compare.h"
#include "input_error.h"
#include "sha256.h"
#include "tolerance.h"
#include "tool.h"
#include "trajectories.h"
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

namespace impulse::test::comparing {

namespace fs = std::filesystem;
using namespace impulse::harness;
using impulse::test::Outcome;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double quiet_nan = std::numeric_limits<double>::quiet_NaN();
constexpr double tiny = std::numeric_limits<double>::denorm_min();

inline double up(double value, int ulps = 1) {
    for (int i = 0; i < ulps; ++i) {
        value = std::nextafter(value, inf);
    }
    return value;
}

inline std::uint64_t bits_of(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// An event of the sample's bounce (the point, the normal and the normal
// velocities fixed) between `a` and `b` at `t`.
inline TrajectoryEvent event(double t, const std::string& a, const std::string& b, double impulse) {
    return make_event(t, a, b, 0.25, 0.0, 0.0, 1.0, impulse, -2.0, 1.5);
}

// One body, four frames a quarter second apart, two events. Values are chosen
// so that differences can be worked out by hand.
inline Trajectory sample() {
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

inline ChannelTolerance tol(double atol, double rtol, std::uint64_t ulp) {
    ChannelTolerance t;
    t.atol = atol;
    t.rtol = rtol;
    t.ulp = ulp;
    return t;
}

inline Tolerances every_channel(ChannelTolerance t) {
    Tolerances tolerances;
    for (auto& slot : tolerances.channels) {
        slot = t;
    }
    return tolerances;
}

inline const ChannelSummary& summary(const Comparison& c, Channel channel) {
    return c.channels[static_cast<std::size_t>(channel)];
}

inline std::vector<std::string> lines_of(const std::string& text) {
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

inline Outcome diff(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    Outcome o;
    o.exited = true;
    o.exit_code = impulse::harness::cli::diff_verb(args, out, err);
    o.out = out.str();
    o.err = err.str();
    return o;
}

// The whole tool's entry point, for the exit code main() makes of exceptions.
inline Outcome impulse_main(std::vector<std::string> args) {
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

} // namespace impulse::test::comparing
