#include "strict_json.h"

#include "input_error.h"

#include <algorithm>
#include <optional>
#include <set>
#include <vector>

namespace impulse::harness {

namespace {

// A file committed in the middle of a merge must say so, not "invalid JSON".
void reject_merge_conflict_markers(const std::string& text, const std::string& file) {
    std::size_t line = 1;
    std::size_t start = 0;
    while (start <= text.size()) {
        for (const char* marker : {"<<<<<<<", "=======", ">>>>>>>"}) {
            if (text.compare(start, 7, marker) == 0) {
                throw InputError(file, "",
                                 "has a merge-conflict marker at line " + std::to_string(line) +
                                     "; resolve the conflict or regenerate the file");
            }
        }
        const std::size_t end = text.find('\n', start);
        if (end == std::string::npos) {
            break;
        }
        start = end + 1;
        ++line;
    }
}

// Counts brackets outside strings, so a pathological file ("[[[[...") is
// refused instead of exhausting the stack.
void reject_deep_nesting(const std::string& text, const std::string& file) {
    int depth = 0;
    JsonStringScanner strings;
    for (const char c : text) {
        if (strings.consumes(c)) {
            continue;
        }
        if (c == '[' || c == '{') {
            if (++depth > max_json_nesting) {
                throw InputError(file, "",
                                 "is nested too deeply: more than " +
                                     std::to_string(max_json_nesting) +
                                     " levels of arrays and objects");
            }
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

bool is_number_char(char c) {
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}

// nlohmann's message, e.g. "[json.exception.parse_error.101] parse error at
// line 1, column 10: syntax error while parsing value - invalid literal; last
// read: '"a": tru}'", cut to "line 1, column 10: invalid literal while parsing
// value". The "last read" excerpt is dropped: it repeats raw file bytes, which
// may be control characters or broken UTF-8.
std::string shorten_parse_error(std::string message) {
    const std::size_t tag_end = message.find("] ");
    if (message.rfind("[json.exception.", 0) == 0 && tag_end != std::string::npos) {
        message.erase(0, tag_end + 2);
    }
    if (message.rfind("parse error at ", 0) == 0) {
        message.erase(0, std::string("parse error at ").size());
    }
    const std::string last_read = "; last read: '";
    const std::size_t excerpt = message.find(last_read);
    if (excerpt != std::string::npos) {
        const std::size_t expected = message.rfind("'; expected ");
        const std::size_t cut_end =
            expected != std::string::npos && expected >= excerpt + last_read.size()
                ? expected + 1
                : message.size();
        message.erase(excerpt, cut_end - excerpt);
    }
    // "syntax error while parsing X - REASON" reads better as "REASON while parsing X".
    const std::string syntax = "syntax error while parsing ";
    const std::size_t where = message.find(syntax);
    if (where != std::string::npos) {
        const std::size_t dash = message.find(" - ", where);
        if (dash != std::string::npos) {
            const std::size_t reason_end = std::min(message.find("; ", dash), message.size());
            const std::string what =
                message.substr(where + syntax.size(), dash - where - syntax.size());
            const std::string reason = message.substr(dash + 3, reason_end - dash - 3);
            message.replace(where, reason_end - where, reason + " while parsing " + what);
        }
    }
    for (char& c : message) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte >= 0x7f) {
            c = '?';
        }
    }
    return message;
}

// Follows the parser's events to know the JSON path of every key, so that a
// repeated key is reported where it is. Only the first repeat is kept: it is
// the first in the document.
class DuplicateKeyFinder {
  public:
    template <class Json> bool on_event(nlohmann::json::parse_event_t event, const Json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        switch (event) {
        case Event::object_start:
            open_.push_back({path_of_next_value(), true, {}, {}, 0});
            break;
        case Event::array_start:
            open_.push_back({path_of_next_value(), false, {}, {}, 0});
            break;
        case Event::key: {
            Container& object = open_.back();
            object.key = parsed.template get<std::string>(); // a key event always carries a string
            if (!object.keys.insert(object.key).second && !first_duplicate_) {
                first_duplicate_ = json_member_path(object.path, object.key);
            }
            break;
        }
        case Event::object_end:
        case Event::array_end:
            open_.pop_back();
            value_done();
            break;
        case Event::value:
            value_done();
            break;
        }
        return true;
    }

    const std::optional<std::string>& first_duplicate() const { return first_duplicate_; }

    // Where the parser was about to read a value: the JSON path a number too
    // large for a double, or a NaN or Infinity token, stands at.
    std::string path_of_next_value() const {
        if (open_.empty()) {
            return "";
        }
        const Container& parent = open_.back();
        return parent.is_object ? json_member_path(parent.path, parent.key)
                                : json_element_path(parent.path, parent.index);
    }

  private:
    struct Container {
        std::string path;
        bool is_object;
        std::set<std::string> keys;
        std::string key;   // objects: the key whose value comes next
        std::size_t index; // arrays: the index of the value that comes next
    };

    void value_done() {
        if (!open_.empty() && !open_.back().is_object) {
            ++open_.back().index;
        }
    }

    std::vector<Container> open_;
    std::optional<std::string> first_duplicate_;
};

// Levenshtein distance, for "did you mean" on a mistyped key.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) {
        row[j] = j;
    }
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
            row[j] = std::min({above + 1, row[j - 1] + 1, substitution});
            diagonal = above;
        }
    }
    return row[b.size()];
}

