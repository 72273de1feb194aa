// --engine-command's words (harness/cli/command_words.cpp): what sh would pass
// to the program for the same string, each expected list written from the
// POSIX rules (XCU 2.2 Quoting), with nothing expanded.
#include "cli.h"
#include "command_words.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using impulse::harness::cli::command_words;
using impulse::harness::cli::UsageError;
using Words = std::vector<std::string>;

TEST_CASE("blanks separate words, and runs of them are one separator", "[command-words]") {
    CHECK(command_words("python3 engine/run.py") == Words{"python3", "engine/run.py"});
    CHECK(command_words("  ./eng \t --fast\n-v  ") == Words{"./eng", "--fast", "-v"});
}

TEST_CASE("quotes keep a word with spaces in it", "[command-words]") {
    CHECK(command_words("node 'my engine.js' --fast") == Words{"node", "my engine.js", "--fast"});
    CHECK(command_words("node \"my engine.js\"") == Words{"node", "my engine.js"});
    // Quoted and unquoted parts next to each other are one word.
    CHECK(command_words("./run --dir='a b'/c") == Words{"./run", "--dir=a b/c"});
    // An empty quote is an empty word, as sh passes it.
    CHECK(command_words("prog '' \"\"") == Words{"prog", "", ""});
}

TEST_CASE("inside single quotes every character is itself", "[command-words]") {
    CHECK(command_words(R"(echo 'a\b "c" $d')") == Words{"echo", R"(a\b "c" $d)"});
}

TEST_CASE("inside double quotes a backslash escapes only \" \\ $ and `", "[command-words]") {
    CHECK(command_words(R"(echo "a\"b" "c\\d" "e\$f" "g\`h")") ==
          Words{"echo", "a\"b", "c\\d", "e$f", "g`h"});
    // Before any other character the backslash stays.
    CHECK(command_words(R"(echo "a\nb" "it's")") == Words{"echo", R"(a\nb)", "it's"});
}

TEST_CASE("outside quotes a backslash keeps the next character", "[command-words]") {
    CHECK(command_words(R"(./my\ engine \'x\' \\)") == Words{"./my engine", "'x'", "\\"});
    // A backslash-newline is a line continuation: it is removed, joining nothing new.
    CHECK(command_words("a\\\nb c \\\n d") == Words{"ab", "c", "d"});
}

TEST_CASE("nothing is expanded: no variables, home, globs or operators", "[command-words]") {
    CHECK(command_words("prog $HOME ~ *.json a|b c;d >out") ==
          Words{"prog", "$HOME", "~", "*.json", "a|b", "c;d", ">out"});
}

TEST_CASE("a string a shell could not split, or with no word, is refused", "[command-words]") {
    for (const std::string& bad : {std::string("node 'my engine.js"), std::string("node \"x"),
                                   std::string("node x\\"), std::string("   "), std::string()}) {
        INFO(bad);
        CHECK_THROWS_AS(command_words(bad), UsageError);
    }
    try {
        command_words("node 'my engine.js");
        FAIL("an unclosed quote was accepted");
    } catch (const UsageError& e) {
        const std::string message = e.what();
        CHECK(message.find("--engine-command") != std::string::npos);
        CHECK(message.find("never closed") != std::string::npos);
        CHECK(message.find("node 'my engine.js") != std::string::npos);
    }
}
