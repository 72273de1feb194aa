// `impulse bless [SCENE...]` and `impulse regen [SCENE...]`: write goldens.
// regen is the verb hints name and scripts/regen-goldens calls; both do the same.
#include "cli.h"
#include "gate.h"
#include "input_error.h"
#include "interruption.h"
#include "progress.h"
#include "project_options.h"
#include "scene.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>
#include <system_error>

namespace impulse::harness::cli {

namespace {

constexpr const char* bless_help =
    R"(usage: impulse bless [SCENE...] [--root DIR] [--engine NAME] [--prune] [--partial]

Runs scenes (every scene of the project when none is named) in the project's
engines and writes their goldens to GOLDENS/NAME.json (GOLDENS/ENGINE/NAME.json
when the project has several engines): atomically (temporary file, then
rename), and only when the bytes change, so blessing the same physics twice
changes nothing. A scene that breaks its own declared expectations is not
blessed; one an engine refuses as unsupported is skipped; a scene file outside
the project's scenes is refused (its golden would be unreferenced). Prints what
was new, changed (and what moved, by how much), unchanged and removed.
'impulse regen' does the same.

  --root DIR      the project's folder: DIR/impulse.json, or without one
                  DIR/harness/scenes/ and DIR/goldens/ (default: the first
                  impulse.json found from the current folder upwards, else .)
  --engine NAME   only the project's engine NAME
  --prune         delete goldens whose scene no longer exists
  --partial       write the other goldens even when a scene refuses, saying
                  which goldens that leaves inconsistent
  --quiet      no progress bar (drawn on standard error only when that is a
               terminal, after about a second of work)

All or nothing: when any scene refuses (it breaks its own expectations, or it
cannot be loaded or run), no golden is written and nothing is pruned; the
others are listed as held back. --partial writes them anyway.

Refuses to run in CI mode (CI set to anything but empty, 0 or false): CI never
writes goldens. Exit: 0 done, 1 a scene was refused, 2 bad input or a golden
that could not be written.
)";

constexpr const char* regen_help =
    R"(usage: impulse regen [SCENE...] [--engine NAME] [--prune] [--partial] [--root DIR]

Regenerates the goldens of the project found from the current folder (the
first impulse.json upwards, as git finds .git; --root DIR names it): runs the
named scenes (every scene of the project when none is named) in the project's
engines and writes their goldens, exactly as 'impulse bless' does, printing
what is new, changed (what moved, by how much), unchanged and removed. SCENE
paths are relative to the current folder. This is the command the gate's hints
name (the project file's "regen"), after an intended physics change.

  --engine NAME   only the project's engine NAME
  --prune         delete goldens whose scene no longer exists
  --partial       write the other goldens even when a scene refuses, saying
                  which goldens that leaves inconsistent
  --root DIR      the project's folder
  --quiet         no progress bar

All or nothing: when any scene refuses (it breaks its own expectations, or it
cannot be loaded or run), no golden is written and nothing is pruned.

Refused in CI mode. Exit: 0 done, 1 a scene was refused (it breaks its own
expectations), 2 bad input or a golden that could not be written.
)";

// One line per golden (and what moved, for a changed one), flushed so the
// progress bar can be drawn after it. `name` carries the engine when there
// are several.
void report(const Blessing& b, const std::string& name, std::ostream& out) {
    switch (b.outcome) {
    case Blessing::Outcome::created:
        out << "  new        " << name << " -> " << printable_path(b.golden_file) << "\n";
        break;
    case Blessing::Outcome::changed:
        out << "  changed    " << name << " -> " << printable_path(b.golden_file) << "\n"
            << b.summary;
        break;
    case Blessing::Outcome::unchanged:
        out << "  unchanged  " << name << "\n";
        break;
    case Blessing::Outcome::refused:
        out << "  REFUSED    " << name << ": " << b.summary;
        break;
    case Blessing::Outcome::unwritten:
        out << "  NOT WRITTEN " << name << ": could not write the golden\n";
        break;
    case Blessing::Outcome::skipped:
        out << "  skipped    " << name << ": " << b.summary << "\n";
        break;
    }
    out.flush();
}

struct BlessCounts {
    int created = 0, changed = 0, unchanged = 0, refused = 0, removed = 0, broken = 0;
    int unwritten = 0; // a scene that ran fine but whose golden could not be written
    int skipped = 0;   // an engine refused the scene's settings

