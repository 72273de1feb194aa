// `impulse bless [SCENE...]`: write goldens. scripts/regen-goldens calls this.
#include "cli.h"
#include "gate.h"
#include "input_error.h"

#include <cstdlib>
#include <filesystem>
#include <ostream>

namespace impulse::harness::cli {

namespace {

constexpr const char* bless_help = R"(usage: impulse bless [SCENE...] [--root DIR] [--prune]

Runs scenes (every canonical scene when none is named) and writes their goldens
to ROOT/goldens/NAME.json: atomically (temporary file, then rename), and only
when the bytes change, so blessing the same physics twice changes nothing. A
scene that breaks its own declared expectations is not blessed. Prints what was
new, changed (and what moved, by how much), unchanged and removed.

  --root DIR   where harness/scenes/ and goldens/ are (default: .)
  --prune      delete goldens whose scene no longer exists

Refuses to run in CI mode (CI set to anything but empty, 0 or false): CI never
writes goldens. Exit: 0 done, 1 a scene was refused, 2 bad input.
)";

} // namespace

int bless_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(args, {"--root"}, {"--help", "--prune"});
    if (a.has_flag("--help")) {
        out << bless_help;
        return exit_ok;
    }
    if (ci_mode()) {
        err << "impulse bless: refusing to write goldens in CI mode (CI=" << std::getenv("CI")
            << "); bless on a developer machine and commit the goldens\n";
        return exit_bad_input;
    }
    GateRoot root;
    root.root = a.option("--root").value_or(".");
    std::vector<std::string> paths = scenes_named(root, a.positional);

    int created = 0, changed = 0, unchanged = 0, refused = 0, removed = 0, broken = 0;
    for (const std::string& path : paths) {
        try {
            const Blessing b = bless_scene(root, path);
            switch (b.outcome) {
            case Blessing::Outcome::created:
                ++created;
                out << "  new        " << b.name << " -> " << printable_path(b.golden_file) << "\n";
                break;
            case Blessing::Outcome::changed:
                ++changed;
                out << "  changed    " << b.name << " -> " << printable_path(b.golden_file) << "\n"
                    << b.summary;
                break;
            case Blessing::Outcome::unchanged:
                ++unchanged;
                out << "  unchanged  " << b.name << "\n";
                break;
            case Blessing::Outcome::refused:
                ++refused;
                out << "  REFUSED    " << b.name << ": " << b.summary;
                break;
            }
        } catch (const InputError& e) {
            ++broken;
            err << e.what() << "\n";
        }
    }
    for (const std::string& golden : unreferenced_goldens(root)) {
        if (a.has_flag("--prune")) {
            std::filesystem::remove(golden);
            ++removed;
            out << "  removed    " << printable_path(golden) << "\n";
        } else {
            out << "  unreferenced " << printable_path(golden)
                << " (no scene of that name; --prune deletes it)\n";
        }
    }
    out << "goldens: " << created << " new, " << changed << " changed, " << unchanged
        << " unchanged, " << removed << " removed";
    if (refused > 0) {
        out << ", " << refused << " refused";
    }
    if (broken > 0) {
        out << ", " << broken << " broken scene" << (broken == 1 ? "" : "s");
    }
    out << "\n";
    return broken > 0 ? exit_bad_input : refused > 0 ? exit_failed : exit_ok;
}

} // namespace impulse::harness::cli
