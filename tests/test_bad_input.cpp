// Bad input through the real tool (issue 7, "Bad input"; DESIGN.md, "The
// command-line tool"): every way a scene, a trajectory or a golden can be
// wrong ends in exit code 2 and one line on stderr that names the file and the
// JSON path. Never a crash or a stack trace, never a partial output file,
// never a golden touched, never a file written outside goldens/.
//
// test_scene_validation.cpp and test_trajectory.cpp check the readers'
// messages one by one; these run the built `impulse` as a user does and check
// the contract around them: exit code, one sentence, nothing written.
#include "tool_process.h"
#include "utf8.h"

#include <catch2/catch.hpp>
#include <cerrno>
#include <cstdint>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using impulse::test::start_tool;
using impulse::test::valid_utf8;
using impulse::test::wait_for;

namespace {

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void spit(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// A fresh directory, removed with all it holds when the scope ends.
struct TempDir {
    fs::path dir;
    TempDir() {
        static int counter = 0;
        dir = fs::temp_directory_path() /
              ("impulse-bad-input-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(dir, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

struct Outcome {
    bool exited = false; // false: ended by a signal, i.e. it crashed
    int exit_code = -1;
    std::string out;
    std::string err;
};

// Runs the built tool with these arguments, without a shell, so names with
// spaces, quotes and backslashes arrive as written. The environment is the
// test's without CI (so bless writes and check is not in CI mode), plus
// `extra_env` ("CI=true").
Outcome impulse_tool(const std::vector<std::string>& args,
                     const std::vector<std::string>& extra_env = {}) {
    const TempDir capture;
    const std::string out_file = (capture.dir / "stdout").string();
    const std::string err_file = (capture.dir / "stderr").string();

    const int status = wait_for(start_tool(args, extra_env, out_file, err_file));
    Outcome o;
    o.exited = WIFEXITED(status);
    o.exit_code = o.exited ? WEXITSTATUS(status) : -1;
    o.out = slurp(out_file);
    o.err = slurp(err_file);
    return o;
}

// 64-bit FNV-1a of a file's bytes.
std::uint64_t file_hash(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::uint64_t h = 0xcbf29ce484222325ULL;
    std::vector<char> block(1 << 20);
    while (in) {
        in.read(block.data(), static_cast<std::streamsize>(block.size()));
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            h = (h ^ static_cast<unsigned char>(block[static_cast<std::size_t>(i)])) *
                0x100000001b3ULL;
        }
    }
    return h;
}

// Every entry under `dir` (relative path -> kind, size and content hash): two
// equal snapshots mean nothing was created, removed or changed.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> entries;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
        const std::string name = fs::relative(e.path(), dir).string();
        if (e.is_directory()) {
            entries[name] = "directory";
        } else if (e.file_size() > 16u * 1024 * 1024) {
            // The huge sparse files: hashing them would dominate the test.
            // Their size and modification time show any write.
            entries[name] = "file " + std::to_string(e.file_size()) + " modified " +
                            std::to_string(e.last_write_time().time_since_epoch().count());
        } else {
            entries[name] =
                "file " + std::to_string(e.file_size()) + " " + std::to_string(file_hash(e.path()));
        }
    }
    return entries;
}

std::size_t count_of(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
        ++n;
    }
    return n;
}

// What a crash, an escaped exception or a sanitizer report prints.
const char* const crash_signs[] = {"terminate called", "what():",          "internal error",
                                   "Aborted",          "Segmentation",     "core dumped",
                                   "[json.exception",  "AddressSanitizer", "runtime error:"};

// One sentence: "FILE: PATH: ..." (or "FILE: ..." when `path` is "", any path
// when it is nullopt: where a parser stopped) holding `words`; readable text.
void check_sentence(const std::string& sentence, const std::string& file,
                    const std::optional<std::string>& path, const std::string& words) {
    INFO("sentence: " << sentence);
    const std::string where = !path || path->empty() ? file + ": " : file + ": " + *path + ": ";
    CHECK(sentence.rfind(where, 0) == 0);
    CHECK(sentence.find(words) != std::string::npos);
    CHECK(sentence.find('\n') == std::string::npos);
    CHECK(valid_utf8(sentence));
    // One sentence: none ends inside it and another begins.
    for (std::size_t at = sentence.find(". "); at != std::string::npos;
         at = sentence.find(". ", at + 1)) {
        CHECK_FALSE(
            (at + 2 < sentence.size() && sentence[at + 2] >= 'A' && sentence[at + 2] <= 'Z'));
    }
    for (const char* sign : crash_signs) {
        CHECK(sentence.find(sign) == std::string::npos);
    }
}

// The contract of every verb on bad input: exit 2, exactly one line on stderr,
// that line the sentence.
void check_refused(const Outcome& o, const std::string& file,
                   const std::optional<std::string>& path, const std::string& words) {
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exited);
    CHECK(o.exit_code == 2);
    CHECK(count_of(o.err, "\n") == 1);
    if (o.err.empty() || o.err.back() != '\n') {
        FAIL_CHECK("stderr is not one line");
        return;
    }
    check_sentence(o.err.substr(0, o.err.size() - 1), file, path, words);
}

// `check` reports a broken scene or golden as its row in the table on stdout
// ("  ERROR  NAME  SENTENCE"), exit 2, and prints nothing on stderr.
void check_error_row(const Outcome& o, const std::string& scene_name, const std::string& file,
                     const std::optional<std::string>& path, const std::string& words) {
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exited);
    CHECK(o.exit_code == 2);
    CHECK(o.err.empty());
    std::vector<std::string> rows;
    std::istringstream lines(o.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.find(file) != std::string::npos) {
            rows.push_back(line);
        }
    }
    CHECK(rows.size() == 1);
    const std::string prefix = "  ERROR  " + scene_name;
    if (rows.size() != 1 || rows.front().rfind(prefix, 0) != 0) {
        FAIL_CHECK("no single ERROR row names the file");
        return;
    }
    const std::size_t sentence = rows.front().find_first_not_of(' ', prefix.size());
    if (sentence == std::string::npos) {
        FAIL_CHECK("the ERROR row has no sentence");
        return;
    }
    check_sentence(rows.front().substr(sentence), file, path, words);
    CHECK(o.out.find(" 1 error\n") != std::string::npos);
}

std::string replace_once(const std::string& text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    INFO("replacing: " << from);
    REQUIRE(at != std::string::npos);
    std::string out = text;
    out.replace(at, from.size(), to);
    return out;
}

