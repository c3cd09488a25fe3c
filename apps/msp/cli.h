#pragma once
// Command-line helpers shared by the msp subcommands: the declarative description of a
// subcommand's command line (CommandSpec), the parser that checks a command line against it
// (Args), the help text generated from it, and error reporting.
//
// Each subcommand declares one CommandSpec (its positionals and options, each with a one-line
// help) and parses with `Args args(argc, argv, spec)`. From that one definition come `msp CMD
// --help`, the list of `msp --help`, the README's usage block (scripts/readme-usage.sh; a test
// keeps it equal) and the checks: unknown options, missing values and wrong positional counts
// are UsageErrors (one line, exit status 2), `--help` / `-h` anywhere is a HelpRequested (the
// help on stdout, exit status 0).
//
// Porting a subcommand written against the old `Args(argc, argv, flags)` constructor:
//   1. write `const CommandSpec& NAME_command()` returning a function-local static CommandSpec:
//      the usage's positionals and every name of its old require_known list (a name in the old
//      `flags` list is a switch: empty value; "output" is also -o), each with a help line, and
//      the shared options (json_option(), quiet_option(), ...) where the meaning is theirs
//      (every subcommand takes quiet_option(); a test checks it); an option of several values
//      is one OptionSpec with a placeholder of that many words, `repeatable` if it may recur
//      (then Args::occurrences() replaces a hand-written pre-pass over argv);
//   2. replace the three lines `Args args(argc, argv, {...}); args.require_known({...});
//      args.require_positionals(n, kUsage);` by `Args args(argc, argv, NAME_command());`;
//   3. declare NAME_command next to run_NAME in commands.h and list {NAME_command, run_NAME}
//      in subcommands() (commands.cpp), where `msp --help` finds it;
//   4. `scripts/readme-usage.sh` regenerates the README's usage block.
// The accessors (has, get, get_or, get_double, get_int) are unchanged.
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "msp/io/atomic_file.h"

