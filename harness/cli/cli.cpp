#include "cli.h"

#include "input_error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace impulse::harness::cli {

namespace {

constexpr const char* usage =
    R"(impulse: a deterministic regression harness for 2D rigid-body collision response

usage: impulse <verb> [options]

verbs:
  run SCENE          simulate a scene and write its trajectory
  check [SCENE...]   the gate: simulate scenes and diff them against their goldens
  bless [SCENE...]   write goldens
  regen [SCENE...]   regenerate the goldens of the project found from here
                     (the command hints name; bless by another name)
  init [DIR]         start a project: DIR/impulse.json and one example scene
  diff A B           diff two trajectory files with the rules of check
  box2d [SCENE...]   run scenes in Box2D with friction off and compare observables
  compare [SCENE...] [--with box2d-2.4,box2d-3,chipmunk,rapier]
                     the same observables in every reference engine on this
                     machine, one column each, beside the exact answer
  render SCENE|TRAJECTORY
                     an SVG picture of the motion
  sweep SCENE        the speed/accuracy trade: error against cost over a grid of
                     solver settings, impulse and Box2D
  stress             numerical stability at the extremes: a matrix of built-in
                     scenes, every invariant's worst value against its bound
  conform [--engine ENGINE]
                     the conformance suite: the shipped scenes' exact answers and
                     conservation laws scored in ENGINE (default: the project's
                     first engine), impulse and Box2D beside it

The project: the first impulse.json found from the current folder upwards
(or in --root DIR) says where the scenes and goldens are and which engines
run them (docs/project-file.md); without one, harness/scenes/ and goldens/
with the impulse engine.

options:
  --help       this text; 'impulse <verb> --help' describes one verb
  --version    the tool's version

exit codes: 0 all held, 1 a comparison or expectation failed, 2 bad input or set-up
)";

} // namespace

bool Arguments::has_flag(const std::string& name) const {
    return std::find(flags.begin(), flags.end(), name) != flags.end();
}

std::optional<std::string> Arguments::option(const std::string& name) const {
    const auto it = options.find(name);
    if (it == options.end()) {
        return std::nullopt;
    }
    return it->second;
}

Arguments parse_arguments(const std::vector<std::string>& args,
                          const std::vector<std::string>& options_with_value,
                          const std::vector<std::string>& known_flags) {
    auto known = [](const std::vector<std::string>& list, const std::string& name) {
        return std::find(list.begin(), list.end(), name) != list.end();
    };
    Arguments parsed;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg.size() < 2 || arg.compare(0, 2, "--") != 0) {
            parsed.positional.push_back(arg);
            continue;
        }
        const std::size_t eq = arg.find('=');
        const std::string name = arg.substr(0, eq);
        if (known(options_with_value, name)) {
            if (eq != std::string::npos) {
                parsed.options[name] = arg.substr(eq + 1);
            } else if (i + 1 < args.size()) {
                parsed.options[name] = args[++i];
            } else {
                throw UsageError(name + " needs a value");
            }
        } else if (known(known_flags, name) && eq == std::string::npos) {
            parsed.flags.push_back(name);
        } else {
            throw UsageError("unknown option '" + arg + "'");
        }
    }
    return parsed;
}

std::vector<std::string> normalise_jobs(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    for (const std::string& a : args) {
        if (a == "-j") {
            out.push_back("--jobs");
        } else if (a.size() > 2 && a.compare(0, 2, "-j") == 0) {
            out.push_back("--jobs");
            out.push_back(a.substr(2));
        } else {
            out.push_back(a);
        }
    }
    return out;
}

int parse_count(const std::string& option, const std::string& text, int low, int high) {
    int value = 0;
    std::istringstream in(text);
    if (!(in >> value) || !in.eof() || value < low || value > high) {
        throw UsageError(option + " must be a whole number from " + std::to_string(low) + " to " +
                         std::to_string(high) + ", got '" + text + "'");
    }
    return value;
}

double positive_seconds(const std::string& option, const std::string& text) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value) || value <= 0.0) {
        throw UsageError(option + " must be a finite number of seconds > 0, got '" + text + "'");
    }
    return value;
}

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    std::ostream& out = std::cout;
    std::ostream& err = std::cerr;
    if (args.empty()) {
        err << usage;
        return exit_bad_input;
    }
    const std::string verb = args.front();
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    try {
        if (verb == "--help" || verb == "-h" || verb == "help") {
            out << usage;
            return exit_ok;
        }
        if (verb == "--version") {
            out << "impulse " << IMPULSE_VERSION << "\n";
            return exit_ok;
        }
        if (verb == "run") {
            return run_verb(rest, out, err);
        }
        if (verb == "check") {
            return check_verb(rest, out, err);
        }
        if (verb == "bless") {
            return bless_verb(rest, out, err);
        }
        if (verb == "diff") {
            return diff_verb(rest, out, err);
        }
        if (verb == "box2d") {
            return box2d_verb(rest, out, err);
        }
        if (verb == "compare") {
            return compare_verb(rest, out, err);
        }
        if (verb == "render") {
            return render_verb(rest, out, err);
        }
        if (verb == "sweep") {
            return sweep_verb(rest, out, err);
        }
        if (verb == "stress") {
            return stress_verb(rest, out, err);
        }
        if (verb == "init") {
            return init_verb(rest, out, err);
        }
        if (verb == "regen") {
            return regen_verb(rest, out, err);
        }
        if (verb == "conform") {
            return conform_verb(rest, out, err);
        }
        err << "impulse: unknown verb '" << verb << "'; see 'impulse --help'\n";
        return exit_bad_input;
    } catch (const InputError& e) {
        err << e.what() << "\n";
        return exit_bad_input;
    } catch (const UsageError& e) {
        err << "impulse " << verb << ": " << e.what() << "; see 'impulse " << verb << " --help'\n";
        return exit_bad_input;
    } catch (const std::exception& e) {
        // Never a crash or a stack trace, even for a failure nobody foresaw.
        err << "impulse " << verb << ": internal error: " << e.what() << "\n";
        return exit_bad_input;
    }
}

std::vector<std::string> comma_list(const std::string& text) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, ',')) {
        parts.push_back(part);
    }
    if (parts.empty() || text.back() == ',') {
        throw UsageError("empty item in list '" + text + "'");
    }
    return parts;
}

} // namespace impulse::harness::cli
