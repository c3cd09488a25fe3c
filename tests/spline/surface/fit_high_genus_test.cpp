// msp fit's pipeline on closed surfaces of genus 4 and 8 (msp generate's rows of fused tori): one
// cone of 2 pi (2g - 1), whose patch must neither fold nor show a seam. At genus 8 the valence
// modification and the cone refinement leave a band of slivers around the 30 pi cone; the cone
// hole must reach past them (cone_hole_limits' reach) or its patch flips (main before the reach:
// seam 164 degrees at 12k faces; 1.79 degrees and 24 folds at 2400). Genus 4 also with the
// data placed through the intrinsic flips (tracked_parameters).
#include <gtest/gtest.h>

#include <string>

#include "ricci/mesh/generate.h"
#include "spline/surface/fit_surface.h"

namespace {

struct HighGenusCase {
  int genus;
  int faces;
  double rms;  ///< the fit's RMS bound, relative to the bounding-box diagonal
  bool tracked = false;  ///< FitSurfaceOptions::tracked_parameters
};

class FitSurfaceHighGenus : public ::testing::TestWithParam<HighGenusCase> {};

TEST_P(FitSurfaceHighGenus, OneConeWatertightWithoutFoldsAndASmallSeam) {
  const HighGenusCase c = GetParam();
  ricci::GenerateOptions generate;
  generate.genus = c.genus;
  generate.target_faces = c.faces;
  const ricci::Mesh mesh = ricci::generate_surface(generate);
  spline::FitSurfaceOptions options;
  options.tracked_parameters = c.tracked;
  const spline::FittedSurface fitted = spline::fit_surface(mesh, options);
  EXPECT_EQ(fitted.input.genus, c.genus);
  EXPECT_EQ(fitted.atlas.intrinsic, true);
  EXPECT_EQ(fitted.atlas.flip_record.empty(), !c.tracked);
  EXPECT_TRUE(fitted.watertight);
  EXPECT_TRUE(fitted.topology.closed(c.genus));
  EXPECT_EQ(fitted.surface_dihedral.over_90_deg, 0);
  EXPECT_LT(fitted.fill_normal_jump_deg, 1.0);
  EXPECT_LT(fitted.edge_normal_jump_deg, 1.0);
  EXPECT_LT(fitted.fit_rms / fitted.bbox_diagonal, c.rms);
}

// At 12k faces the first fit of generated genus 8 folds at 3 edges next to the cone's rim, where
// the fold rounds' raised smoothing does not reach: each fold round then gives the same fit
// (before kFoldRoundStall: ten rounds, each within 1e-7 of the RMS before it, 16 of the 44 s).
// A round that changes nothing ends its series; the refinement round then removes the folds.
TEST(FitSurfaceHighGenusRounds, FoldRoundsThatChangeNothingEndTheirSeries) {
  ricci::GenerateOptions generate;
  generate.genus = 8;
  generate.target_faces = 12000;
  const spline::FittedSurface fitted = spline::fit_surface(ricci::generate_surface(generate));
  ASSERT_GE(fitted.refinement.size(), 2u);
  const int first_domain = fitted.refinement.front().domain_faces;
  int on_first_domain = 0;
  for (const spline::RefinementRound& r : fitted.refinement)
    on_first_domain += r.domain_faces == first_domain;
  // The first fit and one round per fold series (stepped, then tapered).
  EXPECT_LE(on_first_domain, 3);
  EXPECT_GT(fitted.refinement.front().folds, 0);  // the case this test is about
  EXPECT_TRUE(fitted.watertight);
  EXPECT_EQ(fitted.surface_dihedral.over_90_deg, 0);
}

INSTANTIATE_TEST_SUITE_P(Generated, FitSurfaceHighGenus,
                         ::testing::Values(HighGenusCase{4, 6000, 1e-3},
                                           HighGenusCase{4, 6000, 1e-3, true},
                                           HighGenusCase{8, 2400, 2e-3}),
                         [](const auto& info) {
                           return "genus" + std::to_string(info.param.genus) +
                                  (info.param.tracked ? "_tracked" : "");
                         });

}  // namespace
