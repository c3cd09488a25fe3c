// msp fit's pipeline on a closed genus-4 surface: one cone of 14 pi, whose patch must neither
// fold nor show a seam.
#include <gtest/gtest.h>

#include "ricci/mesh/generate.h"
#include "spline/surface/fit_surface.h"

namespace {

TEST(FitSurfaceGenus4, OneConeWatertightWithoutFoldsAndASmallSeam) {
  ricci::GenerateOptions generate;
  generate.genus = 4;
  generate.target_faces = 6000;
  const ricci::Mesh mesh = ricci::generate_surface(generate);
  const spline::FittedSurface fitted = spline::fit_surface(mesh);
  EXPECT_EQ(fitted.input.genus, 4);
  EXPECT_TRUE(fitted.watertight);
  EXPECT_EQ(fitted.surface_dihedral.over_90_deg, 0);
  EXPECT_LT(fitted.fill_normal_jump_deg, 1.0);
  EXPECT_LT(fitted.edge_normal_jump_deg, 1.0);
  EXPECT_LT(fitted.fit_rms / fitted.bbox_diagonal, 1e-3);
}

}  // namespace
