// `msp fit` hole filling as a user sees it: the report's watertight, open_rims, filled_rims and
// boundary_rims agree with the topology of the surface written to the OBJ, for an open model
// with and without --fill-boundaries and for a closed genus-0 model (the punctured sphere).
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <ostream>
#include <fstream>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <nlohmann/json.hpp>

#include "apps/info_subprocess.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;

struct FitOutput {
  nlohmann::json report;
  ricci::SurfaceTopology surface;  ///< Of the OBJ (the welded tessellation).
};

FitOutput run_fit(const std::string& model, const std::string& name, bool fill_boundaries,
                  const std::vector<std::string>& size = {"--domain-faces", "400", "--density",
                                                          "3"}) {
  const fs::path dir =
      fs::temp_directory_path() / ("msp_fit_fill_tests_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<std::string> args = {"fit",
                                   model,
                                   "-o",
                                   (dir / "x.glb").string(),
                                   "--json",
                                   (dir / "x.json").string(),
                                   "--obj",
                                   (dir / "x.obj").string(),
                                   "--quiet"};
  args.insert(args.end(), size.begin(), size.end());
  if (fill_boundaries) args.push_back("--fill-boundaries");
  const auto r = msp_test::run_msp(args);
  EXPECT_EQ(r.exit_status, 0) << r.err;
  FitOutput out;
  std::ifstream in(dir / "x.json");
  out.report = nlohmann::json::parse(in);
  out.surface = ricci::surface_topology(ricci::read_mesh((dir / "x.obj").string()));
  fs::remove_all(dir);
  return out;
}

// Without --fill-boundaries the boundary rims stay open, one per input loop: the surface keeps
// the input's genus and boundary loops.
TEST(FitFill, OpenModelKeepsOneLoopPerOpenRim) {
  const FitOutput out =
      run_fit(msp_test::bundled_model("genus2_two_holes.off"), "open", false);
  const auto& r = out.report;
  EXPECT_TRUE(r["watertight"].get<bool>()) << r.dump(1);
  EXPECT_EQ(r["boundary_loops"], 2);
  EXPECT_EQ(r["boundary_rims"], 2);
  EXPECT_EQ(r["open_rims"], r["boundary_rims"]);
  EXPECT_TRUE(r["fill_failures"].empty());
  EXPECT_EQ(out.surface.genus, 2);
  EXPECT_EQ(out.surface.boundary_loops, 2);
  EXPECT_EQ(r["tessellation"]["boundary_loops"], r["open_rims"]);
}

// With --fill-boundaries every rim is capped (a positions-only patch where no height field fits,
// counted in fallback_fills; nearby loops may share a rim): a closed surface of the input's
// genus.
TEST(FitFill, FillBoundariesClosesTheSurface) {
  const FitOutput out =
      run_fit(msp_test::bundled_model("genus2_two_holes.off"), "filled", true);
  const auto& r = out.report;
  EXPECT_TRUE(r["watertight"].get<bool>()) << r.dump(1);
  EXPECT_EQ(r["open_rims"], 0);
  EXPECT_GE(r["boundary_rims"].get<int>(), 1);
  EXPECT_LE(r["boundary_rims"].get<int>(), 2);
  EXPECT_GE(r["filled_rims"].get<int>(), r["boundary_rims"].get<int>());
  EXPECT_LE(r["fallback_fills"].get<int>(), r["filled_rims"].get<int>());
  EXPECT_EQ(out.surface.genus, 2);
  EXPECT_EQ(out.surface.boundary_loops, 0);
}

// A closed genus-0 input is punctured by the one-cone pipeline; the puncture is one rim, always
// capped (without --fill-boundaries too): a closed sphere. The knight's puncture is no height
// field (its rim normals span more than a hemisphere): main left it open.
TEST(FitFill, PuncturedSphereIsCapped) {
  const FitOutput out =
      run_fit(msp_test::test_mesh("closed_g0/knight_decimated.off"), "sphere", false);
  const auto& r = out.report;
  EXPECT_TRUE(r["watertight"].get<bool>()) << r.dump(1);
  EXPECT_EQ(r["filled_rims"], 1);
  EXPECT_EQ(r["open_rims"], 0);
  EXPECT_EQ(r["boundary_rims"], 0);
  EXPECT_EQ(out.surface.genus, 0);
  EXPECT_EQ(out.surface.boundary_loops, 0);
}

// The seams at msp fit's defaults (2000 domain faces) on real scans, issue 6's "maximum seam
// normal jump below 1 degree". Earlier mains left them at 4.2 degrees (bunny_npm_closed: the
// surface turns fast next to the rim's vertices; meet_patches moved it to the patch: 1.3; the
// patch refined at the rim's corners: 0.78), 6.9 (femur: 0.44 with both), 169 (block: the cone
// patch flipped; the hole grown by one more layer: 2.4; refined: 0.32), 179 (elephant_cgal:
// the spline folds next to its 10 pi cone; the hole grown past the folds: 15, then 21), 13
// (helmet) and 179 (joint); the domain refined around the cone (ricci::refine_around_cone)
// brought the last three to 0.14, 0.75 and 0.24, and the fit RMS below 0.2% of the diagonal
// (joint: 1.56% before, 0.21% after; its 446 faces are its own domain, so every face has fewer
// points than functions and takes FitOptions::sparse_smoothing: 0.31%, the price of a surface
// that folds less: 1846 tessellation edges over 60 degrees instead of 2668).
struct SeamCase {
  const char* model;
  double max_rms_relative;
};

void PrintTo(const SeamCase& c, std::ostream* os) { *os << c.model; }

class FitSeams : public ::testing::TestWithParam<SeamCase> {};

TEST_P(FitSeams, BelowOneDegreeAtTheDefaults) {
  const SeamCase& c = GetParam();
  const FitOutput out = run_fit(msp_test::test_mesh(c.model), "seams", false,
                                {"--density", "3"});
  const auto& r = out.report;
  EXPECT_TRUE(r["watertight"].get<bool>()) << c.model;
  EXPECT_LT(r["seam_normal_jump_max_deg"].get<double>(), 1.0) << c.model;
  EXPECT_LT(r["fit_rms_relative"].get<double>(), c.max_rms_relative) << c.model;
  EXPECT_EQ(r["fallback_fills"], 0) << c.model;
}

INSTANTIATE_TEST_SUITE_P(Scans, FitSeams,
                         ::testing::Values(SeamCase{"closed_g0/bunny_npm_closed.off", 0.002},
                                           SeamCase{"closed_g2/femur.off.gz", 0.002},
                                           SeamCase{"closed_g2/joint.off", 0.0035},
                                           SeamCase{"closed_g3/block.off", 0.002},
                                           SeamCase{"closed_g3/elephant_cgal.off", 0.002},
                                           SeamCase{"closed_g3/helmet.off", 0.002}),
                         [](const ::testing::TestParamInfo<SeamCase>& info) {
                           std::string name = info.param.model;
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

}  // namespace
