#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <ricci/mesh/errors.h>

#include "msp/cli.h"

namespace {

TEST(Args, ParsesPositionalsOptionsAndFlags) {
  const char* raw[] = {"mesh.obj", "--degree", "3", "--json", "--tol=1e-9", "-o", "out.glb"};
  msp::Args args(7, const_cast<char**>(raw), {"json"});
  ASSERT_EQ(args.positionals().size(), 1u);
  EXPECT_EQ(args.get_int("degree", 0), 3);
  EXPECT_TRUE(args.has("json"));
  EXPECT_DOUBLE_EQ(args.get_double("tol", 0), 1e-9);
  EXPECT_EQ(args.get_or("output", ""), "out.glb");
}

TEST(Args, RejectsUnknownOptionsAndBadNumbers) {
  const char* raw[] = {"--degre", "x"};
  msp::Args args(2, const_cast<char**>(raw), {});
  EXPECT_THROW(args.require_known({"degree"}), msp::UsageError);
  EXPECT_THROW(args.get_int("degre", 0), msp::UsageError);
}

msp::CommandSpec test_spec() {
  return {"demo",
          "a command for the tests",
          {{"MESH", "the mesh"}},
          {{"degree", "n", "the degree"},
           {"output", "OUT.glb", "the output"},
           {"fairness", "r", "the fairness"},
           {"genus", "G", "the genus", true},
           msp::json_option()}};
}

msp::Args parse(const msp::CommandSpec& spec, std::vector<std::string> words) {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  return msp::Args(static_cast<int>(argv.size()), argv.data(), spec);
}

TEST(ArgsSpec, ParsesAgainstTheSpec) {
  const auto spec = test_spec();
  const auto args = parse(spec, {"--degree=4", "m.off", "-o", "x.glb", "--fairness", "-1",
                                 "--genus", "2", "--json"});
  ASSERT_EQ(args.positionals(), std::vector<std::string>{"m.off"});
  EXPECT_EQ(args.get_int("degree", 0), 4);
  EXPECT_EQ(args.get_or("output", ""), "x.glb");
  EXPECT_EQ(args.get_int("fairness", 0), -1);  // a negative number is a value
  EXPECT_TRUE(args.has("json"));
  EXPECT_EQ(parse(spec, {"m.off", "--genus", "1", "--output", "y.glb"}).get_or("output", ""),
            "y.glb");
}

TEST(ArgsSpec, RefusesWhatTheSpecDoesNotSay) {
  const auto spec = test_spec();
  const std::vector<std::vector<std::string>> bad = {
      {"m.off", "--genus", "1", "--degre", "3"},  // unknown option
      {"m.off", "--genus", "1", "-d"},            // unknown short option
      {"m.off", "--genus", "1", "--json=yes"},    // a switch with a value
      {"m.off", "--genus", "1", "--degree"},      // no value
      {"m.off", "--genus", "--json"},             // a value never starts with --
      {"m.off"},                                  // required --genus missing
      {"--genus", "1"},                           // MESH missing
      {"a.off", "b.off", "--genus", "1"},         // one positional too many
  };
  for (const auto& words : bad) EXPECT_THROW(parse(spec, words), msp::UsageError) << words[1];
  // Reading an option the spec does not declare is the command's bug, not the user's.
  const auto args = parse(spec, {"m.off", "--genus", "1"});
  EXPECT_THROW((void)args.has("degre"), std::logic_error);
}

TEST(ArgsSpec, MultiValueAndRepeatedOptions) {
  const msp::CommandSpec spec{"demo",
                              "a command for the tests",
                              {},
                              {{"move", "INDEX DX DY DZ", "move a point", false, true},
                               {"ball", "X Y Z R", "a ball", false, true},
                               {"degree", "n", "the degree"}}};
  const auto args = parse(spec, {"--move", "3", "0", "-0.5", "1e-3", "--ball", "1", "2", "3", "4",
                                 "--move=7", "1", "1", "1", "--degree", "2", "--degree", "5"});
  using Values = std::vector<std::string>;
  EXPECT_EQ(args.get_all("move"),
            (std::vector<Values>{{"3", "0", "-0.5", "1e-3"}, {"7", "1", "1", "1"}}));
  EXPECT_EQ(args.get("ball"), "1 2 3 4");
  EXPECT_EQ(args.get_int("degree", 0), 5);  // a repeated single option: the last one
  ASSERT_EQ(args.occurrences().size(), 5u);
  EXPECT_EQ(args.occurrences()[1].name, "ball");  // the order given
  EXPECT_EQ(args.occurrences()[2].name, "move");
  EXPECT_THROW(parse(spec, {"--move", "3", "0", "1"}), msp::UsageError);
  EXPECT_THROW(parse(spec, {"--move", "3", "0", "1", "--degree", "2"}), msp::UsageError);
  EXPECT_EQ(msp::usage_text(spec),
            "msp demo [--move INDEX DX DY DZ]... [--ball X Y Z R]... [--degree n]\n");
}

TEST(ArgsSpec, HelpAnywhereWins) {
  const auto spec = test_spec();
  for (const auto& words : std::vector<std::vector<std::string>>{
           {"--help"}, {"-h"}, {"m.off", "--degree", "--help"}, {"--bogus", "-h"}}) {
    try {
      (void)parse(spec, words);
      ADD_FAILURE() << "no help for " << words.back();
    } catch (const msp::HelpRequested& help) {
      EXPECT_EQ(help.spec, &spec);
    }
  }
}

TEST(ArgsSpec, UsageWrapsAndShowsRequiredOptionsBare) {
  auto spec = test_spec();
  EXPECT_EQ(msp::usage_text(spec),
            "msp demo MESH [--degree n] [-o OUT.glb] [--fairness r] --genus G [--json]\n");
  EXPECT_EQ(msp::usage_text(spec, 40),
            "msp demo MESH [--degree n] [-o OUT.glb]\n"
            "         [--fairness r] --genus G\n"
            "         [--json]\n");
  const std::string help = msp::help_text(spec);
  const std::string genus = "  --genus G" + std::string(13, ' ') + "the genus (required)\n";
  const std::string flag = "  -h, --help" + std::string(12, ' ') + "print this help and exit\n";
  EXPECT_NE(help.find(genus), std::string::npos) << help;
  EXPECT_NE(help.find(flag), std::string::npos) << help;
}

TEST(AtomicWrite, FailureLeavesNoFile) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "msp_atomic_test";
  fs::create_directories(dir);
  fs::path target = dir / "out.txt";
  fs::remove(target);
  EXPECT_THROW(msp::write_file_atomically(target.string(),
                                          [](const std::string&) { throw ricci::IOError("boom"); }),
               ricci::IOError);
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(dir));
  msp::write_text_atomically(target.string(), "hello");
  std::ifstream in(target);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "hello");
  fs::remove_all(dir);
}

}  // namespace
