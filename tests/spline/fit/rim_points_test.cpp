// fit_scan leaves out the points where the basis is no partition of unity (next to the domain's
// rim, where the functions of the faces beyond it are missing): fitted there, they inflated the
// control points and folded the surface two rings in from an open boundary, where the fill's
// seam and the surface shown begin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/io.h"
#include "spline/fill/hole_fill.h"
#include "spline/fit/fit.h"
#include "test_paths.h"

namespace spline {
namespace {

const ScanFitResult& genus2_hole() {
  static const ScanFitResult fit = [] {
    ScanFitOptions options;
    options.domain_faces = 2000;
    return fit_scan(ricci::read_mesh(msp_test::bundled_model("genus2_hole.off")),
                    options);
  }();
  return fit;
}

TEST(FitScanRim, EveryFittedPointHasAPartitionOfUnity) {
  const ScanFitResult& fit = genus2_hole();
  const auto& space = *fit.spline.space;
  int fitted = 0;
  for (const DomainPoint& p : fit.vertex_parameters) {
    if (p.face < 0) continue;
    double sum = 0.0;
    for (const auto& s : space.evaluate_basis(p, -1, {}, BasisDerivatives::none))
      sum += s.jet.value;
    EXPECT_NEAR(sum, 1.0, 1e-9) << "face " << p.face;
    ++fitted;
  }
  // The band left out is thin: most of the scan's vertices are fitted. With the boundary
  // collar (on by default) the band lies in the collar, beyond the boundary: every scan vertex
  // next to the boundary is fitted too.
  EXPECT_GT(fitted, static_cast<int>(0.9 * fit.vertex_parameters.size()));
  EXPECT_FALSE(fit.collar_faces.empty());
  EXPECT_TRUE(fit.collar_refused.empty()) << fit.collar_refused;
}

TEST(FitScanRim, SurfaceNextToAnOpenBoundaryDoesNotFold) {
  // Rings 2 and 3 from the boundary: the first ones the fill's grown rim leaves to the surface.
  // Measured: the normal turns by at most 0.66 degrees within 1/100 of an edge there (120
  // degrees when the rim's points were fitted).
  const ScanFitResult& fit = genus2_hole();
  const auto& space = *fit.spline.space;
  const std::vector<int> rings = domain_rim_rings(space);
  double largest = 0.0;
  int faces = 0;
  for (int d = 0; d < space.domain_face_count(); ++d) {
    if (rings[d] != 2 && rings[d] != 3) continue;
    largest = std::max(largest, max_normal_step_deg(fit.spline, space.domain_faces()[d]));
    ++faces;
  }
  EXPECT_GT(faces, 20);
  EXPECT_LT(largest, 5.0);
}

}  // namespace
}  // namespace spline
