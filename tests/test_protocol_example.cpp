// docs/engine-protocol.md's smallest engine, taken from the page as printed
// and run through the real tool: the contract a reader follows must be one
// the harness accepts, and its numbers the motion the page says it computes.
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool_in_folder.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;
using namespace impulse::test;

TEST_CASE("the protocol page's smallest engine runs behind the gate as printed",
          "[engine-protocol]") {
    REQUIRE(fs::exists(IMPULSE_PYTHON3)); // scripts/setup installs python3
    const std::string page = slurp(fs::path(IMPULSE_SOURCE_DIR) / "docs" / "engine-protocol.md");
    const std::size_t begin = page.find("```python\n");
    REQUIRE(begin != std::string::npos);
    const std::size_t end = page.find("```", begin + 10);
    REQUIRE(end != std::string::npos);

    TempDir project;
    spit(project.dir / "engine.py", page.substr(begin + 10, end - begin - 10));
    const double dt = 0.01, g = 9.81, y0 = 10.0, vx = 1.5;
    spit(project.dir / "fall.json",
         R"({"schema": "impulse/scene@1", "name": "fall", "dt": 0.01, "duration": 0.5,
  "bodies": [{"name": "ball", "shape": {"circle": 0.5}, "position": [0, 10], "velocity": [1.5, 0]}]})");
    const Outcome ran = run_tool_in(project.dir, {"run", "fall.json", "--engine", "smallest",
                                                  "--engine-command", "python3 engine.py"});
    require_exit(ran, 0);

    // Symplectic Euler as the page writes it (velocity first, then position):
    // frame k holds y0 - g dt^2 (1 + ... + k) = y0 - g dt^2 k(k+1)/2
    // with vy = -g dt k and x = vx dt k.
    const nlohmann::json trajectory = nlohmann::json::parse(ran.out);
    CHECK(trajectory.at("engine") == "smallest");
    const auto& frames = trajectory.at("frames");
    REQUIRE(frames.size() == 51);
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const double kd = static_cast<double>(k);
        INFO("frame " << k);
        CHECK(frames[k][1].get<double>() == Approx(vx * dt * kd).margin(1e-12));
        CHECK(frames[k][2].get<double>() ==
              Approx(y0 - g * dt * dt * kd * (kd + 1.0) / 2.0).margin(1e-12));
        CHECK(frames[k][5].get<double>() == Approx(-g * dt * kd).margin(1e-12));
    }
}
