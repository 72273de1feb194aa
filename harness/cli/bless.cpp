// `impulse bless [SCENE...]`: write goldens. scripts/regen-goldens calls this.
#include "cli.h"
#include "gate.h"
#include "input_error.h"
#include "progress.h"

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
  --quiet      no progress bar (drawn on standard error only when that is a
               terminal, after about a second of work)

Refuses to run in CI mode (CI set to anything but empty, 0 or false): CI never
writes goldens. Exit: 0 done, 1 a scene was refused, 2 bad input or a golden
that could not be written.
)";

// One line per golden (and what moved, for a changed one), flushed so the
// progress bar can be drawn after it.
void report(const Blessing& b, std::ostream& out) {
    switch (b.outcome) {
    case Blessing::Outcome::created:
        out << "  new        " << b.name << " -> " << printable_path(b.golden_file) << "\n";
        break;
    case Blessing::Outcome::changed:
        out << "  changed    " << b.name << " -> " << printable_path(b.golden_file) << "\n"
            << b.summary;
        break;
    case Blessing::Outcome::unchanged:
        out << "  unchanged  " << b.name << "\n";
        break;
    case Blessing::Outcome::refused:
        out << "  REFUSED    " << b.name << ": " << b.summary;
        break;
    case Blessing::Outcome::unwritten:
        out << "  NOT WRITTEN " << b.name << ": could not write the golden\n";
        break;
    }
    out.flush();
}

} // namespace

int bless_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(args, {"--root"}, {"--help", "--prune", "--quiet"});
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
    int unwritten = 0; // a scene that ran fine but whose golden could not be written
    {                  // the bar lives while scenes run, and is erased before the summary
        Progress progress("bless", progress_wanted(a.has_flag("--quiet")));
        progress.set_total(paths.size(), "scenes");
        for (const std::string& path : paths) {
            progress.set_item(std::filesystem::path(path).stem().string());
            try {
                const Blessing b = bless_scene(root, path);
                progress.advance();
                progress.without_bar([&] { report(b, out); });
                switch (b.outcome) {
                case Blessing::Outcome::created:
                    ++created;
                    break;
                case Blessing::Outcome::changed:
                    ++changed;
                    break;
                case Blessing::Outcome::unchanged:
                    ++unchanged;
                    break;
                case Blessing::Outcome::refused:
                    ++refused;
                    break;
                case Blessing::Outcome::unwritten:
                    ++unwritten;
                    progress.without_bar([&] { err << b.summary << "\n" << std::flush; });
                    break;
                }
            } catch (const InputError& e) {
                ++broken;
                progress.advance();
                progress.without_bar([&] { err << e.what() << "\n" << std::flush; });
            }
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
    if (unwritten > 0) {
        out << ", " << unwritten << " could not write the golden";
    }
    out << "\n";
    return broken > 0 || unwritten > 0 ? exit_bad_input : refused > 0 ? exit_failed : exit_ok;
}

} // namespace impulse::harness::cli
