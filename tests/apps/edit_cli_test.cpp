// msp edit as the real binary: bad spline files (tests/data/bad/*.msp) give one line on stderr
// naming the file and the problem, exit status 1 and no output file; a good file is edited (a
// region move, a control point by index) and the written file reads back with exactly the
// requested change; bad command lines exit with status 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "info_subprocess.h"
#include "spline/io/bad_splines.h"
#include "spline/io/spline_file.h"
#include "spline/surface/surface_fixtures.h"

namespace {

namespace fs = std::filesystem;
using msp_test::line_count;
using msp_test::run_msp;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("msp_edit_tests_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string bad_path(const char* name) { return std::string(MSP_TEST_DATA) + "/bad/" + name; }

TEST(EditCli, EveryBadSplineIsInTheTableAndViceVersa) {
  std::set<std::string> listed, present;
  for (const auto& bad : spline::testing::kBadSplines) listed.insert(bad.name);
  for (const auto& entry : fs::directory_iterator(std::string(MSP_TEST_DATA) + "/bad")) {
    if (entry.path().extension() == ".msp") present.insert(entry.path().filename().string());
  }
  EXPECT_EQ(listed, present);
}

TEST(EditCli, BadSplineFilesGiveOneLineAndNoOutput) {
  const fs::path out = scratch() / "edited.msp";
  for (const auto& bad : spline::testing::kBadSplines) {
    SCOPED_TRACE(bad.name);
    const auto result = run_msp({"edit", bad_path(bad.name), "--move-region", "0", "0", "0", "1",
                                 "0", "0", "0.1", "-o", out.string()});
    EXPECT_EQ(result.exit_status, 1);  // refused on purpose; -1 or 3 would be a crash
    EXPECT_EQ(line_count(result.err), 1) << result.err;
    EXPECT_EQ(result.err.rfind("msp edit: error: ", 0), 0u) << result.err;
    EXPECT_NE(result.err.find(bad.name), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.keyword), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(EditCli, MovesARegionAndAControlPoint) {
  const fs::path dir = scratch();
  const spline::SplineSurface& surface = spline::testing::small_surface("genus1.off", 100);
  const std::string input = (dir / "torus.msp").string();
  spline::save_spline_surface(surface, input, {{"tool", "test"}});
  const int face = surface.spline.space->domain_faces()[7];
  const Eigen::Vector3d centre =
      surface.spline.evaluate({face, Eigen::Vector3d::Constant(1.0 / 3.0)}).position;

  const std::string region = (dir / "region.msp").string();
  auto result = run_msp({"edit", input, "--move-region", std::to_string(centre.x()),
                         std::to_string(centre.y()), std::to_string(centre.z()), "0.5", "0", "0",
                         "0.05", "-o", region, "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const auto report = nlohmann::json::parse(result.out);
  EXPECT_GT(report.at("moved_control_points").get<int>(), 0);
  EXPECT_GT(report.at("affected_faces").get<int>(), 0);
  EXPECT_LE(report.at("max_displacement").get<double>(), 0.05);
  const spline::SplineFile edited = spline::read_spline_file(region);
  EXPECT_EQ(edited.header.provenance.at("tool"), "test");
  EXPECT_EQ(edited.header.provenance.at("edited_by"), "msp edit");
  const Eigen::MatrixX3d delta =
      edited.surface.spline.control_points - surface.spline.control_points;
  EXPECT_GT(delta.col(2).maxCoeff(), 0.0);
  EXPECT_LE(delta.col(2).maxCoeff(), 0.05 + 1e-12);
  EXPECT_EQ(delta.leftCols(2).cwiseAbs().maxCoeff(), 0.0);

  const std::string point = (dir / "point.msp").string();
  result = run_msp({"edit", input, "--move-point", "5", "0", "0", "1", "-o", point});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_EQ(line_count(result.out), 1) << result.out;
  const Eigen::MatrixX3d moved =
      spline::load_spline_surface(point).spline.control_points - surface.spline.control_points;
  EXPECT_NEAR(moved(5, 2), 1.0, 1e-12);
  EXPECT_NEAR(moved.cwiseAbs().sum(), 1.0, 1e-12);
  fs::remove_all(dir);
}

// msp fit --spline writes the fitted surface (with its cone patch), msp edit reads it.
TEST(EditCli, FitWritesASplineFileThatEditReads) {
  const fs::path dir = scratch();
  const std::string fitted = (dir / "genus2.msp").string();
  const std::string json = (dir / "genus2.json").string();
  auto result = run_msp({"fit", std::string(MSP_SOURCE_DIR) + "/models/genus2.off", "--spline",
                         fitted, "--json", json, "--domain-faces", "400", "--density", "3",
                         "--quiet"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const spline::SplineFile file = spline::read_spline_file(fitted);
  EXPECT_EQ(file.header.provenance.at("tool"), "msp fit");
  EXPECT_EQ(file.surface.fills.size(), 1u);
  std::ifstream report_file(json);
  const auto report = nlohmann::json::parse(report_file);
  EXPECT_EQ(file.surface.spline.control_points.rows(), report.at("control_points").get<int>());
  result = run_msp({"edit", fitted, "--move-point", "0", "0", "0", "0.01", "-o",
                    (dir / "edited.msp").string()});
  EXPECT_EQ(result.exit_status, 0) << result.err;
  result = run_msp({"fit", std::string(MSP_SOURCE_DIR) + "/models/genus2.off", "--spline",
                    (dir / "x.glb").string(), "--quiet"});
  EXPECT_EQ(result.exit_status, 2) << result.err;  // --spline must name an .msp file
  fs::remove_all(dir);
}

TEST(EditCli, BadCommandLinesAreRefused) {
  const fs::path dir = scratch();
  const std::string input = (dir / "torus.msp").string();
  spline::save_spline_surface(spline::testing::small_surface("genus1.off", 100), input);
  const std::string out = (dir / "out.msp").string();
  const std::vector<std::vector<std::string>> usage_errors = {
      {"edit", input, "--move-region", "0", "0", "0", "1", "0", "0", "0.1"},  // no -o
      {"edit", input, "-o", out},                                             // no move
      {"edit", input, "--move-region", "0", "0", "0", "-o", out},             // too few numbers
      {"edit", input, "--move-point", "x", "0", "0", "1", "-o", out},         // not a number
      {"edit", input, "--move-point", "1.5", "0", "0", "1", "-o", out},       // not an index
      {"edit", input, "--scale", "2", "--move-point", "1", "0", "0", "1", "-o", out},
  };
  for (const auto& args : usage_errors) {
    const auto result = run_msp(args);
    EXPECT_EQ(result.exit_status, 2) << result.err;
    EXPECT_EQ(line_count(result.err), 1) << result.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const auto result =
      run_msp({"edit", input, "--move-point", "99999999", "0", "0", "1", "-o", out});
  EXPECT_EQ(result.exit_status, 1) << result.err;
  EXPECT_NE(result.err.find("control point 99999999 is outside"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out));
  const auto radius =
      run_msp({"edit", input, "--move-region", "0", "0", "0", "-1", "0", "0", "1", "-o", out});
  EXPECT_EQ(radius.exit_status, 1) << radius.err;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

}  // namespace
