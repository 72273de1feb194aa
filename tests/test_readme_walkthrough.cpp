// The README's "Gate your own engine" page, run as written: every command of
// the block between <!-- walkthrough:begin --> and <!-- walkthrough:end -->,
// in one shell, from the clone, with a fresh HOME (so ~/.local and
// ~/my-engine are the test's own). A command's expected exit is its
// "# exit N" comment, 0 without one. Hidden from the unit run (it builds,
// installs and runs the Python engine): CTest's walkthrough.readme.
#include "support/files.h"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using impulse::test::slurp;
using impulse::test::spit;
using impulse::test::TempDir;

namespace {

struct Command {
    std::string text;
    int expected_exit = 0;
};

// The shell commands of the README's walkthrough block, in order.
std::vector<Command> walkthrough_commands(const std::string& readme) {
    const std::size_t begin = readme.find("<!-- walkthrough:begin -->");
    const std::size_t end = readme.find("<!-- walkthrough:end -->");
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    std::istringstream block(readme.substr(begin, end - begin));
    const std::regex exit_comment(R"(\s+#\s*exit\s+(\d+)\s*$)");
    std::vector<Command> commands;
    bool in_code = false;
    for (std::string line; std::getline(block, line);) {
        if (line.rfind("```", 0) == 0) {
            in_code = !in_code;
            continue;
        }
        if (!in_code || line.empty() || line[0] == '#') {
            continue;
        }
        Command c;
        c.text = line;
        std::smatch m;
        if (std::regex_search(line, m, exit_comment)) {
            c.expected_exit = std::stoi(m[1].str());
            c.text = line.substr(0, static_cast<std::size_t>(m.position(0)));
        }
        commands.push_back(c);
    }
    return commands;
}

} // namespace

TEST_CASE("the README's walkthrough runs as written on this machine", "[.][walkthrough]") {
    const fs::path source = IMPULSE_SOURCE_DIR;
    const std::vector<Command> commands = walkthrough_commands(slurp(source / "README.md"));
    REQUIRE(commands.size() >= 10);

    TempDir home;
    // One shell, so cd and export carry from line to line as for a reader;
    // after each command a marker line with its exit status. CI mode is the
    // CI machine's, not the reader's: bless and regen refuse under it.
    std::string script =
        "unset CI\nexport HOME='" + home.dir.string() + "'\ncd '" + source.string() + "'\n";
    for (std::size_t i = 0; i < commands.size(); ++i) {
        script += "echo '@@begin " + std::to_string(i) + "'\n" + commands[i].text +
                  "\necho \"@@end " + std::to_string(i) + " $?\"\n";
    }
    spit(home.dir / "walkthrough.sh", script);
    const fs::path log = home.dir / "walkthrough.log";
    const std::string shell = "bash '" + (home.dir / "walkthrough.sh").string() + "' > '" +
                              log.string() + "' 2>&1 < /dev/null";
    REQUIRE(std::system(shell.c_str()) == 0);

    // Each command's output and exit, from the markers.
    const std::string output = slurp(log);
    std::map<std::size_t, std::pair<int, std::string>> ran;
    std::istringstream lines(output);
    std::string current;
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("@@begin ", 0) == 0) {
            current.clear();
        } else if (line.rfind("@@end ", 0) == 0) {
            std::istringstream fields(line.substr(6));
            std::size_t index = 0;
            int status = 0;
            fields >> index >> status;
            ran[index] = {status, current};
        } else {
            current += line + "\n";
        }
    }
    for (std::size_t i = 0; i < commands.size(); ++i) {
        INFO("command " << i << ": " << commands[i].text);
        REQUIRE(ran.count(i) == 1);
        INFO("its output:\n" << ran[i].second);
        CHECK(ran[i].first == commands[i].expected_exit);
    }

    // The failing check names the scene, a body's channel, the time and the size.
    for (std::size_t i = 0; i < commands.size(); ++i) {
        if (commands[i].expected_exit == 1) {
            const std::string& said = ran[i].second;
            INFO(said);
            CHECK(said.find("FAILED drop") != std::string::npos);
            CHECK(std::regex_search(said, std::regex(R"(first divergence: ball\.\w+ at t = )")));
            CHECK(said.find("golden ") != std::string::npos);
            CHECK(std::regex_search(said, std::regex(R"(abs [0-9.e+-]+ +rel )")));
        }
    }
    // The reader's project holds what the page says it does.
    const fs::path project = home.dir / "my-engine";
    CHECK(fs::is_regular_file(project / "impulse.json"));
    CHECK(fs::is_regular_file(project / "goldens" / "drop.json"));
    CHECK(fs::is_regular_file(home.dir / ".local" / "bin" / "impulse"));
}
