#include "golden_settings.h"

#include "text.h"

#include <algorithm>

namespace impulse::harness {

namespace {

using SolverBlock = std::vector<std::pair<std::string, std::string>>;

// "impulse 0.1.0" -> "impulse"; a string without a space is all name.
std::string engine_name(const std::string& engine) {
    return engine.substr(0, engine.find(' '));
}

const std::string* find_key(const SolverBlock& block, const std::string& key) {
    const auto it = std::find_if(block.begin(), block.end(),
                                 [&](const auto& entry) { return entry.first == key; });
    return it == block.end() ? nullptr : &it->second;
}

} // namespace

SettingsComparison compare_settings(const Trajectory& gold, const Trajectory& value) {
    SettingsComparison result;
    if (engine_name(gold.engine) != engine_name(value.engine)) {
        result.differences.push_back("engine: golden " + double_quoted(gold.engine) + ", new " +
                                     double_quoted(value.engine) +
                                     ": the golden was recorded by another engine");
    } else if (gold.engine != value.engine) {
        result.notes.push_back("engine: the golden was blessed with " + double_quoted(gold.engine) +
                               ", this run is " + double_quoted(value.engine) +
                               "; its numbers and solver settings are compared as always, so "
                               "the version alone does not fail the gate");
    }
    // The golden's keys in its order, then the keys only the new run has.
    for (const auto& [key, gold_text] : gold.solver) {
        const std::string* new_text = find_key(value.solver, key);
        if (new_text == nullptr) {
            result.differences.push_back("solver." + key + ": golden " + gold_text +
                                         ", new run has no such key");
        } else if (*new_text != gold_text) {
            result.differences.push_back("solver." + key + ": golden " + gold_text + ", new " +
                                         *new_text);
        }
    }
    for (const auto& [key, new_text] : value.solver) {
        if (find_key(gold.solver, key) == nullptr) {
            result.differences.push_back("solver." + key + ": golden has no such key, new " +
                                         new_text);
        }
    }
    return result;
}

} // namespace impulse::harness
