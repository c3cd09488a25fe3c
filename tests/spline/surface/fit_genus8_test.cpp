// msp fit's pipeline on a closed genus-8 surface: one cone of 30 pi, around which the valence
// modification and the cone refinement leave a band of slivers; the cone hole must reach past
// them (cone_hole_limits' reach) or its patch flips (main before the reach: seam 164 degrees).
#include <gtest/gtest.h>

#include "ricci/mesh/generate.h"
#include "spline/surface/fit_surface.h"

namespace {

TEST(FitSurfaceGenus8, OneConeWatertightWithoutFoldsAndNoFlippedPatch) {
  ricci::GenerateOptions generate;
  generate.genus = 8;
  generate.target_faces = 2400;
  const ricci::Mesh mesh = ricci::generate_surface(generate);
  const spline::FittedSurface fitted = spline::fit_surface(mesh);
  EXPECT_EQ(fitted.input.genus, 8);
  EXPECT_TRUE(fitted.watertight);
  EXPECT_TRUE(fitted.topology.closed(8));
  EXPECT_EQ(fitted.surface_dihedral.over_90_deg, 0);
  EXPECT_LT(fitted.fill_normal_jump_deg, 1.0);
  EXPECT_LT(fitted.edge_normal_jump_deg, 1.0);
  EXPECT_LT(fitted.fit_rms / fitted.bbox_diagonal, 2e-3);
}

}  // namespace