    void add(Blessing::Outcome outcome) {
        switch (outcome) {
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
            break;
        case Blessing::Outcome::skipped:
            ++skipped;
            break;
        }
    }
};

// One scene's prepared blessing, named as the report names it.
struct Prepared {
    std::string name; // ENGINE/NAME when the project has several engines
    Blessing blessing;
};

struct Preparation {
    std::vector<Prepared> ready;
    // Scenes that hold the writing back: those refused (they break their
    // own expectations) and broken ones (not loaded or not run, their
    // sentence printed already), in the order met.
    std::vector<std::string> refusing;
    std::vector<std::string> failing;       // the broken ones among them
    std::vector<std::string> never_blessed; // those among them with no golden yet
    std::vector<std::string> unwritable;    // those whose golden's path cannot be written
};

// Notes a scene that holds the writing back, and whether it has a golden:
// --partial leaves an old golden inconsistent with the others, and a
// missing one missing.
void note_refusing(Preparation& p, const std::string& name, const std::string& golden) {
    p.refusing.push_back(name);
    std::error_code error;
    if (!std::filesystem::exists(golden, error)) {
        p.never_blessed.push_back(name);
    }
}

// Runs every (engine, scene) pair and decides each golden, writing none;
// the progress bar is erased before returning.
Preparation prepare_all(const Project& project, const std::vector<EngineSpec>& engines,
                        const std::vector<std::string>& paths, bool quiet, std::ostream& err) {
    Preparation p;
    Progress progress("bless", progress_wanted(quiet));
    progress.set_total(paths.size() * engines.size(), "scenes");
    const bool several = project.engines.size() > 1;
    for (const EngineSpec& engine : engines) {
        for (const std::string& path : paths) {
            const std::string stem = std::filesystem::path(path).stem().string();
            progress.set_item(stem);
            try {
                Blessing b = prepare_blessing(project, engine, path);
                progress.without_bar([&] {
                    for (const std::string& warning : b.warnings) {
                        err << "warning: " << warning << "\n" << std::flush;
                    }
                });
                const std::string name = several ? engine.name + "/" + b.name : b.name;
                if (b.outcome == Blessing::Outcome::refused) {
                    note_refusing(p, name, b.golden_file);
                }
                p.ready.push_back({name, std::move(b)});
            } catch (const InputError& e) {
                note_refusing(p, several ? engine.name + "/" + stem : stem,
                              golden_path(project, engine, stem));
                p.failing.push_back(p.refusing.back());
                progress.without_bar([&] { err << e.what() << "\n" << std::flush; });
            }
            progress.advance();
        }
    }
    return p;
}

// "a, b and c".
std::string listed(const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    }
    return text;
}

bool among(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

bool would_write(const Blessing& b) {
    return b.outcome == Blessing::Outcome::created || b.outcome == Blessing::Outcome::changed;
}

// "a refuses to be blessed", "b could not be loaded or run (its error above)", or both
// joined: a scene whose engine crashed was not refused by its expectations.
std::string why_held(const Preparation& p) {
    std::vector<std::string> refused;
    for (const std::string& name : p.refusing) {
        if (!among(p.failing, name) && !among(p.unwritable, name)) {
            refused.push_back(name);
        }
    }
    std::string why;
    if (!refused.empty()) {
        why = listed(refused) + (refused.size() == 1 ? " refuses" : " refuse") + " to be blessed";
    }
    if (!p.failing.empty()) {
        why += (why.empty() ? "" : " and ") + listed(p.failing) + " could not be loaded or run (" +
               (p.failing.size() == 1 ? "its error" : "their errors") + " above)";
    }
    if (!p.unwritable.empty()) {
        why += std::string(why.empty() ? "" : " and ") + "the golden of " + listed(p.unwritable) +
               " cannot be written (NOT WRITTEN above)";
    }
    return why;
}

// What --partial left: "--partial: 3 goldens were written, but a was not
// regenerated and still holds the old motion, so the goldens are
// inconsistent until it is fixed and regenerated; b has no golden yet".
std::string partial_note(const Preparation& p, int written) {
    std::vector<std::string> stale;
    for (const std::string& name : p.refusing) {
        if (!among(p.never_blessed, name) && !among(p.unwritable, name)) {
            stale.push_back(name);
        }
    }
    std::string text = "--partial: " + std::to_string(written) + " golden" +
                       (written == 1 ? " was" : "s were") + " written, but ";
    if (!stale.empty()) {
        const bool one = stale.size() == 1;
        text += listed(stale) + (one ? " was" : " were") + " not regenerated and still " +
                (one ? "holds" : "hold") +
                " the old motion, so the goldens are inconsistent until " +
                (one ? "it is" : "they are") + " fixed and regenerated";
    }
    if (!p.never_blessed.empty()) {
        const bool one = p.never_blessed.size() == 1;
        text += std::string(stale.empty() ? "" : "; ") + listed(p.never_blessed) +
                (one ? " has" : " have") + " no golden yet, so check reports " +
                (one ? "it" : "them") + " until " + (one ? "it is" : "they are") +
                " fixed and blessed";
    }
    return text + "\n";
}

// Writes the prepared goldens, or, when a scene refuses and `partial` is
// not given, none of them: a goldens folder half from one engine and half
// from another would pass the gate for the wrong reason.
BlessCounts write_prepared(Preparation& p, bool partial, std::ostream& out, std::ostream& err) {
    // A golden whose path cannot take it (a folder there, a read-only
    // folder) holds the others back as a refusing scene does: found before
    // any is written, so the goldens are never half from the new motion.
    for (Prepared& item : p.ready) {
        if (would_write(item.blessing)) {
            try {
                check_golden_writable(item.blessing);
            } catch (const InputError& e) {
                item.blessing.outcome = Blessing::Outcome::unwritten;
                item.blessing.summary = e.what();
                p.refusing.push_back(item.name);
                p.unwritable.push_back(item.name);
            }
        }
    }
    BlessCounts counts;
    counts.broken = static_cast<int>(p.failing.size());
    const bool hold = !p.refusing.empty() && !partial;
    int held = 0;
    for (Prepared& item : p.ready) {
        Blessing& b = item.blessing;
        if (hold && would_write(b)) {
            ++held;
            out << "  held back  " << item.name << ": would be "
                << (b.outcome == Blessing::Outcome::created ? "new" : "changed") << "\n";
            continue;
        }
        write_blessing(b);
        report(b, item.name, out);
        counts.add(b.outcome);
        if (b.outcome == Blessing::Outcome::unwritten) {
            err << b.summary << "\n" << std::flush;
        }
    }
    if (hold) {
        // Held back: goldens that would be new or changed (an unchanged one
        // is not "held", and a new one did not "stay" anywhere).
        out << "no golden was written: " << why_held(p);
        if (held > 0) {
            out << ", and " << held << " other new or changed golden"
                << (held == 1 ? " was" : "s were") << " held back; fix "
                << (p.refusing.size() == 1 ? "it" : "them") << ", or write the others with "
                << "--partial\n";
        } else {
            out << "; fix " << (p.refusing.size() == 1 ? "it" : "them") << "\n";
        }
    } else if (!p.refusing.empty()) {
        out << partial_note(p, counts.created + counts.changed);
    }
    return counts;
}

} // namespace

