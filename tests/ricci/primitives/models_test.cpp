// The bundled models/ and `msp generate`: every row of models/INDEX.md matches its file (counts,
// topology, min angle), files stay small, and the command line reports bad options in one line.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ricci/mesh/generate.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"

namespace ricci {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line.substr(1));
  std::string cell;
  while (std::getline(in, cell, '|')) {
    const auto first = cell.find_first_not_of(" `");
    const auto last = cell.find_last_not_of(" `");
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return cells;
}

// Rows of the first markdown table in `path`, keyed by header name.
std::vector<std::map<std::string, std::string>> read_table(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("|", 0) != 0) continue;
    if (line.rfind("|---", 0) == 0) continue;
    const auto cells = split_row(line);
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

TEST(BundledModels, IndexMatchesEveryFile) {
  const fs::path folder = fs::path(MSP_SOURCE_DIR) / "models";
  const auto rows = read_table(folder / "INDEX.md");
  ASSERT_GE(rows.size(), 8u);
  bool has_genus2 = false;
  bool has_genus3 = false;
  for (const auto& row : rows) {
    const std::string file = row.at("file");
    SCOPED_TRACE(file);
    has_genus2 = has_genus2 || file == "genus2.off";
    has_genus3 = has_genus3 || file == "genus3.off";
    ASSERT_TRUE(fs::exists(folder / file));
    EXPECT_LT(fs::file_size(folder / file), 400u * 1024);
    const Mesh mesh = read_mesh((folder / file).string());
    const SurfaceTopology t = surface_topology(mesh);
    EXPECT_EQ(std::to_string(t.vertices), row.at("V"));
    EXPECT_EQ(std::to_string(t.faces), row.at("F"));
    EXPECT_EQ(std::to_string(t.boundary_loops), row.at("bdry loops"));
    EXPECT_EQ(std::to_string(t.genus), row.at("genus"));
    EXPECT_EQ(row.at("clean manifold"), "yes");
    EXPECT_TRUE(t.manifold);
    EXPECT_EQ(t.components, 1);
    EXPECT_NEAR(min_corner_angle_degrees(mesh), std::stod(row.at("min angle")), 0.051);
    EXPECT_EQ(row.at("how made").rfind("msp generate ", 0), 0u);
    EXPECT_NE(row.at("how made").find("-o models/" + file), std::string::npos);
    if (t.boundary_loops == 0) {
      EXPECT_GT(signed_volume(mesh), 0);
    }
  }
  EXPECT_TRUE(has_genus2);
  EXPECT_TRUE(has_genus3);
}

// Runs msp with `args`, returns its exit status and its stderr.
std::pair<int, std::string> run_msp(const std::string& args) {
  const fs::path err = fs::temp_directory_path() / ("msp_generate_test_" + std::to_string(::getpid()));
  const int status = std::system((std::string(MSP_BINARY) + " " + args + " 2> " + err.string() +
                                  " > /dev/null").c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  fs::remove(err);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

TEST(MspGenerate, BadOptionsAreOneLineUsageErrors) {
  for (const std::string args : {"--genus -1 -o x.off", "--genus 11 -o x.off",
                                 "--genus 1 --faces 10 -o x.off", "--genus 1 --holes 7 -o x.off",
                                 "--genus 1", "--faces 300 -o x.off", "--genus 1 --bogus 2 -o x.off"}) {
    SCOPED_TRACE(args);
    const auto [status, message] = run_msp("generate " + args);
    EXPECT_EQ(status, 2);
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  }
  EXPECT_FALSE(fs::exists("x.off"));
}

TEST(MspGenerate, WritesTheRequestedSurface) {
  const fs::path out = fs::temp_directory_path() / ("msp_generate_" + std::to_string(::getpid()) + ".obj");
  const auto [status, message] = run_msp("generate --genus 2 --holes 2 --faces 400 -o " + out.string());
  ASSERT_EQ(status, 0) << message;
  const Mesh mesh = read_mesh(out.string());
  fs::remove(out);
  const SurfaceTopology t = surface_topology(mesh);
  EXPECT_EQ(t.genus, 2);
  EXPECT_EQ(t.boundary_loops, 2);
  EXPECT_NEAR(t.faces, 400, 60);
}

}  // namespace
}  // namespace ricci
