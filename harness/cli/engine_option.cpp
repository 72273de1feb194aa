#include "engine_option.h"

#include "command_words.h"

#include <algorithm>
#include <vector>

namespace impulse::harness::cli {

namespace {

// The name rule of scenes and bodies: an engine's name becomes a goldens
// folder and a column of tables.
bool is_engine_name(const std::string& name) {
    const auto letter_or_digit = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    };
    return !name.empty() && name.size() <= 64 && letter_or_digit(name.front()) &&
           std::all_of(name.begin(), name.end(), [&](char c) {
               return letter_or_digit(c) || c == '.' || c == '_' || c == '-';
           });
}

// An engine given on the command line instead of in impulse.json: a quick
// try before a project file exists.
EngineSpec command_engine(const std::optional<std::string>& name, const std::string& command) {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::external;
    spec.name = name.value_or("external");
    if (spec.name == "impulse" || spec.name == "box2d" || spec.name == "chipmunk" ||
        !is_engine_name(spec.name)) {
        throw UsageError("--engine with --engine-command names the external engine: 1 to 64 "
                         "letters, digits, '.', '_' or '-', not impulse, box2d or chipmunk, got '" +
                         spec.name + "'");
    }
    spec.command = command_words(command);
    spec.working_directory = ".";
    spec.origin = "--engine-command";
    return spec;
}

} // namespace

EngineSpec chosen_engine(const Project& project, const Arguments& arguments) {
    const std::optional<std::string> name = arguments.option(engine_option);
    const std::optional<std::string> command = arguments.option(engine_command_option);
    EngineSpec engine = command ? command_engine(name, *command)
                        : name  ? engine_named(project, *name, true)
                                : project.engines.front();
    require_startable(engine);
    return engine;
}

} // namespace impulse::harness::cli
