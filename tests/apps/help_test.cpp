// The command line as a new user meets it: every subcommand answers --help and -h with its help
// on stdout and status 0, refuses a bad option with one line and status 2, accepts the shared
// switches, and the README shows the usages the tool prints.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "apps/info_subprocess.h"
#include "msp/cli.h"
#include "msp/commands.h"

namespace {

using msp_test::line_count;
using msp_test::run_msp;

TEST(HelpText, EverySubcommandAnswersHelp) {
  ASSERT_GE(msp::subcommands().size(), 6u);
  for (const auto& command : msp::subcommands()) {
    const msp::CommandSpec& spec = command.spec();
    for (const char* flag : {"--help", "-h"}) {
      const auto r = run_msp({spec.name, flag});
      EXPECT_EQ(r.exit_status, 0) << spec.name << " " << flag << ": " << r.err;
      EXPECT_EQ(r.out, msp::help_text(spec)) << spec.name << " " << flag;
      EXPECT_EQ(r.err, "") << spec.name << " " << flag;
    }
    // Anywhere on the line, even where a value was expected (the issue's `msp fit --help`).
    const auto late = run_msp({spec.name, "x.off", "--tolerance", "--help"});
    EXPECT_EQ(late.exit_status, 0) << spec.name;
    EXPECT_EQ(late.out.rfind("msp " + spec.name + " ", 0), 0u) << late.out;
  }
}

TEST(HelpText, HelpNamesEveryOption) {
  for (const auto& command : msp::subcommands()) {
    const msp::CommandSpec& spec = command.spec();
    const std::string help = msp::help_text(spec);
    EXPECT_EQ(help.rfind(msp::usage_text(spec), 0), 0u) << spec.name;
    EXPECT_NE(help.find(spec.summary), std::string::npos) << spec.name;
    for (const auto& option : spec.options) {
      EXPECT_NE(help.find("--" + option.name), std::string::npos)
          << spec.name << " " << option.name;
      EXPECT_FALSE(option.help.empty()) << spec.name << " " << option.name;
    }
    for (const auto& line : {msp::usage_text(spec), help}) {
      std::istringstream in(line);
      for (std::string row; std::getline(in, row);) EXPECT_LE(row.size(), 100u) << row;
    }
  }
}

TEST(HelpText, OverviewListsEverySubcommand) {
  const auto r = run_msp({"--help"});
  EXPECT_EQ(r.exit_status, 0);
  for (const auto& command : msp::subcommands()) {
    const msp::CommandSpec& spec = command.spec();
    EXPECT_NE(r.out.find("  " + spec.name + " "), std::string::npos) << spec.name;
    EXPECT_NE(r.out.find(spec.summary), std::string::npos) << spec.name;
  }
  EXPECT_EQ(run_msp({"-h"}).out, r.out);
  const auto bare = run_msp({});
  EXPECT_EQ(bare.exit_status, 2);
  EXPECT_EQ(bare.err, r.out);
}

TEST(HelpText, BadCommandLinesGetOneLineAndStatusTwo) {
  for (const auto& command : msp::subcommands()) {
    const std::string name = command.spec().name;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{name, "x.off", "--no-such-option"},
          std::vector<std::string>{name, "x.off", "-x"},
          std::vector<std::string>{name, "x.off", "y.off", "z.off"}}) {
      // Three meshes are a good command line where the last positional takes several (MESH...).
      const auto& positionals = command.spec().positionals;
      if (args.size() == 4 && !positionals.empty() &&
          positionals.back().name.find("...") != std::string::npos)
        continue;
      const auto r = run_msp(args);
      EXPECT_EQ(r.exit_status, 2) << name << ": " << r.err;
      EXPECT_EQ(line_count(r.err), 1) << name << ": " << r.err;
      EXPECT_EQ(r.err.rfind("msp " + name + ": ", 0), 0u) << r.err;
      EXPECT_EQ(r.out, "") << name;
    }
  }
  EXPECT_NE(run_msp({"info", "x.off", "--no-such-option"}).err.find("--no-such-option"),
            std::string::npos);
}

// The shared switches mean the same on every subcommand: --quiet is accepted everywhere (the
// issue's `msp uniformize --quiet`); --json, where there is one, prints JSON on stdout, but in
// msp fit, where it has always named the report file.
TEST(HelpText, SharedSwitchesAreAcceptedEverywhere) {
  for (const auto& command : msp::subcommands()) {
    const msp::CommandSpec& spec = command.spec();
    bool quiet = false, json = true;
    for (const auto& option : spec.options) {
      if (option.name == "quiet")
        quiet = option.value.empty() && option.help == msp::quiet_option().help;
      if (option.name == "json")
        json = option.value.empty() ? option.help == msp::json_option().help : spec.name == "fit";
      if (option.name == "metric") {
        EXPECT_TRUE(option.value == msp::metric_option("").value ||
                    option.value == msp::metric_option("", true).value)
            << spec.name;
      }
    }
    EXPECT_TRUE(quiet) << spec.name;
    EXPECT_TRUE(json) << spec.name;
    // Refused for the missing mesh or required option, not for the switch.
    const auto r = run_msp({spec.name, "--quiet"});
    EXPECT_EQ(r.exit_status, 2) << spec.name;
    EXPECT_EQ(r.err.find("unknown option"), std::string::npos) << r.err;
  }
}

// A value never starts with "--": `--json --quiet` is a missing value, not a file "--quiet".
TEST(HelpText, OptionValuesAreNotOptions) {
  const auto r = run_msp({"fit", "x.off", "--json", "--quiet"});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("option --json needs a value"), std::string::npos) << r.err;
}

std::string readme_usage_block() {
  std::ifstream in(std::string(MSP_SOURCE_DIR) + "/README.md");
  std::string block, line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("<!-- msp usage: end", 0) == 0) break;
    if (inside && line.rfind("```", 0) != 0) block += line + "\n";
    if (line.rfind("<!-- msp usage: begin", 0) == 0) inside = true;
  }
  return block;
}

TEST(HelpText, ReadmeUsageBlockIsGenerated) {
  std::string expected;
  for (const auto& command : msp::subcommands()) expected += msp::usage_text(command.spec());
  EXPECT_EQ(readme_usage_block(), expected)
      << "README.md's usage block is out of date: run scripts/readme-usage.sh";
}

}  // namespace
