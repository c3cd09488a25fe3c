// msp-bench's command line: a bad number, list or subcommand gives one clear line on stderr and a
// non-zero exit before any benchmark runs (no model is read: the cases would need the shared
// collection otherwise).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "apps/info_subprocess.h"

#ifdef MSP_BENCH_BINARY

namespace {

using msp_test::line_count;
using msp_test::ProcessResult;

ProcessResult run_bench(const std::vector<std::string>& args) {
  return msp_test::run_program(MSP_BENCH_BINARY, args);
}

struct BadNumber {
  std::vector<std::string> args;
  std::string expected;  // what the one line must say
};

TEST(BenchCli, BadNumbersGiveOneLineAndExitOne) {
  const std::string mesh = std::string(MSP_SOURCE_DIR) + "/models/genus1.off";
  const std::vector<BadNumber> cases = {
      {{"one-cone-one", mesh, "--warm-fraction", "abc"},
       "--warm-fraction expects a number, got 'abc'"},
      {{"one-cone-one", mesh, "--cone", "12x"}, "--cone expects an integer, got '12x'"},
      {{"one-cone-one", "generated:4x:1000"}, "genus expects an integer, got '4x'"},
      {{"fill", "--faces", "many"}, "option --faces expects an integer, got 'many'"},
      {{"fill", "--smoothing", "1e-3e"}, "option --smoothing expects a number, got '1e-3e'"},
      {{"spline-fit", "--lambda", "x"}, "option --lambda expects a number, got 'x'"},
      {{"loop-fit", "--control", "2000,x"}, "option --control expects an integer, got 'x'"},
      {{"intrinsic", "--genera", "4,,6"}, "option --genera expects an integer, got ''"},
      {{"fit-scale", mesh, "--levels", "0,1.5"}, "option --levels expects an integer, got '1.5'"},
      {{"adaptive", "--rms", "0.1%"}, "option --rms expects a number, got '0.1%'"},
      {{"dms", "sixteen"}, "the grid size expects an integer, got 'sixteen'"},
  };
  for (const BadNumber& c : cases) {
    SCOPED_TRACE(c.args[0] + " " + c.args.back());
    const ProcessResult r = run_bench(c.args);
    EXPECT_EQ(r.exit_status, 1);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_EQ(r.err.rfind("msp-bench " + c.args[0] + ": ", 0), 0u) << r.err;
  }
}

TEST(BenchCli, UnknownBenchmarkIsRefusedWithUsage) {
  const ProcessResult r = run_bench({"no-such-benchmark"});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_EQ(r.err.rfind("msp-bench: unknown benchmark 'no-such-benchmark'\n", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("one-cone-one"), std::string::npos) << "the usage lists the benchmarks";
}

}  // namespace

#endif  // MSP_BENCH_BINARY
