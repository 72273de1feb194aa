#include "trajectory_stream.h"

#include "input_error.h"
#include "strict_json.h"

#include <cmath>
#include <set>

namespace impulse::harness::trajectory_fields {

namespace {

// One value built from parser events, as nlohmann's own tree parser builds it:
// for the few small members of a trajectory (its names, solver block, columns)
// and for one event at a time.
class TreeBuilder {
  public:
    void begin(Json* target) {
        target_ = target;
        open_.clear();
    }
    void value(Json value) { place(std::move(value)); }
    void open(Json container) { open_.push_back(place(std::move(container))); }
    void key(const std::string& key) { key_ = key; }
    void close() { open_.pop_back(); }

  private:
    // Only the innermost open container ever grows, so the pointers held to
    // the ones around it stay valid.
    Json* place(Json value) {
        if (open_.empty()) {
            *target_ = std::move(value);
            return target_;
        }
        Json& parent = *open_.back();
        if (parent.is_array()) {
            parent.push_back(std::move(value));
            return &parent.back();
        }
        Json& slot = parent[key_];
        slot = std::move(value);
        return &slot;
    }

    Json* target_ = nullptr;
    std::vector<Json*> open_;
    std::string key_;
};

// What an open array or object is to the reader.
enum class Kind {
    top,    // the top-level object
    frames, // its "frames" array
    row,    // one frame
    events, // its "events" array
    event,  // one event, built as a tree, checked when it closes
    tree,   // inside a value built as a tree
    skip,   // a value whose contents no check looks at
};

struct Level {
    Kind kind;
    bool is_object;
    std::string key;            // objects: the key whose value comes next
    std::size_t index = 0;      // arrays: the index of the value that comes next
    std::set<std::string> keys; // objects: the keys so far, for repeats
};

// The SAX handler (nlohmann's interface). It follows the JSON path of every
// value, as parse_strict_json does, to name where a syntax error or a
// repeated key is.
class TrajectoryStream {
  public:
    TrajectoryStream(const std::string& file, std::size_t frames_hint,
                     std::vector<std::size_t> minus_zeros)
        : file_(file), minus_zeros_(std::move(minus_zeros)) {
        document_.frames.reserve(frames_hint);
    }

    bool null() { return scalar(Json(nullptr)); }
    bool boolean(bool value) { return scalar(Json(value)); }
    bool number_integer(std::int64_t value) {
        if (is_minus_zero()) { // the token -0: the format keeps the sign of zero
            return number(-0.0);
        }
        return in(Kind::row) ? row_integer(value) : scalar(Json(value));
    }
    bool number_unsigned(std::uint64_t value) {
        ++number_ordinal_;
        return in(Kind::row) ? row_integer(value) : scalar(Json(value));
    }
    bool number_float(double value, const std::string&) {
        ++number_ordinal_;
        return number(value);
    }
    bool number(double value) {
        if (!in(Kind::row)) {
            return scalar(Json(value));
        }
        if (!std::isfinite(value)) {
            bad_value("must be a finite number");
        }
        return row_number(value);
    }
    bool string(std::string& value) { return scalar(Json(std::move(value))); }
    bool binary(Json::binary_t&) { return true; } // never produced by the JSON parser
    bool start_object(std::size_t) { return open(true); }
    bool start_array(std::size_t) { return open(false); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(std::string& key) {
        Level& level = levels_.back();
        if (!level.keys.insert(key).second && !first_duplicate_) {
            first_duplicate_ = json_member_path(container_path(levels_.size() - 1), key);
        }
        if (level.kind == Kind::event || level.kind == Kind::tree) {
            tree_.key(key);
        }
        level.key = std::move(key);
        return true;
    }

    bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception& error) {
        throw json_syntax_error(error, file_, path_of_next_value());
    }

    StreamedDocument finish() {
        if (first_duplicate_) {
            throw InputError(file_, *first_duplicate_,
                             "appears more than once in the same object; keys must be unique");
        }
        return std::move(document_);
    }

  private:
    // Counts one number token and says whether it was spelled -0.
    bool is_minus_zero() {
        const bool minus = next_minus_zero_ < minus_zeros_.size() &&
                           minus_zeros_[next_minus_zero_] == number_ordinal_;
        next_minus_zero_ += minus ? 1 : 0;
        ++number_ordinal_;
        return minus;
    }

    bool in(Kind kind) const { return !levels_.empty() && levels_.back().kind == kind; }

    // The path of the container levels_[depth], built only when a message needs it.
    std::string container_path(std::size_t depth) const {
        std::string path;
        for (std::size_t i = 0; i < depth; ++i) {
            const Level& level = levels_[i];
            path = level.is_object ? json_member_path(path, level.key)
                                   : json_element_path(path, level.index);
        }
        return path;
    }

    std::string path_of_next_value() const { return container_path(levels_.size()); }

    void value_done() {
        if (!levels_.empty() && !levels_.back().is_object) {
            ++levels_.back().index;
        }
    }

    // ------------------------------------------------------------ frames

