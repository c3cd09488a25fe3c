// Open scans whose boundary the surface used to miss, fitted with the defaults: the output's
// boundary within 0.5% of the diagonal of the input's (Hausdorff, both ways), no fold, the
// surface near the scan both ways. eight_hole.off has a hexagonal hole whose corners a fit to
// the points alone rounded off (2.5% of the diagonal); beetle.off's eleven boundary loops are a
// scan's jagged cuts (0.62%), which a heavy pull on the boundary would fold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/io.h"
#include "spline/surface/fit_surface.h"
#include "test_paths.h"

namespace spline {
namespace {

class OpenBoundary : public ::testing::TestWithParam<std::string> {};

TEST_P(OpenBoundary, ReachedWithoutFolds) {
  const ricci::Mesh scan = ricci::read_mesh(msp_test::test_mesh(GetParam()));
  const FittedSurface r = fit_surface(scan);
  const double diag = r.bbox_diagonal;
  EXPECT_TRUE(r.collar_refused.empty()) << r.collar_refused;
  EXPECT_TRUE(r.watertight);
  EXPECT_GE(r.delivered.boundary_hausdorff, 0.0);
  EXPECT_LT(r.delivered.boundary_hausdorff, 0.005 * diag);
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0);
  EXPECT_EQ(r.fit_points, static_cast<int>(scan.n_vertices()));
  EXPECT_LT(r.fit_rms, 0.002 * diag);
  EXPECT_LT(r.fit_max, 0.02 * diag);
  EXPECT_LT(r.delivered.surface_to_scan_max, 0.02 * diag);
}

INSTANTIATE_TEST_SUITE_P(Scans, OpenBoundary,
                         ::testing::Values("open/eight_hole.off", "open/beetle.off.gz"),
                         [](const auto& info) {
                           return info.param.substr(5, info.param.find('.') - 5);
                         });

// mech-holes-shark.off's outer boundary is a zigzag of 46 one-triangle teeth, 1.35% of the
// diagonal high, narrower than a domain edge: moving and splitting the simplified boundary left
// it tangled (0.76% away), pulled onto the scan's the spline folded (108 fold edges), and without
// the pull the output boundary was 1.43% away. With the band along that loop rebuilt from the
// scan's own boundary vertices (follow_boundary, rebuild_boundary_bands) the pull is kept and
// the boundary reached (0.441% measured). Its fold round keeps the raised smoothing off the band
// (open_fold_floor): spread there from folds a ring inside, it left a tooth tip 0.504% away.
TEST(OpenBoundary, AZigzagBoundaryIsReachedThroughItsRebuiltBand) {
  const ricci::Mesh scan = ricci::read_mesh(msp_test::test_mesh("open/mech-holes-shark.off.gz"));
  const FittedSurface r = fit_surface(scan);
  const double diag = r.bbox_diagonal;
  EXPECT_EQ(r.boundary_follow.loops_rebuilt, 1);
  EXPECT_FALSE(r.boundary_curve_dropped);
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0);
  EXPECT_LT(r.delivered.boundary_hausdorff, 0.005 * diag);
  EXPECT_LT(r.fit_rms, 0.002 * diag);
  EXPECT_LT(r.fit_max, 0.02 * diag);
  EXPECT_LT(r.delivered.surface_to_scan_max, 0.02 * diag);
}

// lion.off folds inside (its mane: 40 fold edges with the boundary curve pulled) and next to its
// boundary; the fold rounds smooth there, up to the RMS goal, and keep the pull: 0 folds and the
// boundary within the 0.5% (0.495% measured; 0.774% and 2 folds when the band was left
// out and the pull dropped).
TEST(OpenBoundary, FoldsOfAnOpenScanAreSmoothedAndItsBoundaryReached) {
  const ricci::Mesh scan = ricci::read_mesh(msp_test::test_mesh("open/lion.off.gz"));
  const FittedSurface r = fit_surface(scan);
  const double diag = r.bbox_diagonal;
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0);
  EXPECT_FALSE(r.boundary_curve_dropped);
  EXPECT_LT(r.delivered.boundary_hausdorff, 0.005 * diag);
  EXPECT_LT(r.fit_rms, 0.002 * diag);
  EXPECT_LT(r.fit_max, 0.02 * diag);
  EXPECT_LT(r.delivered.surface_to_scan_max, 0.02 * diag);
}

// A scan with one triangle missing (a hole of three edges narrower than small_hole_diameter;
// ChineseDragon-10kv.off has two): the hole is capped before the fit, its edges are left out of
// the boundary comparison, and the hexagonal hole is still reached.
TEST(OpenBoundary, AMissingTriangleIsCappedAndTheRealHoleStillReached) {
  const ricci::Mesh whole = ricci::read_mesh(msp_test::test_mesh("open/eight_hole.off"));
  const ricci::VertexFaceArrays a = ricci::to_arrays(whole);
  // The narrowest face off the hexagonal hole's rim.
  Eigen::Index removed = -1;
  double narrowest = INFINITY;
  for (Eigen::Index f = 0; f < a.F.rows(); ++f) {
    double width = 0.0;
    bool on_boundary = false;
    for (int k = 0; k < 3; ++k) {
      on_boundary |= whole.is_boundary(whole.vertex_handle(a.F(f, k)));
      width = std::max(width, (a.V.row(a.F(f, k)) - a.V.row(a.F(f, (k + 1) % 3))).norm());
    }
    if (!on_boundary && width < narrowest) {
      narrowest = width;
      removed = f;
    }
  }
  ASSERT_GE(removed, 0);
  Eigen::MatrixX3i F(a.F.rows() - 1, 3);
  F << a.F.topRows(removed), a.F.bottomRows(a.F.rows() - removed - 1);
  const ricci::Mesh scan = ricci::from_arrays(a.V, F);
  ASSERT_EQ(ricci::surface_topology(scan).boundary_loops, 2);

  // The test mesh is coarse: its triangles are 3.5-7% of the diagonal wide, its hexagonal hole
  // 8.7% (a scan's missing triangles, as on ChineseDragon-10kv.off, are below the default 0.2%).
  FitSurfaceOptions options;
  options.small_hole_diameter = 0.05;
  const FittedSurface r = fit_surface(scan, options);
  EXPECT_EQ(r.capped_holes, 1);
  EXPECT_GT(r.capped_hole_diameter, 0.0);
  EXPECT_LT(r.capped_hole_diameter, 0.05);
  EXPECT_EQ(r.input.boundary_loops, 1);
  EXPECT_EQ(r.delivered.scan_boundary_edges_left_out, 3);
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0);
  EXPECT_GE(r.delivered.boundary_hausdorff, 0.0);
  EXPECT_LT(r.delivered.boundary_hausdorff, 0.005 * r.bbox_diagonal);
  EXPECT_EQ(r.fit_points, static_cast<int>(scan.n_vertices()));
  EXPECT_LT(r.fit_max, 0.02 * r.bbox_diagonal);
  EXPECT_LT(r.delivered.surface_to_scan_max, 0.02 * r.bbox_diagonal);
}

}  // namespace
}  // namespace spline
