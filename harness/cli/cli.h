// The `impulse` command line: argument parsing and one function per verb.
// main() only forwards here, so tests call the verbs directly.
#pragma once

#include <iosfwd>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse::harness::cli {

// Exit codes for every verb (docs/design.md).
inline constexpr int exit_ok = 0;
inline constexpr int exit_failed = 1;    // a comparison or an expectation failed
inline constexpr int exit_bad_input = 2; // the input or the set-up was wrong

// Arguments after the verb: positionals and --options (as "--key value" or
// "--key=value"). Flags take no value.
struct Arguments {
    std::vector<std::string> positional;
    std::map<std::string, std::string> options;
    std::vector<std::string> flags;

    bool has_flag(const std::string& name) const;
    std::optional<std::string> option(const std::string& name) const;
};

class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Throws UsageError for an unknown option or a missing value. An option
// given twice keeps its last value (README, "Other verbs"): scripts/gate
// passes -j first, so that a user's own -j wins.
Arguments parse_arguments(const std::vector<std::string>& args,
                          const std::vector<std::string>& options_with_value,
                          const std::vector<std::string>& known_flags);

// "-j 4" and "-j4" spelled "--jobs 4" for parse_arguments (check, conform).
std::vector<std::string> normalise_jobs(const std::vector<std::string>& args);

// The most scenes `check` and `conform` run at once (-j N): far past the
// cores of any machine they run on, and a bound a message can name.
inline constexpr int max_jobs = 1024;

// A whole number from low to high given to `option` (--jobs, --shard,
// --substeps), or UsageError naming the range.
int parse_count(const std::string& option, const std::string& text, int low,
                int high = std::numeric_limits<int>::max());

// A strictly parsed positive finite number of seconds, or UsageError naming the option.
double positive_seconds(const std::string& option, const std::string& text);
// The items of a comma-separated LIST option (--dt 0.01,0.005), or UsageError
// for an empty item.
std::vector<std::string> comma_list(const std::string& text);

int main(int argc, char** argv);
// One function per verb; each returns the exit code and throws InputError or
// UsageError for bad input (main turns those into exit code 2).
int run_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int check_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int bless_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int diff_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int box2d_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int compare_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int render_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int sweep_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int stress_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int init_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int regen_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
// bless and regen, one implementation: `verb` picks the help text and names
// the verb in messages.
int write_goldens(const std::string& verb, const std::vector<std::string>& args, std::ostream& out,
                  std::ostream& err);
int conform_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

} // namespace impulse::harness::cli
