// JSON text with exact doubles (exact_json.h).
#include "exact_json.h"

#include "number_format.h"

#include <cmath>
#include <cstddef>

namespace impulse::harness {

namespace {

using Json = nlohmann::ordered_json;

std::string scalar_text(const Json& value) {
    if (value.is_number_float()) {
        const double v = value.get<double>();
        return std::isfinite(v) ? format_double(v) : "null";
    }
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void write(const Json& value, std::size_t depth, std::string& out) {
    const bool object = value.is_object();
    if (!(object || value.is_array())) {
        out += scalar_text(value);
        return;
    }
    if (value.empty()) {
        out += object ? "{}" : "[]";
        return;
    }
    const std::string inner(2 * (depth + 1), ' ');
    out += object ? "{\n" : "[\n";
    bool first = true;
    for (auto it = value.begin(); it != value.end(); ++it) {
        out += (first ? "" : ",\n") + inner;
        first = false;
        if (object) {
            out += scalar_text(Json(it.key())) + ": ";
        }
        write(*it, depth + 1, out);
    }
    out += "\n" + std::string(2 * depth, ' ') + (object ? "}" : "]");
}

} // namespace

std::string exact_json_text(const Json& document) {
    std::string out;
    write(document, 0, out);
    return out + "\n";
}

} // namespace impulse::harness
