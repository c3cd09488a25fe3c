#pragma once
// The msp subcommands. Each takes the arguments after its name and returns the exit status;
// errors are thrown (ricci::Error, msp::UsageError, msp::HelpRequested) and reported by main().
// Each has one CommandSpec (cli.h) describing its command line: its help and its checks.
#include <string>
#include <vector>

#include "msp/cli.h"

namespace msp {

const CommandSpec& info_command();
int run_info(int argc, char** argv);
const CommandSpec& generate_command();
int run_generate(int argc, char** argv);
const CommandSpec& flow_command();
int run_flow(int argc, char** argv);
const CommandSpec& atlas_command();
int run_atlas(int argc, char** argv);
const CommandSpec& uniformize_command();
int run_uniformize(int argc, char** argv);
const CommandSpec& fit_command();
int run_fit(int argc, char** argv);
const CommandSpec& edit_command();
int run_edit(int argc, char** argv);
const CommandSpec& eval_command();
int run_eval(int argc, char** argv);
const CommandSpec& bezier_command();
int run_bezier(int argc, char** argv);
const CommandSpec& tessellate_command();
int run_tessellate(int argc, char** argv);
const CommandSpec& module_command();
int run_module(int argc, char** argv);
const CommandSpec& index_command();
int run_index(int argc, char** argv);
const CommandSpec& match_command();
int run_match(int argc, char** argv);

/// A subcommand as main() dispatches it.
struct Subcommand {
  const CommandSpec& (*spec)();
  int (*run)(int, char**);
};

/// Every subcommand, in the order `msp --help` lists them.
const std::vector<Subcommand>& subcommands();

/// `msp --help`: the usage of msp and one line per subcommand.
[[nodiscard]] std::string overview_text();

}  // namespace msp
