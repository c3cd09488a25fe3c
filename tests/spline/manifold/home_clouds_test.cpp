// ManifoldSplineSpace from given home clouds (the spline file's constructor): the clouds of a
// built space give a space evaluating bit for bit like it; clouds that break the rule's
// guarantees (wrong count, degree, start, a knot beyond half the smallest inradius) are refused.
#include <gtest/gtest.h>

#include <cstring>

#include "ricci/mesh/errors.h"
#include "spline/manifold/manifold_fixtures.h"

namespace spline {
namespace {

using testing::small_atlas;
using testing::small_space;

std::vector<KnotCloud> clouds_of(const ManifoldSplineSpace& space, std::size_t vertices) {
  std::vector<KnotCloud> clouds(vertices);
  for (std::size_t v = 0; v < vertices; ++v) clouds[v] = space.home_cloud(static_cast<int>(v));
  return clouds;
}

TEST(HomeClouds, GivenCloudsEvaluateBitForBit) {
  const auto& a = small_atlas("genus2.off", 300);
  const auto space = small_space("genus2.off", 3, 300);
  const std::size_t vertices = a.problem.mesh.n_vertices();
  const ManifoldSplineSpace given(a.problem.mesh, a.atlas, 3, clouds_of(*space, vertices));
  ASSERT_EQ(given.function_count(), space->function_count());
  for (int face : space->domain_faces()) {
    const DomainPoint point{face, Eigen::Vector3d(0.2, 0.3, 0.5)};
    const auto x = space->evaluate_basis(point);
    const auto y = given.evaluate_basis(point);
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(x[i].function, y[i].function);
      EXPECT_EQ(std::memcmp(&x[i].jet.value, &y[i].jet.value, sizeof(double)), 0);
      EXPECT_TRUE(x[i].jet.gradient == y[i].jet.gradient);
    }
  }
}

TEST(HomeClouds, CloudsBreakingTheRuleAreRefused) {
  const auto& a = small_atlas("genus2.off", 300);
  const auto space = small_space("genus2.off", 3, 300);
  const ricci::Mesh& mesh = a.problem.mesh;
  const auto good = clouds_of(*space, mesh.n_vertices());
  int v = 0;  // a vertex of the domain (it has a cloud)
  while (good[v].knots.empty()) ++v;
  auto clouds = good;
  clouds.pop_back();
  EXPECT_THROW(ManifoldSplineSpace(mesh, a.atlas, 3, clouds), ricci::InvalidInputError);
  EXPECT_THROW(ManifoldSplineSpace(mesh, a.atlas, 2, good), ricci::InvalidInputError);
  clouds = good;
  clouds[v].knots[0].x() += 1e-12;
  EXPECT_THROW(ManifoldSplineSpace(mesh, a.atlas, 3, clouds), ricci::InvalidInputError);
  clouds = good;
  clouds[v].knots[1] = clouds[v].knots[0] + 10.0 * (clouds[v].knots[1] - clouds[v].knots[0]);
  EXPECT_THROW(ManifoldSplineSpace(mesh, a.atlas, 3, clouds), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