// The line that starts `  "KEY": `, without its newline.
std::string line_of(const std::string& text, const std::string& key) {
    const std::size_t at = text.find("\n  \"" + key + "\": ");
    INFO("key: " << key);
    REQUIRE(at != std::string::npos);
    return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

// The first `"KEY": VALUE` (a scalar or a flat array) with another value.
std::string with_value(const std::string& text, const std::string& key, const std::string& value) {
    const std::string member = "\"" + key + "\": ";
    const std::size_t at = text.find(member);
    INFO("key: " << key);
    REQUIRE(at != std::string::npos);
    const std::size_t start = at + member.size();
    const std::size_t end =
        text[start] == '[' ? text.find(']', start) + 1 : text.find_first_of(",}", start);
    return text.substr(0, start) + value + text.substr(end);
}

// The first `"KEY": VALUE, ` taken out.
std::string without_member(const std::string& text, const std::string& key) {
    const std::string marked = with_value(text, key, "@");
    const std::size_t at = marked.find("\"" + key + "\": @, ");
    REQUIRE(at != std::string::npos);
    return marked.substr(0, at) + marked.substr(at + key.size() + 7);
}

// A way a file can be wrong: how to write it, and what the sentence about it
// must say.
struct BadFile {
    std::string what;
    std::function<void(const fs::path&)> write;
    std::optional<std::string> path;  // the JSON path named; nullopt: any
    std::string words;                // in the sentence
    bool is_scene_for_render = false; // `render` reads it as a scene (and may draw it)
};

BadFile bad_text(std::string what, std::string text, std::optional<std::string> path,
                 std::string words) {
    return {std::move(what), [text](const fs::path& p) { spit(p, text); }, std::move(path),
            std::move(words)};
}

// Over the loader's size limit without using the disk: a sparse file.
BadFile bad_size(std::string what, std::uintmax_t bytes, std::string words) {
    return {std::move(what),
            [bytes](const fs::path& p) {
                spit(p, "{");
                fs::resize_file(p, bytes);
            },
            std::string(), std::move(words)};
}

// ---------------------------------------------------------------- the gate's root

const std::vector<std::string> gate_scenes = {"drop-box", "glancing"};

// A root with two canonical scenes and their goldens, blessed by this build:
// each case works on a copy of it.
const fs::path& gate_template() {
    static const TempDir dir;
    static const bool blessed = [] {
        fs::create_directories(dir.dir / "harness" / "scenes");
        for (const std::string& name : gate_scenes) {
            fs::copy_file(fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / (name + ".json"),
                          dir.dir / "harness" / "scenes" / (name + ".json"));
        }
        const Outcome o = impulse_tool({"bless", "--root", dir.dir.string()});
        INFO(o.out << o.err);
        return o.exit_code == 0;
    }();
    REQUIRE(blessed);
    return dir.dir;
}

// A copy of the template at DIR/root, so that anything written beside the
// root (an escape from goldens/) shows in a snapshot of DIR.
fs::path copy_of_gate(const TempDir& dir) {
    const fs::path root = dir.dir / "root";
    fs::copy(gate_template(), root, fs::copy_options::recursive);
    return root;
}

std::string golden_of_template(const std::string& name) {
    return slurp(gate_template() / "goldens" / (name + ".json"));
}

// ---------------------------------------------------------------- the runners

// A bad scene through run, render, check and bless: exit 2, the sentence,
// and not one byte written anywhere.
void require_scene_refused(const BadFile& bad) {
    INFO("case: " << bad.what);
    {
        const TempDir dir;
        const fs::path scene = dir.dir / "scene.json";
        bad.write(scene);
        const fs::path existing = dir.dir / "existing.json";
        spit(existing, "the previous trajectory\n");
        const auto before = snapshot(dir.dir);

        // run --out FILE: FILE never appears, not even as a temporary file.
        const fs::path fresh = dir.dir / "trajectory.json";
        const Outcome to_new = impulse_tool({"run", scene.string(), "--out", fresh.string()});
        check_refused(to_new, scene.string(), bad.path, bad.words);
        CHECK(to_new.out.empty());
        CHECK(snapshot(dir.dir) == before);

        // run --out over an existing file: it keeps its bytes.
        const Outcome over = impulse_tool({"run", scene.string(), "--out", existing.string()});
        check_refused(over, scene.string(), bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);

        // run to stdout: nothing on it.
        const Outcome to_stdout = impulse_tool({"run", scene.string()});
        check_refused(to_stdout, scene.string(), bad.path, bad.words);
        CHECK(to_stdout.out.empty());

        // render reads the file as a scene or a trajectory by its schema, so
        // its wording may differ; the contract does not.
        const fs::path picture = dir.dir / "picture.svg";
        const Outcome drawn = impulse_tool({"render", scene.string(), "--out", picture.string()});
        check_refused(drawn, scene.string(), std::nullopt, "");
        CHECK(snapshot(dir.dir) == before);
    }
    {
        // The gate: the broken scene in place of a canonical one that has a golden.
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        const fs::path scene = root / "harness" / "scenes" / "drop-box.json";
        bad.write(scene);
        const auto before = snapshot(dir.dir);
        const std::string r = root.string();

        check_error_row(impulse_tool({"check", "--root", r}), "drop-box", scene.string(), bad.path,
                        bad.words);
        check_error_row(impulse_tool({"check", "drop-box", "--root", r}), "drop-box",
                        scene.string(), bad.path, bad.words);
        check_error_row(impulse_tool({"check", "--root", r}, {"CI=true"}), "drop-box",
                        scene.string(), bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);

        const Outcome all = impulse_tool({"bless", "--root", r});
        check_refused(all, scene.string(), bad.path, bad.words);
        CHECK(all.out.find("1 broken scene") != std::string::npos);
        const Outcome named = impulse_tool({"bless", "drop-box", "--root", r});
        check_refused(named, scene.string(), bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);
    }
}

// A bad trajectory through diff and render, and as a golden through check
// (exit 2, nothing written) and bless (which regenerates it: the repair).
void require_trajectory_refused(const BadFile& bad) {
    INFO("case: " << bad.what);
    {
        const TempDir dir;
        const fs::path good = dir.dir / "good.json";
        spit(good, golden_of_template("drop-box"));
        const fs::path broken = dir.dir / "broken.json";
        bad.write(broken);
        const auto before = snapshot(dir.dir);

        check_refused(impulse_tool({"diff", good.string(), broken.string()}), broken.string(),
                      bad.path, bad.words);
        check_refused(impulse_tool({"diff", broken.string(), good.string()}), broken.string(),
                      bad.path, bad.words);
        if (!bad.is_scene_for_render) {
            const fs::path picture = dir.dir / "picture.svg";
            check_refused(impulse_tool({"render", broken.string(), "--out", picture.string()}),
                          broken.string(), std::nullopt, "");
        }
        CHECK(snapshot(dir.dir) == before);
    }
    {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        const fs::path golden = root / "goldens" / "drop-box.json";
        bad.write(golden);
        const auto before = snapshot(dir.dir);
        const std::string r = root.string();

        check_error_row(impulse_tool({"check", "--root", r}), "drop-box", golden.string(), bad.path,
                        bad.words);
        check_error_row(impulse_tool({"check", "drop-box", "--root", r}), "drop-box",
                        golden.string(), bad.path, bad.words);
        check_error_row(impulse_tool({"check", "--root", r}, {"CI=true"}), "drop-box",
                        golden.string(), bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);

        // Regenerating is how a broken golden is repaired: bless writes the
        // new one whole and says what was wrong with the old.
        const Outcome blessed = impulse_tool({"bless", "--root", r});
        INFO(blessed.out << blessed.err);
        CHECK(blessed.exit_code == 0);
        CHECK(blessed.err.empty());
        CHECK(blessed.out.find("changed    drop-box") != std::string::npos);
        CHECK((blessed.out.find("the old golden does not parse: " + golden.string()) !=
                   std::string::npos ||
               blessed.out.find("the old golden could not be read: " + golden.string()) !=
                   std::string::npos));
        CHECK(slurp(golden) == golden_of_template("drop-box"));
        CHECK(slurp(root / "goldens" / "glancing.json") == golden_of_template("glancing"));
    }
}

// ---------------------------------------------------------------- the scenes

// A valid scene, written over several lines as people write them: a box
// dropped onto static ground. Every case below changes one thing in it.
const std::string valid_scene = R"({
  "schema": "impulse/scene@1",
  "name": "drop",
  "gravity": [0, -9.81],
  "restitution": 0.5,
  "dt": 0.01,
  "duration": 0.5,
  "solver": {"integrator": "symplectic-euler"},
  "bodies": [
    {"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
    {"name": "box", "shape": {"box": [0.5, 0.5]}, "mass": 1, "position": [0, 2]}
  ]
}
)";

