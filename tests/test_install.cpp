// cmake --install and the CMake package, as a user meets them (label
// `install`, CTest install.package; hidden from the unit run because it
// installs the build and builds a program): the layout of the prefix, the
// installed tool gating the installed scenes, and examples/engines/cpp-minimal
// built against the installed package with find_package(impulse) and run on
// canonical scenes.
#include "scene.h"
#include "support/program.h"
#include "support/tool.h"
#include "trajectory.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using impulse::test::Outcome;
using impulse::test::run_program;
using impulse::test::slurp;
using impulse::test::TempDir;

namespace {

// The build tree the test was built in: IMPULSE_BUILD_DIR (CTest sets it),
// else the tool's folder's parent (the build writes the tool to BUILD/bin).
fs::path build_dir() {
    const char* dir = std::getenv("IMPULSE_BUILD_DIR");
    return dir != nullptr && *dir != '\0' ? fs::path(dir)
                                          : fs::path(IMPULSE_BINARY).parent_path().parent_path();
}

// Every file under `from` (relative paths) with a byte-identical copy under `to`.
void require_copies(const fs::path& from, const fs::path& to, const std::string& pattern = "") {
    int compared = 0;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(from)) {
        const std::string name = e.path().filename().string();
        if (!e.is_regular_file() || (!pattern.empty() && name.find(pattern) == std::string::npos) ||
            e.path().string().find("__pycache__") != std::string::npos) {
            continue;
        }
        const fs::path copy = to / fs::relative(e.path(), from);
        INFO(copy);
        REQUIRE(fs::is_regular_file(copy));
        CHECK(slurp(copy) == slurp(e.path()));
        ++compared;
    }
    CHECK(compared > 0);
}

// Height of the ball's lowest point above the ground's top in drop-circle:
// from the scene's own bodies, so the exact answer follows the scene.
double drop_height(const impulse::harness::Scene& scene) {
    double ball_bottom = 0.0, ground_top = 0.0;
    for (const impulse::harness::SceneBody& b : scene.bodies) {
        if (b.is_static) {
            double top = -INFINITY;
            for (int i = 0; i < b.shape.polygon.count; ++i) {
                top = std::max(top, b.shape.polygon.vertices[static_cast<std::size_t>(i)].y);
            }
            ground_top = b.position.y + top;
        } else {
            ball_bottom = b.position.y - b.shape.radius;
        }
    }
    return ball_bottom - ground_top;
}

// The build installed once per test run into a prefix that lives as long as
// the process, for every test here.
const fs::path& installed_prefix() {
    static const TempDir dir;
    static const fs::path prefix = [] {
        const fs::path p = dir.dir / "prefix";
        const Outcome install =
            run_program({"cmake", "--install", build_dir().string(), "--prefix", p.string()});
        INFO(install.out << install.err);
        REQUIRE(install.exit_code == 0);
        return p;
    }();
    return prefix;
}

// The compiler and flags the installed libraries were built with (CTest
// passes them), for the example's configure: a sanitizer build's libraries
// need the sanitizer's runtime in the engine's link too.
void append_build_settings(std::vector<std::string>& args) {
    for (const char* setting :
         {"CMAKE_CXX_COMPILER", "CMAKE_CXX_FLAGS", "CMAKE_EXE_LINKER_FLAGS"}) {
        const char* value = std::getenv((std::string("IMPULSE_BUILD_") + setting).c_str());
        if (value != nullptr && *value != '\0') {
            args.push_back(std::string("-D") + setting + "=" + value);
        }
    }
}

// The installed copy of examples/engines/cpp-minimal, configured with
// CMAKE_PREFIX_PATH the prefix and built: the path of the engine.
const std::string& cpp_minimal() {
    static const TempDir dir;
    static const std::string engine = [] {
        const fs::path example =
            installed_prefix() / "share" / "impulse" / "examples" / "engines" / "cpp-minimal";
        const fs::path build = dir.dir / "build";
        std::vector<std::string> args = {"cmake",
                                         "-S",
                                         example.string(),
                                         "-B",
                                         build.string(),
                                         "-DCMAKE_PREFIX_PATH=" + installed_prefix().string(),
                                         "-DCMAKE_BUILD_TYPE=Release"};
        append_build_settings(args);
        const Outcome configure = run_program(args);
        {
            INFO(configure.out << configure.err);
            REQUIRE(configure.exit_code == 0);
        }
        const Outcome built = run_program({"cmake", "--build", build.string()});
        INFO(built.out << built.err);
        REQUIRE(built.exit_code == 0);
        return (build / "cpp-minimal").string();
    }();
    return engine;
}

fs::path installed_scene(const std::string& name) {
    return installed_prefix() / "share" / "impulse" / "scenes" / (name + ".json");
}

} // namespace