    // The path is built only for an integer a double cannot hold: golden
    // frames are full of 0.
    template <typename Integer> bool row_integer(Integer value) {
        const double as_double = static_cast<double>(value);
        if (std::fabs(as_double) < 9007199254740992.0) { // 2^53: every integer below is exact
            return row_number(as_double);
        }
        try {
            return row_number(exact_integer(value, path_of_next_value()));
        } catch (const FieldError& invalid) {
            note(document_.first_bad_value, invalid);
            return row_number(0.0);
        }
    }

    bool row_number(double value) {
        document_.frames.back().push_back(value);
        value_done();
        return true;
    }

    void bad_value(const std::string& message) {
        note(document_.first_bad_value, FieldError{path_of_next_value(), message});
    }

    void note(std::optional<FrameProblem>& problem, const FieldError& invalid) const {
        if (!problem) {
            problem = FrameProblem{document_.frames.size() - 1, invalid};
        }
    }

    // A new element of "frames": its row, sized like the last one.
    void new_row() {
        const std::size_t columns = document_.frames.empty() ? 0 : row_size_;
        document_.frames.emplace_back();
        document_.frames.back().reserve(columns);
    }

    // ------------------------------------------------------------ values

    bool scalar(Json value) {
        if (levels_.empty()) {
            document_.top = std::move(value);
            return true;
        }
        switch (levels_.back().kind) {
        case Kind::top:
            tree_.begin(&document_.top[levels_.back().key]);
            tree_.value(std::move(value));
            break;
        case Kind::frames:
            new_row();
            note(document_.first_frame_not_array,
                 FieldError{path_of_next_value(), "must be an array, " + got(value)});
            break;
        case Kind::row:
            bad_value("must be a number, " + got(value));
            return row_number(0.0);
        case Kind::events:
            if (!document_.first_bad_event) {
                tree_.begin(&event_);
                tree_.value(std::move(value));
                check_event();
            }
            break;
        case Kind::event:
        case Kind::tree:
            tree_.value(std::move(value));
            break;
        case Kind::skip:
            break;
        }
        value_done();
        return true;
    }

    // What an array or object that starts here is.
    Kind kind_of_new(bool is_object) {
        if (levels_.empty()) {
            return is_object ? Kind::top : Kind::skip;
        }
        const Level& parent = levels_.back();
        switch (parent.kind) {
        case Kind::top:
            if (!is_object && (parent.key == "frames" || parent.key == "events")) {
                const bool frames = parent.key == "frames";
                (frames ? document_.frames_streamed : document_.events_streamed) = true;
                document_.top[parent.key] = Json::array();
                return frames ? Kind::frames : Kind::events;
            }
            tree_.begin(&document_.top[parent.key]);
            return Kind::tree;
        case Kind::frames:
            new_row();
            if (!is_object) {
                return Kind::row;
            }
            note(document_.first_frame_not_array,
                 FieldError{path_of_next_value(), "must be an array, got an object"});
            return Kind::skip;
        case Kind::row:
            bad_value(std::string("must be a number, got an ") + (is_object ? "object" : "array"));
            document_.frames.back().push_back(0.0);
            return Kind::skip;
        case Kind::events:
            if (document_.first_bad_event) {
                return Kind::skip;
            }
            tree_.begin(&event_);
            return Kind::event;
        case Kind::event:
        case Kind::tree:
            return Kind::tree;
        case Kind::skip:
            return Kind::skip;
        }
        return Kind::skip;
    }

    bool open(bool is_object) {
        const Kind kind = kind_of_new(is_object);
        if (kind == Kind::top) {
            document_.top = Json::object();
        } else if (kind == Kind::event || kind == Kind::tree) {
            tree_.open(is_object ? Json::object() : Json::array());
        }
        levels_.push_back(Level{kind, is_object, {}, 0, {}});
        return true;
    }

    bool close() {
        const Kind kind = levels_.back().kind;
        if (kind == Kind::row) {
            row_size_ = document_.frames.back().size();
        }
        levels_.pop_back();
        if (kind == Kind::event || kind == Kind::tree) {
            tree_.close();
        }
        if (kind == Kind::event) {
            check_event();
        }
        value_done();
        return true;
    }

    // An event is checked as soon as it is read and only its fields are kept.
    void check_event() {
        const std::string path = path_of_next_value();
        try {
            document_.events.push_back(read_event(event_, path));
        } catch (const FieldError& invalid) {
            document_.first_bad_event = invalid;
        }
        event_ = Json();
    }

    std::string file_;
    std::vector<std::size_t> minus_zeros_; // minus_zero_integers() of the text
    std::size_t next_minus_zero_ = 0;
    std::size_t number_ordinal_ = 0;
    StreamedDocument document_;
    std::vector<Level> levels_;
    TreeBuilder tree_;
    Json event_;
    std::size_t row_size_ = 0;
    std::optional<std::string> first_duplicate_;
};

} // namespace

StreamedDocument stream_trajectory(const std::string& text, const std::string& file,
                                   std::size_t frames_hint) {
    TrajectoryStream stream(file, frames_hint, minus_zero_integers(text));
    Json::sax_parse(text, &stream);
    return stream.finish();
}

} // namespace impulse::harness::trajectory_fields