// The same with `from` replaced by `to`.
std::string scene_edit(const std::string& from, const std::string& to) {
    return replace_once(valid_scene, from, to);
}

// A valid gas scene (no listed bodies: the block makes them).
const std::string valid_gas_scene = R"({
  "schema": "impulse/scene@1",
  "name": "gas",
  "gravity": [0, 0],
  "dt": 0.01,
  "duration": 0.1,
  "gas": {"count": 4, "shape": {"circle": 0.1}, "mass": 1, "spacing": 0.5, "max_speed": 1}
}
)";

std::string gas_edit(const std::string& from, const std::string& to) {
    return replace_once(valid_gas_scene, from, to);
}

std::string with_scene_name(const std::string& json_string) {
    return scene_edit("\"name\": \"drop\"", "\"name\": " + json_string);
}

const std::string name_rule = "must be 1 to 64 letters, digits, '.', '_' or '-'";

} // namespace

TEST_CASE("The scenes the bad-input cases start from are valid", "[unit][bad-input]") {
    const TempDir dir;
    for (const std::string& text : {valid_scene, valid_gas_scene}) {
        const fs::path scene = dir.dir / "scene.json";
        spit(scene, text);
        const Outcome o = impulse_tool({"run", scene.string()});
        INFO(o.err);
        CHECK(o.exit_code == 0);
        CHECK(o.err.empty());
        CHECK_FALSE(o.out.empty());
    }
}

