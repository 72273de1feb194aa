#include "reference_option.h"

#include "cli.h"

#include <algorithm>
#include <ostream>

namespace impulse::harness::cli {

std::optional<ReferenceChoice> chosen_references(const std::optional<std::string>& with,
                                                 const std::string& box2d_off,
                                                 const std::string& verb, std::ostream& err) {
    ReferenceChoice choice;
    const std::vector<ReferenceEngine> all = reference_engines();
    if (!with) {
        for (const ReferenceEngine& r : all) {
            if (r.name == "box2d-2.4" && !box2d_off.empty()) {
                choice.notes.push_back(r.name + " left out: " + box2d_off);
            } else {
                (r.available ? choice.used : choice.skipped).push_back(r);
            }
        }
        return choice;
    }
    if (*with == "none") {
        return choice;
    }
    for (const std::string& name : comma_list(*with)) {
        const auto found = std::find_if(all.begin(), all.end(),
                                        [&](const ReferenceEngine& r) { return r.name == name; });
        if (found == all.end()) {
            std::string names;
            for (const std::string& known : reference_names()) {
                names += (names.empty() ? "" : ", ") + known;
            }
            throw UsageError(std::string(with_option) + ": no reference engine is named '" + name +
                             "'; the references are " + names + " (or none)");
        }
        if (!found->available) {
            err << "impulse " << verb << ": " << unavailable_sentence(*found) << "\n";
            return std::nullopt;
        }
        if (std::none_of(choice.used.begin(), choice.used.end(),
                         [&](const ReferenceEngine& r) { return r.name == name; })) {
            choice.used.push_back(*found);
        }
    }
    return choice;
}

} // namespace impulse::harness::cli
