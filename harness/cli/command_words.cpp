#include "command_words.h"

#include "cli.h"

namespace impulse::harness::cli {

namespace {

bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\n';
}

// Characters a backslash escapes inside double quotes (POSIX, 2.2.3).
bool escapes_in_double_quotes(char c) {
    return c == '"' || c == '\\' || c == '$' || c == '`';
}

[[noreturn]] void refuse(const std::string& command, const std::string& why) {
    throw UsageError("--engine-command " + why + " (" + command +
                     "); a word with spaces is quoted as in a shell: 'my engine.py'");
}

} // namespace

std::vector<std::string> command_words(const std::string& command) {
    std::vector<std::string> words;
    std::string word;
    bool in_word = false; // a quote starts a word even when it stays empty
    for (std::size_t i = 0; i < command.size(); ++i) {
        const char c = command[i];
        if (is_blank(c)) {
            if (in_word) {
                words.push_back(word);
                word.clear();
                in_word = false;
            }
            continue;
        }
        const bool was_in_word = in_word;
        in_word = true;
        if (c == '\\') {
            if (++i == command.size()) {
                refuse(command, "ends in a backslash with nothing after it");
            }
            if (command[i] == '\n') {
                in_word = was_in_word; // a line continuation, not a character
            } else {
                word += command[i];
            }
        } else if (c == '\'') {
            const std::size_t close = command.find('\'', i + 1);
            if (close == std::string::npos) {
                refuse(command, "has a ' that is never closed");
            }
            word.append(command, i + 1, close - i - 1);
            i = close;
        } else if (c == '"') {
            for (++i;; ++i) {
                if (i == command.size()) {
                    refuse(command, "has a \" that is never closed");
                }
                if (command[i] == '"') {
                    break;
                }
                if (command[i] == '\\' && i + 1 < command.size() && command[i + 1] == '\n') {
                    ++i; // a line continuation
                    continue;
                }
                if (command[i] == '\\' && i + 1 < command.size() &&
                    escapes_in_double_quotes(command[i + 1])) {
                    ++i;
                }
                word += command[i];
            }
        } else {
            word += c;
        }
    }
    if (in_word) {
        words.push_back(word);
    }
    if (words.empty()) {
        throw UsageError("--engine-command needs a program to run, got '" + command + "'");
    }
    return words;
}

} // namespace impulse::harness::cli
