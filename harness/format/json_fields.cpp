// The typed JSON reader shared by scenes and trajectories (json_fields.h).
#include "json_fields.h"

#include "strict_json.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace impulse::harness::json_fields {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw FieldError{path, message};
}

std::string list_of(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) {
        out += (out.empty() ? "" : ", ") + name;
    }
    return out;
}

template <class Json> std::string shown(const Json& value) {
    if (value.is_object()) {
        return "an object";
    }
    if (value.is_array()) {
        return "an array";
    }
    std::string text = value.dump();
    constexpr std::size_t longest = 40;
    if (text.size() > longest) {
        std::size_t cut = longest;
        // never cut a UTF-8 sequence in half: the message must stay valid text
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) {
            --cut;
        }
        text = text.substr(0, cut) + "...";
    }
    return text;
}

template <class Json> std::string got(const Json& value) {
    return "got " + shown(value);
}

template <class Json> void require_object(const Json& value, const std::string& path) {
    if (!value.is_object()) {
        fail(path, "must be an object, " + got(value));
    }
}

template <class Json> void require_array(const Json& value, const std::string& path) {
    if (!value.is_array()) {
        fail(path, "must be an array, " + got(value));
    }
}

template <class Json>
const Json& require_key(const Json& object, const std::string& path, const std::string& key) {
    const auto found = object.find(key);
    if (found == object.end()) {
        fail(json_member_path(path, key), "is required but missing");
    }
    return *found;
}

template <class Json>
void reject_unknown_keys(const Json& object, const std::string& path,
                         const std::vector<std::string>& allowed) {
    for (const auto& item : object.items()) {
        if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) {
            continue;
        }
        const std::string closest = closest_known_key(item.key(), allowed);
        fail(json_member_path(path, item.key()),
             (closest.empty() ? "unknown key" : "unknown key (did you mean " + closest + "?)") +
                 "; the keys allowed here are " + list_of(allowed));
    }
}

template <class Json> std::string read_string(const Json& value, const std::string& path) {
    if (!value.is_string()) {
        fail(path, "must be a string, " + got(value));
    }
    return value.template get<std::string>();
}

template <class Json> bool read_bool(const Json& value, const std::string& path) {
    if (!value.is_boolean()) {
        fail(path, "must be true or false, " + got(value));
    }
    return value.template get<bool>();
}

template <class Json> double read_number(const Json& value, const std::string& path) {
    if (!value.is_number()) {
        fail(path, "must be a number, " + got(value));
    }
    const double number = value.template get<double>();
    if (!std::isfinite(number)) {
        fail(path, "must be a finite number");
    }
    return number;
}

#define IMPULSE_JSON_FIELDS_FOR(Json)                                                              \
    template std::string shown(const Json&);                                                       \
    template std::string got(const Json&);                                                         \
    template void require_object(const Json&, const std::string&);                                 \
    template void require_array(const Json&, const std::string&);                                  \
    template const Json& require_key(const Json&, const std::string&, const std::string&);         \
    template void reject_unknown_keys(const Json&, const std::string&,                             \
                                      const std::vector<std::string>&);                            \
    template std::string read_string(const Json&, const std::string&);                             \
    template bool read_bool(const Json&, const std::string&);                                      \
    template double read_number(const Json&, const std::string&);

IMPULSE_JSON_FIELDS_FOR(nlohmann::json)
IMPULSE_JSON_FIELDS_FOR(nlohmann::ordered_json)

#undef IMPULSE_JSON_FIELDS_FOR

} // namespace impulse::harness::json_fields
