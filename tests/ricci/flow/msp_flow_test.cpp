// The msp flow subcommand, run as a process: JSON fields, atomic edge-length output, and a
// one-line error with a non-zero exit for infeasible or non-convergent runs.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "ricci/test_meshes.h"
#include "test_paths.h"

namespace {

struct ProcessRun {
  int status = -1;
  std::string out, err;
};

ProcessRun run_msp(const std::string& arguments) {
  namespace fs = std::filesystem;
  const fs::path err_file = fs::temp_directory_path() / ("msp_flow_test_" + std::to_string(::getpid()) + ".err");
  const std::string command = std::string(MSP_BINARY) + " flow " + arguments + " 2> " + err_file.string();
  ProcessRun run;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  while (pipe && fgets(buffer.data(), buffer.size(), pipe)) run.out += buffer.data();
  const int raw = pipe ? pclose(pipe) : -1;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(err_file);
  std::stringstream s;
  s << in.rdbuf();
  run.err = s.str();
  fs::remove(err_file);
  return run;
}

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(MspFlow, PrintsOneJsonObjectAndWritesLengths) {
  namespace fs = std::filesystem;
  const fs::path lengths = fs::temp_directory_path() / "msp_flow_test_lengths.txt";
  fs::remove(lengths);
  const ProcessRun run = run_msp(msp_test::test_mesh("closed_g1/knot1.off.gz") +
                          " --json --lengths-out " + lengths.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["status"], "converged");
  EXPECT_LT(j["max_curvature_error"].get<double>(), 1e-10);
  EXPECT_GT(j["iterations"].get<int>(), 0);
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
  EXPECT_EQ(j["vertices"].get<int>(), 3200);
  EXPECT_EQ(j["faces"].get<int>(), 6400);
  // Progress on stderr, one line per Newton iteration.
  EXPECT_EQ(count_lines(run.err), j["iterations"].get<int>());
  std::ifstream in(lengths);
  int v0, v1, edges = 0;
  double length;
  while (in >> v0 >> v1 >> length) {
    ++edges;
    EXPECT_GT(length, 0.0);
  }
  EXPECT_EQ(edges, 9600);
  fs::remove(lengths);
}

TEST(MspFlow, InfeasibleTargetExitsNonZeroWithOneLine) {
  const ProcessRun run = run_msp(msp_test::test_mesh("closed_g2/eight.off") + " --target uniform");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("hyperbolic"), std::string::npos) << run.err;
}

TEST(MspFlow, NonConvergentRunExitsNonZeroWithOneLineAndNoLengths) {
  namespace fs = std::filesystem;
  const fs::path lengths = fs::temp_directory_path() / "msp_flow_test_no_lengths.txt";
  fs::remove(lengths);
  const ProcessRun run = run_msp(msp_test::test_mesh("closed_g1/elk.off") +
                          " --metric inversive-distance --quiet --lengths-out " + lengths.string());
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("worst vertices"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(lengths));
}

TEST(MspFlow, BadOptionsAreUsageErrors) {
  EXPECT_EQ(run_msp(msp_test::test_mesh("closed_g1/knot1.off.gz") + " --geometry flat").status, 2);
  EXPECT_EQ(run_msp(msp_test::test_mesh("closed_g1/knot1.off.gz") + " --target cone:x").status, 2);
}

}  // namespace