namespace msp {

/// Thrown for a bad command line; main() prints it as one line and exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CommandSpec;

/// Thrown by Args when the command line asks for help; main() prints help_text(spec) on stdout
/// and exits with status 0.
struct HelpRequested {
  const CommandSpec* spec;
};

/// One option: `--name VALUE`, or the switch `--name` when `value` is empty. A value of k words
/// ("X Y Z") takes k values (`--move 1 2 3`).
struct OptionSpec {
  std::string name;   ///< Long name without the dashes; "output" is also spelled -o.
  std::string value;  ///< What the value is, as the usage shows it ("N", "OUT.glb"); empty: switch.
  std::string help;   ///< One line: what it does, its unit and default.
  bool required = false;    ///< Shown without brackets; a command line without it is refused.
  bool repeatable = false;  ///< Shown with "..."; every occurrence is kept (Args::get_all).
};

/// The number of values `option` takes: the words of its value placeholder.
[[nodiscard]] std::size_t value_count(const OptionSpec& option);

struct PositionalSpec {
  std::string name;  ///< As the usage shows it ("MESH").
  std::string help;
};

/// The command line of one subcommand.
struct CommandSpec {
  std::string name;     ///< "fit": `msp fit`.
  std::string summary;  ///< One line for `msp --help`.
  /// All required, in order; a last one whose name ends in "..." ("MESH...") takes one or more.
  std::vector<PositionalSpec> positionals;
  std::vector<OptionSpec> options;
};

/// The usage: "msp NAME POSITIONALS [--option VALUE] ...", wrapped before `width` columns with
/// continuation lines indented under the first positional; ends with a newline.
[[nodiscard]] std::string usage_text(const CommandSpec& spec, std::size_t width = 100);
/// The usage, a blank line, the summary, and one line per positional and option (with -h).
[[nodiscard]] std::string help_text(const CommandSpec& spec);

// Options several subcommands share, so the name means the same everywhere.
[[nodiscard]] OptionSpec json_option();   ///< --json: one JSON object on stdout instead of text.
[[nodiscard]] OptionSpec quiet_option();  ///< --quiet: no progress lines on stderr.
/// --metric circle-packing|inversive-distance|combinatorial: that metric alone, no fall-back to
/// the others (with --radii too); `fallback` says what happens without it.
/// --metric; `intrinsic` adds intrinsic-delaunay (the vertex-scaling flow with intrinsic
/// Delaunay flips, ricci/intrinsic/conformal_flow.h) for the commands that offer it.
[[nodiscard]] OptionSpec metric_option(const std::string& fallback, bool intrinsic = false);
[[nodiscard]] OptionSpec radii_option();   ///< --radii mean|min|least-squares.
[[nodiscard]] OptionSpec solver_option();  ///< --solver auto|eigen-ldlt|...
/// --tolerance T: the flow's stopping tolerance on max |K - target|, default `fallback`.
[[nodiscard]] OptionSpec tolerance_option(const std::string& fallback);
[[nodiscard]] OptionSpec singularity_option();  ///< --singularity auto|VERTEX.

/// `text` read whole as a number; `what` names it in the error ("option --faces").
/// \throw UsageError "WHAT expects a number, got 'TEXT'" for anything else (trailing
///        characters included).
[[nodiscard]] double parse_double(const std::string& text, const std::string& what);
/// `text` read whole as an int. \throw UsageError "WHAT expects an integer, got 'TEXT'".
[[nodiscard]] int parse_int(const std::string& text, const std::string& what);
/// A comma-separated list of ints ("1,2,4"), each read by parse_int.
[[nodiscard]] std::vector<int> parse_int_list(const std::string& text, const std::string& what);

/// Parsed arguments: positionals in order, `--name value` options and `--flag` switches.
class Args {
 public:
  /// Parses against `spec` (which must outlive the Args): `--name VALUE`, `--name=VALUE`,
  /// `-o VALUE` for "output", switches, positionals anywhere. A value never starts with "--"
  /// (`--json --quiet` is a missing value, not a file called "--quiet").
  /// \throw HelpRequested for --help or -h anywhere; UsageError for an unknown option, a missing
  ///        or unexpected value, a missing required option or a wrong number of positionals.
  Args(int argc, char** argv, const CommandSpec& spec);

  /// Old style, for subcommands not yet ported (see the top of this file): `flags` lists the
  /// switches that take no value; every other `--name` takes one; nothing is checked until
  /// require_known / require_positionals.
  Args(int argc, char** argv, std::initializer_list<std::string> flags);

  const std::vector<std::string>& positionals() const { return positionals_; }
  /// For Args built from a CommandSpec, naming an option the spec lacks is a programming error:
  /// std::logic_error (main() reports an internal error).
  bool has(const std::string& name) const;
  /// The value of the option's last occurrence (the values of a multi-value option joined by
  /// single spaces).
  std::optional<std::string> get(const std::string& name) const;
  /// Every occurrence of the option, in command-line order, each its values.
  std::vector<std::vector<std::string>> get_all(const std::string& name) const;
  /// One option as given on the command line.
  struct Occurrence {
    std::string name;
    std::vector<std::string> values;
  };
  /// Every option given, in command-line order (how repeated options of several kinds
  /// interleave). Empty for old-style Args.
  const std::vector<Occurrence>& occurrences() const { return occurrences_; }
  std::string get_or(const std::string& name, const std::string& fallback) const;
  double get_double(const std::string& name, double fallback) const;
  int get_int(const std::string& name, int fallback) const;
  /// Old style: throws UsageError naming the first option not in `known`.
  void require_known(const std::vector<std::string>& known) const;
  /// Old style: throws UsageError unless there are exactly `count` positionals.
  void require_positionals(size_t count, const std::string& usage) const;

 private:
  void check_declared(const std::string& name) const;

  const CommandSpec* spec_ = nullptr;
  std::vector<std::string> positionals_;
  std::map<std::string, std::string> options_;
  std::vector<Occurrence> occurrences_;
};

}  // namespace msp