TEST_CASE("A scene that is not JSON is exit 2, one sentence, nothing written",
          "[unit][bad-input]") {
    const std::string real_scene =
        slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json");
    REQUIRE(real_scene.size() > 100);
    const std::vector<BadFile> cases = {
        bad_text("not JSON", "this is not a scene\n", "", "not valid JSON: line 1, column "),
        bad_text("a bare word where a value belongs", scene_edit("\"drop\"", "drop"), "name",
                 "not valid JSON: line 3"),
        bad_text("empty file", "", "", "not valid JSON"),
        bad_text("only whitespace", "\n\n  \n", "", "not valid JSON"),
        bad_text("truncated: a real scene cut in the middle",
                 real_scene.substr(0, real_scene.size() / 2), std::nullopt, "not valid JSON"),
        bad_text("truncated: the last brace missing", valid_scene.substr(0, valid_scene.rfind('}')),
                 "", "not valid JSON"),
        bad_text("truncated after a key", valid_scene.substr(0, valid_scene.find("0.01")), "dt",
                 "not valid JSON"),
        bad_text("something after the document", valid_scene + "}\n", "", "not valid JSON"),
        bad_text("a merge conflict",
                 scene_edit("  \"restitution\": 0.5,\n",
                            "<<<<<<< HEAD\n  \"restitution\": 0.5,\n=======\n"
                            "  \"restitution\": 0.7,\n>>>>>>> other-branch\n"),
                 "", "has a merge-conflict marker at line 5"),
        bad_text("a leftover ======= alone", scene_edit("  \"dt\"", "=======\n  \"dt\""), "",
                 "has a merge-conflict marker at line 6"),
        bad_text("a leftover >>>>>>> alone", valid_scene + ">>>>>>> theirs\n", "",
                 "has a merge-conflict marker at line 14"),
        bad_text("binary bytes", std::string("\xff\xfe\x00\x01", 4), "", "not valid JSON"),
        bad_text("a string that is not UTF-8",
                 scene_edit("\"name\": \"drop\"", "\"name\": \"dr\xffop\""), "name",
                 "ill-formed UTF-8"),
        bad_text("the top level an array", "[1, 2]\n", "", "the top level must be a JSON object"),
        bad_text("the top level a string", "\"impulse/scene@1\"\n", "",
                 "the top level must be a JSON object"),
        bad_text("nested 10000 levels deep, unclosed", std::string(10000, '['), "",
                 "is nested too deeply"),
        bad_text(
            "nested 10000 levels deep inside a value",
            scene_edit("\"symplectic-euler\"", std::string(10000, '[') + std::string(10000, ']')),
            "", "is nested too deeply"),
        bad_size("a sparse file of 17 MiB, over the 16 MiB limit", 17u * 1024 * 1024,
                 "is too large: more than 16 MiB"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene with the wrong schema, types or keys is exit 2 naming the JSON path",
          "[unit][bad-input]") {
    const std::vector<BadFile> cases = {
        // schema
        bad_text("a trajectory's schema", scene_edit("impulse/scene@1", "impulse/trajectory@1"),
                 "schema", "not a scene: expected \"impulse/scene@1\""),
        bad_text("no version", scene_edit("impulse/scene@1", "impulse/scene"), "schema",
                 "not a scene"),
        bad_text("version 2", scene_edit("impulse/scene@1", "impulse/scene@2"), "schema",
                 "unsupported scene version \"impulse/scene@2\""),
        bad_text("schema a number", scene_edit("\"impulse/scene@1\"", "1"), "schema",
                 "not a scene"),
        bad_text("schema missing", scene_edit("  \"schema\": \"impulse/scene@1\",\n", ""), "schema",
                 "is required but missing"),
        // wrong types
        bad_text("a string for a number", scene_edit("\"dt\": 0.01", "\"dt\": \"0.01\""), "dt",
                 "must be a number, got \"0.01\""),
        bad_text("a number for a string", scene_edit("\"name\": \"drop\"", "\"name\": 5"), "name",
                 "must be a string, got 5"),
        bad_text("a boolean for a number",
                 scene_edit("\"restitution\": 0.5", "\"restitution\": true"), "restitution",
                 "must be a number, got true"),
        bad_text("an object for an array",
                 scene_edit("\"gravity\": [0, -9.81]", "\"gravity\": {\"x\": 0, \"y\": -9.81}"),
                 "gravity", "must be an array of two numbers"),
        bad_text("a string inside an array", scene_edit("[0, -9.81]", "[0, \"down\"]"),
                 "gravity[1]", "must be a number, got \"down\""),
        bad_text("an array for an object",
                 scene_edit("\"solver\": {\"integrator\": \"symplectic-euler\"}",
                            "\"solver\": [\"symplectic-euler\"]"),
                 "solver", "must be an object, got an array"),
        bad_text("a number for a name in the solver",
                 scene_edit("\"integrator\": \"symplectic-euler\"", "\"integrator\": 4"),
                 "solver.integrator", "must be one of"),
        bad_text("an object for the bodies array",
                 R"({"schema": "impulse/scene@1", "name": "drop", "dt": 0.01, "duration": 0.5,
                     "bodies": {"box": {"shape": {"circle": 1}}}})",
                 "bodies", "must be an array, got an object"),
        bad_text("a string for a body",
                 scene_edit("{\"name\": \"box\", \"shape\": {\"box\": [0.5, 0.5]}, "
                            "\"mass\": 1, \"position\": [0, 2]}",
                            "\"box\""),
                 "bodies[1]", "must be an object"),
        bad_text("an array for a shape",
                 scene_edit("\"shape\": {\"box\": [0.5, 0.5]}", "\"shape\": [0.5, 0.5]"),
                 "bodies[1].shape", "must be an object, got an array"),
        bad_text("a string for a boolean", scene_edit("\"static\": true", "\"static\": \"yes\""),
                 "bodies[0].static", "must be true or false, got \"yes\""),
        bad_text("null for a number", scene_edit("\"mass\": 1", "\"mass\": null"), "bodies[1].mass",
                 "must be a number, got null"),
        bad_text("a pair with one number", scene_edit("\"position\": [0, 2]", "\"position\": [2]"),
                 "bodies[1].position", "must be an array of two numbers"),
        bad_text("\"NaN\" as a string", scene_edit("\"mass\": 1", "\"mass\": \"NaN\""),
                 "bodies[1].mass", "must be a number, got \"NaN\""),
        // missing required keys
        bad_text("name missing", scene_edit("  \"name\": \"drop\",\n", ""), "name",
                 "is required but missing"),
        bad_text("dt missing", scene_edit("  \"dt\": 0.01,\n", ""), "dt",
                 "is required but missing"),
        bad_text("duration missing", scene_edit("  \"duration\": 0.5,\n", ""), "duration",
                 "is required but missing"),
        bad_text("bodies missing",
                 R"({"schema": "impulse/scene@1", "name": "drop", "dt": 0.01, "duration": 0.5})",
                 "bodies", "is required but missing"),
        bad_text("a body's name missing", scene_edit("\"name\": \"box\", ", ""), "bodies[1].name",
                 "is required but missing"),
        bad_text("a body's shape missing", scene_edit("\"shape\": {\"box\": [0.5, 0.5]}, ", ""),
                 "bodies[1].shape", "is required but missing"),
        bad_text("the gas block's count missing", gas_edit("\"count\": 4, ", ""), "gas.count",
                 "is required but missing"),
        // unknown keys, with the hint when it is a typo
        bad_text("a typo at the top level", scene_edit("\"gravity\"", "\"gravty\""), "gravty",
                 "unknown key (did you mean gravity?)"),
        bad_text("a typo in a body", scene_edit("\"mass\": 1", "\"mas\": 1"), "bodies[1].mas",
                 "unknown key (did you mean mass?)"),
        bad_text("a typo in the solver", scene_edit("\"integrator\"", "\"integrater\""),
                 "solver.integrater", "unknown key (did you mean integrator?)"),
        bad_text("a typo in the gas block", gas_edit("\"spacing\"", "\"spaceing\""), "gas.spaceing",
                 "unknown key (did you mean spacing?)"),
        bad_text("an unknown key that is no typo",
                 scene_edit("\"gravity\"", "\"comment\": \"x\", \"gravity\""), "comment",
                 "unknown key; expected one of"),
        bad_text("an unknown key that is not an identifier",
                 scene_edit("\"gravity\"", "\"we ird\": 1, \"gravity\""), "[\"we ird\"]",
                 "unknown key"),
        // duplicate keys
        bad_text("a key twice at the top level",
                 scene_edit("\"dt\": 0.01,", "\"dt\": 0.01, \"dt\": 0.02,"), "dt",
                 "appears more than once in the same object"),
        bad_text("a key twice in a body", scene_edit("\"mass\": 1", "\"mass\": 1, \"mass\": 2"),
                 "bodies[1].mass", "appears more than once"),
        bad_text("a key twice in the solver",
                 scene_edit("\"integrator\": \"symplectic-euler\"",
                            "\"integrator\": \"symplectic-euler\", \"integrator\": \"rk4\""),
                 "solver.integrator", "appears more than once"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene with a non-finite or out-of-range number is exit 2 naming the JSON path",
          "[unit][bad-input]") {
    const std::vector<BadFile> cases = {
        // non-finite: JSON has no NaN or Infinity, and 1e999 overflows a double
        bad_text("1e999", scene_edit("\"restitution\": 0.5", "\"restitution\": 1e999"),
                 "restitution", "number overflow parsing '1e999'"),
        bad_text("-1e999 inside an array", scene_edit("[0, 2]", "[0, -1e999]"),
                 "bodies[1].position[1]", "number overflow"),
        bad_text("NaN", scene_edit("\"mass\": 1", "\"mass\": NaN"), "bodies[1].mass",
                 "not valid JSON"),
        bad_text("Infinity", scene_edit("\"dt\": 0.01", "\"dt\": Infinity"), "dt",
                 "not valid JSON"),
        bad_text("-Infinity", scene_edit("[0, -9.81]", "[0, -Infinity]"), "gravity[1]",
                 "not valid JSON"),
        // out of range
        bad_text("negative mass", scene_edit("\"mass\": 1", "\"mass\": -1"), "bodies[1].mass",
                 "must be > 0, got -1"),
        bad_text("zero mass", scene_edit("\"mass\": 1", "\"mass\": 0"), "bodies[1].mass",
                 "must be > 0, got 0"),
        bad_text("negative inertia", scene_edit("\"mass\": 1", "\"mass\": 1, \"inertia\": -2"),
                 "bodies[1].inertia", "must be > 0, got -2"),
        bad_text("e > 1", scene_edit("\"restitution\": 0.5", "\"restitution\": 1.5"), "restitution",
                 "must be between 0 and 1, got 1.5"),
        bad_text("e < 0", scene_edit("\"restitution\": 0.5", "\"restitution\": -0.1"),
                 "restitution", "must be between 0 and 1, got -0.1"),
        bad_text("dt = 0", scene_edit("\"dt\": 0.01", "\"dt\": 0"), "dt", "must be > 0, got 0"),
        bad_text("dt < 0", scene_edit("\"dt\": 0.01", "\"dt\": -0.01"), "dt",
                 "must be > 0, got -0.01"),
        bad_text("duration shorter than dt", scene_edit("\"duration\": 0.5", "\"duration\": 0.001"),
                 "duration", "must be >= dt"),
        bad_text("a huge duration: too many steps",
                 scene_edit("\"duration\": 0.5", "\"duration\": 1e9"), "duration",
                 "steps; at most 10000000 are allowed"),
        bad_text("an absurd duration", scene_edit("\"duration\": 0.5", "\"duration\": 1e300"),
                 "duration", "steps; at most 10000000 are allowed"),
        bad_text("gas count 0", gas_edit("\"count\": 4", "\"count\": 0"), "gas.count",
                 "must be a whole number from 1 to 100000, got 0"),
        bad_text("gas count 2.5", gas_edit("\"count\": 4", "\"count\": 2.5"), "gas.count",
                 "must be a whole number"),
        bad_text("gas count a million", gas_edit("\"count\": 4", "\"count\": 1000000"), "gas.count",
                 "must be a whole number from 1 to 100000"),
        bad_text("gas spacing too small to keep the bodies apart",
                 gas_edit("\"spacing\": 0.5", "\"spacing\": 0.1"), "gas.spacing",
                 "must be more than the shape's bounding diameter"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene with a bad shape or overlapping bodies is exit 2 naming the body",
          "[unit][bad-input]") {
    const auto shape = [](const std::string& json) {
        return scene_edit("\"shape\": {\"box\": [0.5, 0.5]}", "\"shape\": " + json);
    };
    const std::vector<BadFile> cases = {
        bad_text("a non-convex polygon",
                 shape(R"({"polygon": [[-1, -1], [1, -1], [1, 1], [0, 0], [-1, 1]]})"),
                 "bodies[1].shape.polygon[3]", "is a reflex corner"),
        bad_text("a clockwise polygon", shape(R"({"polygon": [[-1, -1], [0, 1], [1, -1]]})"),
                 "bodies[1].shape.polygon", "must be counter-clockwise (positive area)"),
        bad_text("a zero-area polygon", shape(R"({"polygon": [[0, 0], [1, 0], [2, 0]]})"),
                 "bodies[1].shape.polygon", "got area 0"),
        bad_text("a polygon too small to have an area",
                 shape(R"({"polygon": [[-1e-200, -1e-200], [1e-200, -1e-200], [0, 1e-200]]})"),
                 "bodies[1].shape.polygon", "got area 0"),
        bad_text("a repeated vertex", shape(R"({"polygon": [[-1, -1], [1, -1], [1, -1], [0, 1]]})"),
                 "bodies[1].shape.polygon[2]", "repeats vertex 1"),
        bad_text("every vertex the same", shape(R"({"polygon": [[0, 0], [0, 0], [0, 0]]})"),
                 "bodies[1].shape.polygon[0]", "repeats vertex"),
        bad_text("two vertices", shape(R"({"polygon": [[0, 0], [1, 0]]})"),
                 "bodies[1].shape.polygon", "must have 3 to"),
        bad_text("zero radius", shape(R"({"circle": 0})"), "bodies[1].shape.circle",
                 "must be > 0, got 0"),
        bad_text("negative radius", shape(R"({"circle": -1})"), "bodies[1].shape.circle",
                 "must be > 0, got -1"),
        bad_text("a radius too small for an inertia", shape(R"({"circle": 1e-300})"), "bodies[1]",
                 "moment of inertia"),
        bad_text("a zero half extent", shape(R"({"box": [0.5, 0]})"), "bodies[1].shape.box[1]",
                 "must be > 0, got 0"),
        bad_text("both half extents zero: the first is named", shape(R"({"box": [0, 0]})"),
                 "bodies[1].shape.box[0]", "must be > 0, got 0"),
        bad_text("two kinds of shape", shape(R"({"box": [0.5, 0.5], "circle": 1})"),
                 "bodies[1].shape.circle",
                 "a shape is exactly one of box, circle or polygon; this one also has box"),
        bad_text("no shape kind", shape("{}"), "bodies[1].shape",
                 "must have one of box, circle or polygon"),
        bad_text("a box sunk into the ground", scene_edit("[0, 2]", "[0, 0.4]"), "bodies[1]",
                 "'box' overlaps bodies[0] 'ground' at t = 0"),
        bad_text("two dynamic bodies overlapping",
                 scene_edit("\"position\": [0, 2]}",
                            "\"position\": [0, 2]},\n    {\"name\": \"ball\", \"shape\": "
                            "{\"circle\": 0.5}, \"position\": [0.5, 2.5]}"),
                 "bodies[2]", "overlaps bodies[1] 'box'"),
        bad_text("every body static", scene_edit("\"mass\": 1", "\"static\": true"), "bodies",
                 "every body is static"),
        bad_text("two bodies of one name", scene_edit("\"name\": \"box\"", "\"name\": \"ground\""),
                 "bodies[1].name", "is already the name of bodies[0]"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene or body name that is no plain word, or would leave goldens/, is exit 2",
          "[unit][bad-input]") {
    // As the scene's "name" a golden would be goldens/NAME.json: none of these
    // may become a path. The gate runs in a root inside a temporary folder,
    // whose snapshot shows anything written beside the root, too.
    const std::vector<std::string> names = {
        R"("a b")",  R"("")",        R"("ünïcode")",     "\"" + std::string(100, 'a') + "\"",
        R"("../x")", R"("../../x")", R"("/etc/passwd")", R"("..")",
        R"(".")",    R"(".hidden")", R"("a/b")",         R"("a\\b")",
        R"("-rf")",  R"("a\nb")",    R"("a\u0000b")",    R"("x.json\u0000")",
        R"("a:b")",  R"("a*")",      R"("~")",           R"("$HOME")",
    };
    std::vector<BadFile> cases;
    for (const std::string& name : names) {
        cases.push_back(bad_text("scene name " + name, with_scene_name(name), "name", name_rule));
        cases.push_back(bad_text("body name " + name,
                                 scene_edit("\"name\": \"box\"", "\"name\": " + name),
                                 "bodies[1].name", name_rule));
    }
    cases.push_back(bad_text("a name of 65 characters",
                             with_scene_name("\"" + std::string(65, 'a') + "\""), "name",
                             name_rule));
    // A long name of two-byte characters is shortened in the message without
    // cutting a character in half, wherever the cut falls.
    for (const std::string start : {"", "a", "ab"}) {
        std::string long_unicode = "\"" + start;
        for (int i = 0; i < 40; ++i) {
            long_unicode += "\u00fc"; // ü
        }
        long_unicode += "\"";
        cases.push_back(bad_text("a long name of non-ASCII letters after '" + start + "'",
                                 with_scene_name(long_unicode), "name", name_rule));
    }
    cases.push_back(bad_text("not a name but a number", with_scene_name("0"), "name",
                             "must be a string, got 0"));
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    CHECK_FALSE(fs::exists("/etc/passwd.json"));
    CHECK_FALSE(fs::exists("/x.json"));
}

TEST_CASE("A scene argument that names no scene file is exit 2 and writes nothing",
          "[unit][bad-input]") {
    // check and bless take a scene's name or path. An argument that is not a
    // scene file is refused; nothing is written, in goldens/ or beside it.
    const TempDir dir;
    const fs::path root = copy_of_gate(dir);
    fs::create_directories(dir.dir / "scene-is-a-folder.json");
    spit(dir.dir / "passwd", "root:x:0:0:root:/root:/bin/bash\n"); // a file, but no scene
    const auto before = snapshot(dir.dir);
    const std::string r = root.string();
    const std::string scenes = (root / "harness" / "scenes").string();
    struct Argument {
        std::string given;
        std::string file; // the file the sentence names
        std::string words;
    };
    const std::vector<Argument> arguments = {
        {"no-such-scene", scenes + "/no-such-scene.json", "cannot be read (no such file"},
        {"a b", scenes + "/a b.json", "cannot be read"},
        {"a\\b", scenes + "/a\\b.json", "cannot be read"},
        {"..", scenes + "/...json", "cannot be read"},
        {"", scenes + "/.json", "cannot be read"},
        {"../x", "../x", "cannot be read"},
        {"a/b", "a/b", "cannot be read"},
        {(dir.dir / "missing.json").string(), (dir.dir / "missing.json").string(),
         "cannot be read (no such file"},
        {(dir.dir / "scene-is-a-folder.json").string(),
         (dir.dir / "scene-is-a-folder.json").string(), "cannot be read (it is a directory)"},
        {(dir.dir / "passwd").string(), (dir.dir / "passwd").string(), "not valid JSON"},
    };
    for (const Argument& a : arguments) {
        INFO("argument: '" << a.given << "'");
        check_refused(impulse_tool({"bless", a.given, "--root", r}), a.file, "", a.words);
        const Outcome checked = impulse_tool({"check", a.given, "--root", r});
        CHECK(checked.exit_code == 2);
        CHECK(checked.err.empty());
        CHECK(checked.out.find("  ERROR  ") != std::string::npos);
        CHECK(checked.out.find(a.file + ": ") != std::string::npos);
        // run takes a path: the sentence names the argument as given.
        const std::string run_file = a.given.empty()                ? std::string("<input>")
                                     : a.file.rfind(scenes, 0) == 0 ? a.given
                                                                    : a.file;
        check_refused(impulse_tool({"run", a.given}), run_file, "",
                      a.words == "not valid JSON" ? a.words : "cannot be read");
        CHECK(snapshot(dir.dir) == before);
    }
}

TEST_CASE("A scene whose file is not NAME.json is exit 2 and takes no other scene's golden",
          "[unit][bad-input]") {
    // Its golden would be goldens/NAME.json: a copied scene file that kept its
    // name, or a renamed one, would overwrite another scene's golden.
    const TempDir dir;
    const fs::path root = copy_of_gate(dir);
    const fs::path scenes = root / "harness" / "scenes";
    const std::string r = root.string();
    SECTION("a copy of another scene under a new file name") {
        spit(scenes / "zz-copy.json",
             replace_once(slurp(scenes / "glancing.json"), "\"name\": \"glancing\"",
                          "\"name\": \"drop-box\""));
    }
    SECTION("a scene file renamed without its name") {
        fs::rename(scenes / "drop-box.json", scenes / "zz-copy.json");
    }
    const fs::path stray = scenes / "zz-copy.json";
    const auto before = snapshot(dir.dir);
    const std::string words =
        "is \"drop-box\" but the file is zz-copy.json: a scene's golden is goldens/NAME.json";
    check_refused(impulse_tool({"bless", "--root", r}), stray.string(), "name", words);
    check_refused(impulse_tool({"bless", stray.string(), "--root", r}), stray.string(), "name",
                  words);
    check_error_row(impulse_tool({"check", stray.string(), "--root", r}), "zz-copy", stray.string(),
                    "name", words);
    CHECK(snapshot(dir.dir) == before);
    CHECK(slurp(root / "goldens" / "drop-box.json") == golden_of_template("drop-box"));
}

// ---------------------------------------------------------------- trajectories and goldens

TEST_CASE("A trajectory or golden that is not JSON is exit 2 and no golden is touched",
          "[unit][bad-input]") {
    const std::string golden = golden_of_template("drop-box");
    const std::string digest = line_of(golden, "digest");
    const std::vector<BadFile> cases = {
        bad_text("not JSON", "this is not a trajectory\n", "", "not valid JSON: line 1, column "),
        bad_text("empty file", "", "", "not valid JSON"),
        bad_text("truncated in the middle", golden.substr(0, golden.size() / 2), std::nullopt,
                 "not valid JSON"),
        bad_text("truncated: the last brace missing", golden.substr(0, golden.rfind('}')), "",
                 "not valid JSON"),
        bad_text("one byte", golden.substr(0, 1), "", "not valid JSON"),
        bad_text("two goldens in one file", golden + golden, "", "not valid JSON"),
        bad_text("a merge conflict in the digest",
                 replace_once(golden, digest + "\n",
                              "<<<<<<< HEAD\n" + digest + "\n=======\n" +
                                  "  \"digest\": \"0123456789abcdef\",\n>>>>>>> other-branch\n"),
                 "", "has a merge-conflict marker at line 7"),
        bad_text("a merge conflict at the end", golden + "=======\n", "",
                 "has a merge-conflict marker at line"),
        bad_text("binary bytes", std::string("\x89PNG\r\n\x1a\n", 8), "", "not valid JSON"),
        bad_text("the top level an array", "[1, 2]\n", "", "the top level must be a JSON object"),
        bad_text("nested 10000 levels deep", std::string(10000, '['), "", "is nested too deeply"),
        bad_text("nested 10000 levels deep, closed",
                 std::string(10000, '[') + std::string(10000, ']'), "", "is nested too deeply"),
        bad_size("a sparse file over the 256 MiB limit", 256u * 1024 * 1024 + 1,
                 "is too large: more than 256 MiB"),
    };
    for (const BadFile& bad : cases) {
        require_trajectory_refused(bad);
    }
}

TEST_CASE("A trajectory or golden with a wrong schema, type, key or number is exit 2 naming the "
          "JSON path",
          "[unit][bad-input]") {
    const std::string golden = golden_of_template("drop-box");
    const std::string edit_of_first_frame = "\"frames\": [\n    [0, 0, 1.5, 0, 0, 0, 0]";
    REQUIRE(golden.find(edit_of_first_frame) != std::string::npos);
    const auto frame0 = [&](const std::string& values) {
        return replace_once(golden, edit_of_first_frame, "\"frames\": [\n    " + values);
    };
    const auto edit = [&](const std::string& from, const std::string& to) {
        return replace_once(golden, from, to);
    };
    const std::string columns = line_of(golden, "columns");
    const std::string digest = line_of(golden, "digest");
    const std::string sha = line_of(golden, "scene_sha256");
    const std::string scene_file =
        slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json");
    BadFile scene_as_golden = bad_text("a scene file where a golden belongs", scene_file, "schema",
                                       "must be \"impulse/trajectory@1\", got \"impulse/scene@1\"");
    scene_as_golden.is_scene_for_render = true;

    const std::vector<BadFile> cases = {
        // schema
        bad_text("a scene's schema", edit("\"impulse/trajectory@1\"", "\"impulse/scene@1\""),
                 "schema", "must be \"impulse/trajectory@1\""),
        bad_text("version 2", edit("\"impulse/trajectory@1\"", "\"impulse/trajectory@2\""),
                 "schema", "version 2 of the trajectory format is not supported"),
        bad_text("schema missing", edit("  \"schema\": \"impulse/trajectory@1\",\n", ""), "schema",
                 "the required key is missing"),
        scene_as_golden,
        // wrong types
        bad_text("a number for a string", edit("\"scene\": \"drop-box\"", "\"scene\": 5"), "scene",
                 "must be a string, got 5"),
        bad_text("a string for a number", frame0("[0, 0, \"1.5\", 0, 0, 0, 0]"), "frames[0][2]",
                 "must be a number, got \"1.5\""),
        bad_text("null for a number", frame0("[0, 0, 1.5, null, 0, 0, 0]"), "frames[0][3]",
                 "must be a number, got null"),
        bad_text("an object for a frame", frame0("{\"t\": 0}"), "frames[0]",
                 "must be an array, got an object"),
        bad_text("an object for the columns", edit(columns, "  \"columns\": {\"t\": 0},"),
                 "columns", "must be an array, got an object"),
        bad_text("an array for the solver",
                 edit(line_of(golden, "solver"), "  \"solver\": [\"verlet\"],"), "solver",
                 "must be an object, got an array"),
        bad_text("a number for the digest", edit(digest, "  \"digest\": 12,"), "digest",
                 "must be a string, got 12"),
        bad_text("a number for an event's body", edit("\"a\": \"box\"", "\"a\": 7"), "events[0].a",
                 "must be a string, got 7"),
        bad_text("an object for an event's point",
                 with_value(golden, "point", "{\"x\": 0, \"y\": 0}"), "events[0].point",
                 "must be an array, got an object"),
        bad_text("a boolean for an event's impulse", with_value(golden, "impulse", "true"),
                 "events[0].impulse", "must be a number, got true"),
        // missing and unknown keys
        bad_text("the digest missing", edit(digest + "\n", ""), "digest",
                 "the required key is missing"),
        bad_text("the columns missing", edit(columns + "\n", ""), "columns",
                 "the required key is missing"),
        bad_text("scene_sha256 missing", edit(sha + "\n", ""), "scene_sha256",
                 "the required key is missing"),
        bad_text("an event's impulse missing", without_member(golden, "impulse"),
                 "events[0].impulse", "the required key is missing"),
        bad_text("a typo in an event", edit("\"impulse\": ", "\"impulze\": "), "events[0].impulze",
                 "unknown key (did you mean impulse?)"),
        bad_text("a typo at the top level", edit("\"frames\": [", "\"framez\": ["), "framez",
                 "unknown key (did you mean frames?)"),
        bad_text("an unknown key", edit(digest, digest + "\n  \"comment\": \"hand-edited\","),
                 "comment", "unknown key; the keys allowed here are"),
        // duplicate keys
        bad_text("the digest twice", edit(digest, digest + "\n" + digest), "digest",
                 "appears more than once in the same object"),
        bad_text("a solver key twice",
                 edit("\"toi\": \"bisection\"", "\"toi\": \"bisection\", \"toi\": \"secant\""),
                 "solver.toi", "appears more than once"),
        // non-finite and inexact numbers
        bad_text("1e999 in a frame", frame0("[0, 0, 1e999, 0, 0, 0, 0]"), "frames[0][2]",
                 "number overflow parsing '1e999'"),
        bad_text("NaN in a frame", frame0("[0, 0, NaN, 0, 0, 0, 0]"), "frames[0][2]",
                 "not valid JSON"),
        bad_text("Infinity in a frame", frame0("[0, 0, 1.5, 0, 0, Infinity, 0]"), "frames[0][5]",
                 "not valid JSON"),
        bad_text("-Infinity in an event", with_value(golden, "vn_after", "-Infinity"),
                 "events[0].vn_after", "not valid JSON"),
        bad_text("an integer a double cannot hold",
                 frame0("[0, 9007199254740993, 1.5, 0, 0, 0, 0]"), "frames[0][1]",
                 "cannot be held exactly by a double"),
        // columns and frames that do not match
        bad_text("a frame one value short", frame0("[0, 0, 1.5, 0, 0, 0]"), "frames[0]",
                 "has 6 values but there are 7 columns"),
        bad_text("a frame one value long", frame0("[0, 0, 1.5, 0, 0, 0, 0, 0]"), "frames[0]",
                 "has 8 values but there are 7 columns"),
        bad_text("a column missing", edit(", \"box.omega\"]", "]"), "frames[0]",
                 "has 7 values but there are 6 columns"),
        bad_text("a column too many", edit("\"box.omega\"]", "\"box.omega\", \"box.spin\"]"),
                 "frames[0]", "has 7 values but there are 8 columns"),
        bad_text("no columns", edit(columns, "  \"columns\": [],"), "columns",
                 "the first column must be \"t\""),
        bad_text("a column repeated", edit("\"box.y\"", "\"box.x\""), "columns[2]",
                 "repeats columns[1]"),
        // digests
        bad_text("a wrong digest", edit(digest, "  \"digest\": \"0123456789abcdef\","), "digest",
                 "stored digest 0123456789abcdef does not match the data"),
        bad_text("a number edited by hand", frame0("[0, 0, 1.25, 0, 0, 0, 0]"), "digest",
                 "does not match the data"),
        bad_text("a digest in capitals", edit(digest, "  \"digest\": \"0123456789ABCDEF\","),
                 "digest", "must be 16 lowercase hex digits"),
        bad_text("a short scene_sha256", edit(sha, "  \"scene_sha256\": \"abc\","), "scene_sha256",
                 "must be 64 lowercase hex digits"),
    };
    for (const BadFile& bad : cases) {
        require_trajectory_refused(bad);
    }
}

TEST_CASE("A missing golden or a golden that is a folder is exit 2 and nothing is written",
          "[unit][bad-input]") {
    const TempDir dir;
    const fs::path root = copy_of_gate(dir);
    const fs::path golden = root / "goldens" / "drop-box.json";
    const std::string r = root.string();

    fs::remove(golden);
    auto before = snapshot(dir.dir);
    check_error_row(impulse_tool({"check", "--root", r}), "drop-box", golden.string(), "",
                    "no golden for scene 'drop-box'; bless it with scripts/regen-goldens drop-box");
    check_error_row(impulse_tool({"check", "--root", r}, {"CI=true"}), "drop-box", golden.string(),
                    "", "no golden for scene 'drop-box'");
    CHECK(snapshot(dir.dir) == before);

    // A folder where the golden belongs: check cannot read it, bless cannot
    // replace it; neither leaves a file behind.
    fs::create_directories(golden);
    before = snapshot(dir.dir);
    check_error_row(impulse_tool({"check", "--root", r}), "drop-box", golden.string(), "",
                    "cannot be read (it is a directory)");
    const Outcome blessed = impulse_tool({"bless", "--root", r});
    check_refused(blessed, golden.string(), "", "cannot be written");
    CHECK(snapshot(dir.dir) == before);
}

TEST_CASE("A stale golden is exit 1 and named stale, not a broken input", "[unit][bad-input]") {
    // DESIGN.md: a golden whose scene_sha256 no longer matches its scene is
    // reported as stale, not as a physics diff; README: exit 1.
    const std::string golden = golden_of_template("drop-box");
    const std::string sha = line_of(golden, "scene_sha256");
    const auto require_stale = [](const Outcome& o) {
        INFO(o.out << o.err);
        CHECK(o.exited);
        CHECK(o.exit_code == 1);
        CHECK(o.out.find("FAILED drop-box  stale golden: the scene changed since it was blessed; "
                         "if that was intended, run scripts/regen-goldens drop-box") !=
              std::string::npos);
        CHECK(o.out.find("ERROR") == std::string::npos);
    };

    SECTION("the golden records another scene_sha256, the motion the same") {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        spit(root / "goldens" / "drop-box.json",
             replace_once(golden, sha, "  \"scene_sha256\": \"" + std::string(64, '0') + "\","));
        const auto before = snapshot(dir.dir);
        require_stale(impulse_tool({"check", "--root", root.string()}));
        require_stale(impulse_tool({"check", "--root", root.string()}, {"CI=true"}));
        CHECK(snapshot(dir.dir) == before);
    }
    SECTION("the scene's description was edited since the blessing") {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        const fs::path scene = root / "harness" / "scenes" / "drop-box.json";
        spit(scene,
             replace_once(slurp(scene), "\"description\": \"", "\"description\": \"Edited. "));
        const auto before = snapshot(dir.dir);
        require_stale(impulse_tool({"check", "--root", root.string()}));
        CHECK(snapshot(dir.dir) == before);
        // Blessing again is the way out.
        CHECK(impulse_tool({"bless", "--root", root.string()}).exit_code == 0);
        CHECK(impulse_tool({"check", "--root", root.string()}).exit_code == 0);
    }
    SECTION("the golden of another scene") {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        fs::copy_file(root / "goldens" / "glancing.json", root / "goldens" / "drop-box.json",
                      fs::copy_options::overwrite_existing);
        const auto before = snapshot(dir.dir);
        const Outcome o = impulse_tool({"check", "--root", root.string()});
        require_stale(o);
        CHECK(snapshot(dir.dir) == before);
    }
    SECTION("diff only notes a different scene_sha256") {
        const TempDir dir;
        const fs::path a = dir.dir / "a.json", b = dir.dir / "b.json";
        spit(a, golden);
        spit(b, replace_once(golden, sha, "  \"scene_sha256\": \"" + std::string(64, 'f') + "\","));
        const Outcome o = impulse_tool({"diff", a.string(), b.string()});
        CHECK(o.exit_code == 0);
        CHECK(o.out.find("scene_sha256 differs") != std::string::npos);
        CHECK(o.out.find("identical") != std::string::npos);
    }
}
