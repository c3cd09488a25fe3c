// msp module and msp index end to end on meshes made here: JSON keys and values against the
// closed forms, the SVG, the text tables, and bad input (one line, non-zero status, no file).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>

#include "info_subprocess.h"
#include "scratch_folder.h"
#include "ricci/analysis/analysis_meshes.h"
#include "ricci/test_meshes.h"

namespace {

namespace fs = std::filesystem;

class ModuleCli : public msp_test::ScratchFolderTest {
 protected:
  ModuleCli() : ScratchFolderTest("msp_module_cli_") {}
};

double annulus_module(double r, double R) { return std::log(R / r) / (2 * M_PI); }

TEST_F(ModuleCli, AnnulusJsonAndPicture) {
  const std::string mesh = file("annulus.off", ricci::testing::log_polar_annulus(12, 60, 0.3, 1));
  const std::string svg = (folder_ / "annulus.svg").string();
  const auto r = msp_test::run_msp({"module", mesh, "--json", "-o", svg});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"kind", "genus", "boundary_loops", "module", "vector", "invariant",
                          "roundness", "preparation", "flow", "seconds"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["kind"], "annulus");
  EXPECT_NEAR(j["module"]["module"].get<double>(), annulus_module(0.3, 1), 1e-3);
  EXPECT_EQ(j["preparation"], "as given");
  std::ifstream in(svg);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("annulus module"), std::string::npos);
  EXPECT_NE(text.str().find("<path"), std::string::npos);
}

TEST_F(ModuleCli, RectangleWithCorners) {
  const std::string mesh = file("grid.off", ricci::make_planar_grid(20, 10, 2, 1));
  const auto r = msp_test::run_msp({"module", mesh, "--corners", "0,20,230,210"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_NE(r.out.find("kind rectangle"), std::string::npos) << r.out;
  const size_t at = r.out.find("aspect_ratio ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(at + 13)), 0.5, 1e-6);
}

TEST_F(ModuleCli, DiskMapAndPicture) {
  const std::string mesh = file("disk.off", ricci::testing::circle_domain_mesh({}, 0.1));
  const std::string svg = (folder_ / "disk.svg").string();
  const auto r = msp_test::run_msp({"module", mesh, "--kind", "disk", "--json", "-o", svg});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["kind"], "disk");
  EXPECT_TRUE(j["vector"].empty());
  EXPECT_LT(j["roundness"].get<double>(), 1e-6);
  ASSERT_EQ(j["corners"].size(), 2u);  // the centre and the boundary vertex at 1
  EXPECT_TRUE(fs::exists(svg));
  const int centre = j["corners"][0].get<int>() == 0 ? 1 : j["corners"][0].get<int>();
  const auto given = msp_test::run_msp(
      {"module", mesh, "--kind", "disk", "--centre", std::to_string(centre), "--json"});
  ASSERT_EQ(given.exit_status, 0) << given.err;
  EXPECT_EQ(nlohmann::json::parse(given.out)["corners"][0], centre);
}

TEST_F(ModuleCli, IndexGroupsAndOrders) {
  const std::string a = file("a.off", ricci::testing::log_polar_annulus(8, 40, 0.3, 1));
  const std::string b = file("b.off", ricci::testing::log_polar_annulus(8, 40, 0.5, 1));
  const std::string c = file("c.off", ricci::testing::log_polar_annulus(8, 40, 0.35, 1));
  const std::string t = file("t.off", ricci::testing::torus(40, 16));
  const auto r = msp_test::run_msp({"index", a, b, t, c, "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["meshes"].size(), 4u);
  ASSERT_EQ(j["groups"].size(), 2u);
  const auto& annuli = j["groups"][0];
  EXPECT_EQ(annuli["kind"], "annulus");
  EXPECT_EQ(annuli["members"], nlohmann::json({0, 1, 3}));
  // a's nearest is c (log 0.35 is closer to log 0.3 than log 0.5 is).
  EXPECT_EQ(annuli["nearest"][0], nlohmann::json({3, 1}));
  EXPECT_NEAR(annuli["distances"][0][1].get<double>(),
              annulus_module(0.3, 1) - annulus_module(0.5, 1), 1e-3);
  EXPECT_EQ(j["groups"][1]["kind"], "flat-torus");
  const auto text = msp_test::run_msp({"index", a, b});
  ASSERT_EQ(text.exit_status, 0) << text.err;
  EXPECT_NE(text.out.find("nearest to [0]: [1]"), std::string::npos) << text.out;
}

TEST_F(ModuleCli, IndexReportsAFailureAndGoesOn) {
  const std::string a = file("a.off", ricci::testing::log_polar_annulus(8, 40, 0.3, 1));
  const std::string b = file("b.off", ricci::testing::log_polar_annulus(8, 40, 0.5, 1));
  const std::string missing = (folder_ / "missing.off").string();
  const auto r = msp_test::run_msp({"index", a, missing, b, "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_NE(r.err.find("failed"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["meshes"].size(), 3u);
  EXPECT_TRUE(j["meshes"][1].contains("failed"));
  EXPECT_EQ(j["failed"], nlohmann::json({1}));
  ASSERT_EQ(j["groups"].size(), 1u);
  // Members and neighbours keep the input positions.
  EXPECT_EQ(j["groups"][0]["members"], nlohmann::json({0, 2}));
  EXPECT_EQ(j["groups"][0]["nearest"][0], nlohmann::json({2}));
  const auto text = msp_test::run_msp({"index", missing, a, b});
  ASSERT_EQ(text.exit_status, 0) << text.err;
  EXPECT_NE(text.out.find("[0] " + missing + ": failed"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("nearest to [1]: [2]"), std::string::npos) << text.out;
  // Nothing to index: one line, non-zero.
  const auto none = msp_test::run_msp({"index", missing});
  EXPECT_NE(none.exit_status, 0);
  EXPECT_TRUE(none.out.empty());
}

TEST_F(ModuleCli, BadInputOneLineNoFile) {
  const std::string sphere = file("sphere.off", ricci::testing::sphere(2));
  const std::string grid = file("grid.off", ricci::make_planar_grid(4, 4, 1, 1));
  const std::string svg = (folder_ / "bad.svg").string();
  const std::vector<std::vector<std::string>> cases = {
      {"module", sphere, "--kind", "annulus", "-o", svg},
      {"module", grid, "--corners", "0,4,24,12", "-o", svg},
      {"module", grid, "--corners", "0,4,24", "-o", svg},
      {"module", grid, "--corners", "0,4,24,999", "-o", svg},
      {"module", grid, "--kind", "doughnut"},
      {"module", grid, "--centre", "7"},                       // the rectangle has no centre
      {"module", grid, "--kind", "disk", "--centre", "0"},     // on the boundary
      {"module", sphere, "--kind", "disk"},
      {"module", sphere, "-o", svg},  // a sphere has no canonical domain to draw
      {"module", (folder_ / "missing.off").string()},
      {"index"},
  };
  for (const auto& args : cases) {
    const auto r = msp_test::run_msp(args);
    EXPECT_NE(r.exit_status, 0) << args[1];
    EXPECT_EQ(msp_test::line_count(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(svg));
  }
}

}  // namespace
