// The manifold spline over a genus-8 one-cone atlas (a cone of 30 pi, next to which faces are
// ~1e-13 of the central chart's coordinates): the faces next to the cone keep their functions
// (the atlas lays them out in frames of their own), the basis is a partition of unity away from
// the hole, and every chart holding a face's neighbourhood sees the same surface there.
#include <gtest/gtest.h>

#include <memory>

#include "ricci/pipeline/one_cone_atlas.h"
#include "ricci/test_meshes.h"
#include "spline/manifold/manifold_space.h"

namespace spline {
namespace {

TEST(LargeConeSpace, Genus8KeepsTheFacesNextToTheConeAndOneSurface) {
  const ricci::OneConeAtlasResult atlas = ricci::testing::genus8_fit_atlas();
  const auto space = std::make_shared<const ManifoldSplineSpace>(atlas.problem.mesh, atlas.atlas);
  int atlas_domain = 0;
  for (char in : atlas.atlas.in_domain) atlas_domain += in != 0;
  EXPECT_EQ(space->excluded_faces(), 0);
  EXPECT_EQ(space->domain_face_count(), atlas_domain);

  std::srand(3u);
  const ManifoldSpline spline{space, Eigen::MatrixX3d::Random(space->function_count(), 3)};
  const Eigen::Vector3d centroid = Eigen::Vector3d::Constant(1.0 / 3.0);
  int interior = 0, compared = 0;
  double worst_sum = 0.0, worst_gap = 0.0;
  for (int f : space->domain_faces()) {
    bool next_to_hole = false;
    for (int g : space->reaching_faces(f)) {
      for (int k = 0; k < 3; ++k) next_to_hole |= !space->in_domain(space->neighbour(g, k));
    }
    if (!next_to_hole) {
      double sum = 0.0;
      for (const auto& s : space->evaluate_basis({f, centroid})) sum += s.jet.value;
      worst_sum = std::max(worst_sum, std::abs(sum - 1.0));
      ++interior;
    }
    const int a = space->chart_of(f);
    const Eigen::Vector3d here = spline.evaluate({f, centroid}, a).position;
    for (int b = 0; b < static_cast<int>(space->atlas().charts.size()); ++b) {
      if (b == a || !space->holds_neighbourhood(b, f)) continue;
      worst_gap = std::max(worst_gap, (spline.evaluate({f, centroid}, b).position - here).norm());
      ++compared;
    }
  }
  EXPECT_GT(interior, space->domain_face_count() / 2);
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst_sum, 1e-9);
  // Control points of size ~1: the charts agree to rounding of the knots' transforms.
  EXPECT_LT(worst_gap, 1e-7);
}

}  // namespace
}  // namespace spline