int write_goldens(const std::string& verb, const std::vector<std::string>& args, std::ostream& out,
                  std::ostream& err) {
    const Arguments a = parse_arguments(args, {"--root", "--engine"},
                                        {"--help", "--prune", "--quiet", "--partial"});
    if (a.has_flag("--help")) {
        out << (verb == "regen" ? regen_help : bless_help);
        return exit_ok;
    }
    if (ci_mode()) {
        err << "impulse " << verb
            << ": refusing to write goldens in CI mode (CI=" << std::getenv("CI")
            << "); bless on a developer machine and commit the goldens\n";
        return exit_bad_input;
    }
    const Project project = find_project(a.option("--root"));
    const std::vector<EngineSpec> engines = engines_chosen(project, a.option("--engine"));
    for (const EngineSpec& engine : engines) {
        require_startable(engine);
    }
    const std::vector<std::string> paths = scenes_named(project, a.positional);
    // A scene named on the command line from outside the project is the
    // command's mistake, said alone before anything runs, not a broken scene.
    // A file that is no scene at all keeps its own sentence (a broken scene).
    for (const std::string& path : paths) {
        try {
            require_project_scene(project, path);
        } catch (const InputError&) {
            try {
                (void)load_scene(path);
            } catch (const InputError&) {
                continue;
            }
            throw;
        }
    }
    Preparation prepared = prepare_all(project, engines, paths, a.has_flag("--quiet"), err);
    const bool partial = a.has_flag("--partial");
    BlessCounts c;
    {
        // The goldens change as one set: an interrupt (Ctrl-C, a CI cancel)
        // that arrives once they are being written takes effect after the
        // last is written or pruned. Held on this thread alone, the only one
        // left: the scenes' runs have ended. An outside review interrupted a
        // bless of six changed goldens after the first and found 1 of 6
        // written.
        const HeldInterrupts whole_set;
        c = write_prepared(prepared, partial, out, err);
        const bool held = !prepared.refusing.empty() && !partial;
        for (const std::string& golden : unreferenced_goldens(project)) {
            if (a.has_flag("--prune") && !held) {
                std::filesystem::remove(golden);
                ++c.removed;
                out << "  removed    " << printable_path(golden) << "\n";
            } else {
                out << "  unreferenced " << printable_path(golden)
                    << (held ? std::string(" (not pruned while a scene refuses)\n")
                             : " (" + unreferenced_reason(project, golden) +
                                   "; --prune deletes it)\n");
            }
        }
    }
    out << "goldens: " << c.created << " new, " << c.changed << " changed, " << c.unchanged
        << " unchanged, " << c.removed << " removed";
    if (c.refused > 0) {
        out << ", " << c.refused << " refused";
    }
    if (c.skipped > 0) {
        out << ", " << c.skipped << " skipped (unsupported)";
    }
    if (c.broken > 0) {
        out << ", " << c.broken << " broken scene" << (c.broken == 1 ? "" : "s");
    }
    if (c.unwritten > 0) {
        out << ", " << c.unwritten << " could not write the golden";
    }
    out << "\n";
    return c.broken > 0 || c.unwritten > 0 ? exit_bad_input : c.refused > 0 ? exit_failed : exit_ok;
}

int bless_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    return write_goldens("bless", args, out, err);
}

} // namespace impulse::harness::cli