namespace {

// The targets of a Markdown page's relative links, "](target)" without an
// "#anchor", leaving out web addresses and links within the page.
std::vector<std::string> relative_links(const std::string& page) {
    std::vector<std::string> targets;
    for (std::size_t at = page.find("]("); at != std::string::npos; at = page.find("](", at + 2)) {
        const std::size_t end = page.find_first_of(")# \n", at + 2);
        if (end == std::string::npos) {
            break;
        }
        const std::string target = page.substr(at + 2, end - at - 2);
        if (!target.empty() && target.find("://") == std::string::npos &&
            (target.size() > 3 && (target.compare(target.size() - 3, 3, ".md") == 0 ||
                                   target.compare(target.size() - 4, 4, ".png") == 0 ||
                                   target.compare(target.size() - 4, 4, ".svg") == 0))) {
            targets.push_back(target);
        }
    }
    return targets;
}

} // namespace

TEST_CASE("cmake --install puts the tool, the scenes, the documents, the examples and the CMake "
          "package under the prefix",
          "[.][install]") {
    const fs::path source = IMPULSE_SOURCE_DIR;
    const fs::path& prefix = installed_prefix();
    // The tool alone in bin/: no tests, benchmarks or fuzzers.
    std::vector<std::string> programs;
    for (const fs::directory_entry& e : fs::directory_iterator(prefix / "bin")) {
        programs.push_back(e.path().filename().string());
    }
    CHECK(programs == std::vector<std::string>{"impulse"});
    require_copies(source / "harness" / "scenes", prefix / "share" / "impulse" / "scenes");
    CHECK(fs::is_regular_file(prefix / "share" / "impulse" / "scenes" / "scale" /
                              "gas-circles-10.json"));
    require_copies(source / "docs", prefix / "share" / "doc" / "impulse" / "docs");
    CHECK(slurp(prefix / "share" / "doc" / "impulse" / "README.md") == slurp(source / "README.md"));
    require_copies(source / "examples", prefix / "share" / "impulse" / "examples");
    // Every relative link of an installed page leads to an installed file.
    int links = 0;
    for (const fs::path& folder :
         {prefix / "share" / "doc" / "impulse", prefix / "share" / "impulse" / "examples"}) {
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
            if (e.path().extension() != ".md") {
                continue;
            }
            for (const std::string& target : relative_links(slurp(e.path()))) {
                INFO(e.path().string() << " links " << target);
                CHECK(fs::exists(e.path().parent_path() / target));
                ++links;
            }
        }
    }
    CHECK(links > 50);
    for (const char* file :
         {"impulseConfig.cmake", "impulseConfigVersion.cmake", "impulseTargets.cmake"}) {
        CHECK(fs::is_regular_file(prefix / "lib" / "cmake" / "impulse" / file));
    }
    CHECK(fs::is_regular_file(prefix / "include" / "impulse" / "protocol.h"));
}

TEST_CASE("The installed tool runs from the prefix and gates the installed scenes",
          "[.][install]") {
    const fs::path tool = installed_prefix() / "bin" / "impulse";
    const Outcome version = run_program({tool.string(), "--version"});
    CHECK(version.exit_code == 0);
    CHECK(version.out == std::string("impulse ") + IMPULSE_VERSION + "\n");

    // A root of the installed scenes and the repository's goldens.
    const TempDir dir;
    const fs::path root = dir.dir / "root";
    fs::create_directories(root / "harness");
    fs::copy(installed_prefix() / "share" / "impulse" / "scenes", root / "harness" / "scenes",
             fs::copy_options::recursive);
    fs::copy(fs::path(IMPULSE_SOURCE_DIR) / "goldens", root / "goldens");
    const Outcome check = run_program({tool.string(), "check", "--root", root.string()});
    INFO(check.out << check.err);
    CHECK(check.exit_code == 0);
    CHECK_THAT(check.out, Catch::Contains(" passed, 0 failed, 0 errors"));
}

