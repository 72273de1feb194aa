// The contract of every verb on bad input (test_bad_scenes.cpp,
// test_bad_trajectories.cpp): exit code 2, one sentence on stderr naming the
// file and the JSON path, nothing written; the ways a file can be wrong, the
// gate's root the cases work on, and the runners that feed a bad file to
// every verb that reads it.
#pragma once

#include "files.h"
#include "tool.h"
#include "utf8.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace impulse::test {

// 64-bit FNV-1a of a file's bytes.
inline std::uint64_t file_hash(const std::filesystem::path& path) {
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
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
    std::map<std::string, std::string> entries;
    for (const std::filesystem::directory_entry& e :
         std::filesystem::recursive_directory_iterator(dir)) {
        const std::string name = std::filesystem::relative(e.path(), dir).string();
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

inline std::size_t count_of(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
        ++n;
    }
    return n;
}

// What a crash, an escaped exception or a sanitizer report prints.
inline const char* const crash_signs[] = {"terminate called", "what():",          "internal error",
                                          "Aborted",          "Segmentation",     "core dumped",
                                          "[json.exception",  "AddressSanitizer", "runtime error:"};

// One sentence: "FILE: PATH: ..." (or "FILE: ..." when `path` is "", any path
// when it is nullopt: where a parser stopped) holding `words`; readable text.
inline void check_sentence(const std::string& sentence, const std::string& file,
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
inline void check_refused(const Outcome& o, const std::string& file,
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
inline void check_error_row(const Outcome& o, const std::string& scene_name,
                            const std::string& file, const std::optional<std::string>& path,
                            const std::string& words) {
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

inline std::string replace_once(const std::string& text, const std::string& from,
                                const std::string& to) {
    const std::size_t at = text.find(from);
    INFO("replacing: " << from);
    REQUIRE(at != std::string::npos);
    std::string out = text;
    out.replace(at, from.size(), to);
    return out;
}

// The line that starts `  "KEY": `, without its newline.
inline std::string line_of(const std::string& text, const std::string& key) {
    const std::size_t at = text.find("\n  \"" + key + "\": ");
    INFO("key: " << key);
    REQUIRE(at != std::string::npos);
    return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

// The first `"KEY": VALUE` (a scalar or a flat array) with another value.
inline std::string with_value(const std::string& text, const std::string& key,
                              const std::string& value) {
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
inline std::string without_member(const std::string& text, const std::string& key) {
    const std::string marked = with_value(text, key, "@");
    const std::size_t at = marked.find("\"" + key + "\": @, ");
    REQUIRE(at != std::string::npos);
    return marked.substr(0, at) + marked.substr(at + key.size() + 7);
}

// A way a file can be wrong: how to write it, and what the sentence about it
// must say.
struct BadFile {
    std::string what;
    std::function<void(const std::filesystem::path&)> write;
    std::optional<std::string> path;  // the JSON path named; nullopt: any
    std::string words;                // in the sentence
    bool is_scene_for_render = false; // `render` reads it as a scene (and may draw it)
};

inline BadFile bad_text(std::string what, std::string text, std::optional<std::string> path,
                        std::string words) {
    return {std::move(what), [text](const std::filesystem::path& p) { spit(p, text); },
            std::move(path), std::move(words)};
}

// Over the loader's size limit without using the disk: a sparse file.
inline BadFile bad_size(std::string what, std::uintmax_t bytes, std::string words) {
    return {std::move(what),
            [bytes](const std::filesystem::path& p) {
                spit(p, "{");
                std::filesystem::resize_file(p, bytes);
            },
            std::string(), std::move(words)};
}

// ---------------------------------------------------------------- the gate's root

inline const std::vector<std::string> gate_scenes = {"drop-box", "glancing"};

// A root with two canonical scenes and their goldens, blessed by this build:
// each case works on a copy of it.
inline const std::filesystem::path& gate_template() {
    static const TempDir dir;
    static const bool blessed = [] {
        std::filesystem::create_directories(dir.dir / "harness" / "scenes");
        for (const std::string& name : gate_scenes) {
            std::filesystem::copy_file(std::filesystem::path(IMPULSE_SOURCE_DIR) / "harness" /
                                           "scenes" / (name + ".json"),
                                       dir.dir / "harness" / "scenes" / (name + ".json"));
        }
        const Outcome o = run_tool({"bless", "--root", dir.dir.string()});
        INFO(o.out << o.err);
        return o.exit_code == 0;
    }();
    REQUIRE(blessed);
    return dir.dir;
}

// A copy of the template at DIR/root, so that anything written beside the
// root (an escape from goldens/) shows in a snapshot of DIR.
inline std::filesystem::path copy_of_gate(const TempDir& dir) {
    const std::filesystem::path root = dir.dir / "root";
    std::filesystem::copy(gate_template(), root, std::filesystem::copy_options::recursive);
    return root;
}

inline std::string golden_of_template(const std::string& name) {
    return slurp(gate_template() / "goldens" / (name + ".json"));
}

// ---------------------------------------------------------------- the runners

// A bad scene through run, render, check and bless: exit 2, the sentence,
// and not one byte written anywhere.
inline void require_scene_refused(const BadFile& bad) {
    INFO("case: " << bad.what);
    {
        const TempDir dir;
        const std::filesystem::path scene = dir.dir / "scene.json";
        bad.write(scene);
        const std::filesystem::path existing = dir.dir / "existing.json";
        spit(existing, "the previous trajectory\n");
        const auto before = snapshot(dir.dir);

        // run --out FILE: FILE never appears, not even as a temporary file.
        const std::filesystem::path fresh = dir.dir / "trajectory.json";
        const Outcome to_new = run_tool({"run", scene.string(), "--out", fresh.string()});
        check_refused(to_new, scene.string(), bad.path, bad.words);
        CHECK(to_new.out.empty());
        CHECK(snapshot(dir.dir) == before);

        // run --out over an existing file: it keeps its bytes.
        const Outcome over = run_tool({"run", scene.string(), "--out", existing.string()});
        check_refused(over, scene.string(), bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);

        // run to stdout: nothing on it.
        const Outcome to_stdout = run_tool({"run", scene.string()});
        check_refused(to_stdout, scene.string(), bad.path, bad.words);
        CHECK(to_stdout.out.empty());

        // render reads the file as a scene or a trajectory by its schema, so
        // its wording may differ; the contract does not.
        const std::filesystem::path picture = dir.dir / "picture.svg";
        const Outcome drawn = run_tool({"render", scene.string(), "--out", picture.string()});
        check_refused(drawn, scene.string(), std::nullopt, "");
        CHECK(snapshot(dir.dir) == before);
    }
    {
        // The gate: the broken scene in place of a canonical one that has a golden.
        const TempDir dir;
        const std::filesystem::path root = copy_of_gate(dir);
        const std::filesystem::path scene = root / "harness" / "scenes" / "drop-box.json";
        bad.write(scene);
        const auto before = snapshot(dir.dir);
        const std::string r = root.string();

        check_error_row(run_tool({"check", "--root", r}), "drop-box", scene.string(), bad.path,
                        bad.words);
        check_error_row(run_tool({"check", "drop-box", "--root", r}), "drop-box", scene.string(),
                        bad.path, bad.words);
        check_error_row(run_tool({"check", "--root", r}, {"CI=true"}), "drop-box", scene.string(),
                        bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);

        const Outcome all = run_tool({"bless", "--root", r});
        check_refused(all, scene.string(), bad.path, bad.words);
        CHECK(all.out.find("1 broken scene") != std::string::npos);
        const Outcome named = run_tool({"bless", "drop-box", "--root", r});
        check_refused(named, scene.string(), bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);
    }
}

// A bad trajectory through diff and render, and as a golden through check
// (exit 2, nothing written) and bless (which regenerates it: the repair).
inline void require_trajectory_refused(const BadFile& bad) {
    INFO("case: " << bad.what);
    {
        const TempDir dir;
        const std::filesystem::path good = dir.dir / "good.json";
        spit(good, golden_of_template("drop-box"));
        const std::filesystem::path broken = dir.dir / "broken.json";
        bad.write(broken);
        const auto before = snapshot(dir.dir);

        check_refused(run_tool({"diff", good.string(), broken.string()}), broken.string(), bad.path,
                      bad.words);
        check_refused(run_tool({"diff", broken.string(), good.string()}), broken.string(), bad.path,
                      bad.words);
        if (!bad.is_scene_for_render) {
            const std::filesystem::path picture = dir.dir / "picture.svg";
            check_refused(run_tool({"render", broken.string(), "--out", picture.string()}),
                          broken.string(), std::nullopt, "");
        }
        CHECK(snapshot(dir.dir) == before);
    }
    {
        const TempDir dir;
        const std::filesystem::path root = copy_of_gate(dir);
        const std::filesystem::path golden = root / "goldens" / "drop-box.json";
        bad.write(golden);
        const auto before = snapshot(dir.dir);
        const std::string r = root.string();

        check_error_row(run_tool({"check", "--root", r}), "drop-box", golden.string(), bad.path,
                        bad.words);
        check_error_row(run_tool({"check", "drop-box", "--root", r}), "drop-box", golden.string(),
                        bad.path, bad.words);
        check_error_row(run_tool({"check", "--root", r}, {"CI=true"}), "drop-box", golden.string(),
                        bad.path, bad.words);
        CHECK(snapshot(dir.dir) == before);

        // Regenerating is how a broken golden is repaired: bless writes the
        // new one whole and says what was wrong with the old.
        const Outcome blessed = run_tool({"bless", "--root", r});
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

} // namespace impulse::test