bool is_plain_key_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

} // namespace

std::string json_member_path(const std::string& parent, const std::string& key) {
    const bool plain = !key.empty() && std::all_of(key.begin(), key.end(), is_plain_key_char);
    if (!plain) {
        return parent + "[" + nlohmann::json(key).dump() + "]";
    }
    return parent.empty() ? key : parent + "." + key;
}

std::string json_element_path(const std::string& parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

std::string closest_known_key(const std::string& key, const std::vector<std::string>& known) {
    std::string closest;
    std::size_t best = 3;
    for (const std::string& candidate : known) {
        const std::size_t distance = edit_distance(key, candidate);
        if (distance < best && 2 * distance < key.size()) {
            best = distance;
            closest = candidate;
        }
    }
    return closest;
}

void check_json_text(const std::string& text, const std::string& file) {
    reject_merge_conflict_markers(text, file);
    reject_deep_nesting(text, file);
}

InputError json_syntax_error(const nlohmann::json::exception& error, const std::string& file,
                             const std::string& path_of_next_value) {
    // parse_error for syntax, out_of_range for a number too large for a double
    // (nlohmann gives no line for that one). Both name the JSON path when the
    // parser stopped where a value belongs (1e999, NaN, Infinity, a bad
    // literal): a golden is megabytes, and the path says which number it is.
    const std::string reason = shorten_parse_error(error.what());
    const bool at_value = dynamic_cast<const nlohmann::json::out_of_range*>(&error) != nullptr ||
                          reason.find("while parsing value") != std::string::npos;
    return InputError(file, at_value ? path_of_next_value : "", "not valid JSON: " + reason);
}

template <class Json> Json parse_strict_json(const std::string& text, const std::string& file) {
    check_json_text(text, file);
    DuplicateKeyFinder finder;
    Json document;
    try {
        document =
            Json::parse(text, [&finder](int, nlohmann::json::parse_event_t event, Json& parsed) {
                return finder.on_event(event, parsed);
            });
    } catch (const nlohmann::json::exception& error) {
        throw json_syntax_error(error, file, finder.path_of_next_value());
    }
    if (finder.first_duplicate()) {
        throw InputError(file, *finder.first_duplicate(),
                         "appears more than once in the same object; keys must be unique");
    }
    return document;
}

template nlohmann::json parse_strict_json<nlohmann::json>(const std::string&, const std::string&);
template nlohmann::ordered_json parse_strict_json<nlohmann::ordered_json>(const std::string&,
                                                                          const std::string&);

// The ordinals, counting every number token in document order, of the tokens
// spelled exactly "-0": the parser reports numbers in that same order, and
// only the text keeps the sign of an integer zero.
std::vector<std::size_t> minus_zero_integers(const std::string& text) {
    std::vector<std::size_t> found;
    std::size_t ordinal = 0;
    JsonStringScanner strings;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (strings.consumes(c)) {
            continue;
        }
        if (c == '-' || (c >= '0' && c <= '9')) {
            std::size_t end = i;
            while (end < text.size() && is_number_char(text[end])) {
                ++end;
            }
            if (end - i == 2 && text.compare(i, 2, "-0") == 0) {
                found.push_back(ordinal);
            }
            ++ordinal;
            i = end - 1;
        }
    }
    return found;
}

} // namespace impulse::harness