TEST_CASE("cpp-minimal, built with find_package(impulse), drops a disc onto the exact answer",
          "[.][install]") {
    // First impact at sqrt(2h/g), rebound -e times the approach. Bisection
    // stops within the scene's toi_tolerance (1e-12 s) and rk4 is exact for a
    // constant force, so 1e-9 s leaves room for rounding and the 1e-9 m
    // contact band (1.6e-10 s at 6.3 m/s).
    const impulse::harness::Scene scene =
        impulse::harness::load_scene(installed_scene("drop-circle").string());
    const double g = -scene.gravity.y;
    const double h = drop_height(scene);
    const Outcome run = run_program({cpp_minimal(), installed_scene("drop-circle").string()});
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.empty());
    nlohmann::json output = nlohmann::json::parse(run.out);
    CHECK(output["cost"]["seconds"].get<double>() >= 0.0);
    CHECK(output["cost"]["steps"] == impulse::harness::step_count(scene));
    // The rest is a trajectory the strict golden reader takes (it knows no
    // cost: a golden never holds one), digest included.
    output.erase("cost");
    const impulse::harness::Trajectory trajectory =
        impulse::harness::read_trajectory(output.dump(), "cpp-minimal's output");
    CHECK(trajectory.frames.size() ==
          static_cast<std::size_t>(impulse::harness::step_count(scene)) + 1);
    REQUIRE(!trajectory.events.empty());
    const impulse::harness::TrajectoryEvent& first = trajectory.events.front();
    CHECK(std::abs(first.t - std::sqrt(2.0 * h / g)) < 1e-9);
    CHECK(first.vn_before == Approx(-std::sqrt(2.0 * g * h)).epsilon(1e-9));
    CHECK(first.vn_after == Approx(-scene.restitution * first.vn_before).epsilon(1e-12));

    // The installed tool reads it too: `impulse diff` against the golden
    // compares (0 or 1); it does not refuse the file (2).
    const TempDir dir;
    impulse::test::spit(dir.dir / "drop-circle.json", output.dump());
    const Outcome diff =
        run_program({(installed_prefix() / "bin" / "impulse").string(), "diff",
                     (fs::path(IMPULSE_SOURCE_DIR) / "goldens" / "drop-circle.json").string(),
                     (dir.dir / "drop-circle.json").string()});
    INFO(diff.out << diff.err);
    CHECK((diff.exit_code == 0 || diff.exit_code == 1));
}

TEST_CASE("cpp-minimal refuses a dynamic polygon with exit 3 and one sentence", "[.][install]") {
    const Outcome refused = run_program({cpp_minimal(), installed_scene("drop-box").string()});
    CHECK(refused.exit_code == 3);
    CHECK(refused.out.empty());
    CHECK(std::count(refused.err.begin(), refused.err.end(), '\n') == 1);
    CHECK_THAT(refused.err, Catch::Contains("'box' is a polygon"));
}

TEST_CASE("cpp-minimal gated by the installed impulse: bless, check and conform on the installed "
          "scenes",
          "[.][install]") {
    // A user's repository: the engine built against the package, copied to
    // bin/ and named in impulse.json by a path relative to the project (it
    // runs in the project's folder), and copies of two installed scenes.
    const fs::path share = installed_prefix() / "share" / "impulse" / "scenes";
    const std::string tool = (installed_prefix() / "bin" / "impulse").string();
    const TempDir dir;
    const fs::path project = dir.dir / "project";
    fs::create_directories(project / "bin");
    fs::copy_file(cpp_minimal(), project / "bin" / "cpp-minimal");
    impulse::test::spit(project / "impulse.json",
                        R"({"schema": "impulse/project@1", "scenes": ["scenes"],
                            "engines": [{"name": "cpp-minimal", "command": ["bin/cpp-minimal"]}]})");
    for (const char* name : {"drop-circle", "head-on"}) {
        impulse::test::spit(project / "scenes" / (std::string(name) + ".json"),
                            slurp(share / (std::string(name) + ".json")));
    }

    // Blessing happens on the engine author's machine, never in CI mode (bless
    // refuses under CI=true, which CI sets for this very test).
    const Outcome blessed =
        run_program({"env", "-u", "CI", tool, "bless", "--root", project.string()});
    {
        INFO(blessed.out << blessed.err);
        REQUIRE(blessed.exit_code == 0);
    }
    for (const char* name : {"drop-circle", "head-on"}) {
        INFO(name);
        const std::string golden = slurp(project / "goldens" / (std::string(name) + ".json"));
        CHECK(golden.find("\"engine\": \"cpp-minimal") != std::string::npos);
    }
    const Outcome checked = run_program({tool, "check", "--root", project.string()});
    INFO(checked.out << checked.err);
    CHECK(checked.exit_code == 0);
    CHECK_THAT(checked.out, Catch::Contains("2 scenes: 2 passed, 0 failed, 0 errors"));

    // conform finds the shipped scenes beside the installed tool.
    const Outcome conformed =
        run_program({tool, "conform", "--engine", "cpp-minimal", "drop-circle", "head-on", "--root",
                     project.string(), "--json", (dir.dir / "card.json").string()});
    INFO(conformed.out << conformed.err);
    CHECK(conformed.exit_code == 0);
    CHECK_THAT(conformed.out, Catch::Contains("2 scenes: 2 passed, 0 failed, 0 unsupported"));
    const nlohmann::json card = nlohmann::json::parse(slurp(dir.dir / "card.json"));
    CHECK(card["engine"] == "cpp-minimal");
    CHECK(fs::equivalent(card["scenes_dir"].get<std::string>(), share));
    CHECK(card["passed"] == true);
}
