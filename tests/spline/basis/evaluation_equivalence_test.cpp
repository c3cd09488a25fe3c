// The shared, per-point-memoised evaluation of a triangle's DAG (simplex_spline.cpp: one pass over
// the nodes, knot offsets and knot-line sides computed once per point, Hessians only at the roots,
// a values-only pass) gives bit for bit the numbers of each function evaluated on its own DAG,
// also at knots and on knot lines where the half-open rule and the exact predicates decide.
#include <gtest/gtest.h>

#include <random>

#include "spline/basis/planar_fixtures.h"
#include "spline/basis/triangle_basis.h"
#include "spline/knots/knot_cloud.h"

namespace spline {
namespace {

// Random points over the hull's box, every knot, and points on lines through knot pairs.
std::vector<Eigen::Vector2d> probe_points(const TriangleBasis& basis, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector2d lo = basis.box_min(), hi = basis.box_max();
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 20; ++k) {
    points.push_back(lo + Eigen::Vector2d(unit(rng), unit(rng)).cwiseProduct(hi - lo));
  }
  std::vector<Eigen::Vector2d> knots;
  for (int i = 0; i < basis.size(); ++i) {
    for (const Eigen::Vector2d& x : basis.knot_set(i)) knots.push_back(x);
  }
  for (std::size_t a = 0; a < knots.size(); a += 3) {
    points.push_back(knots[a]);
    const std::size_t b = (a * 7 + 5) % knots.size();
    points.push_back(0.5 * (knots[a] + knots[b]));  // on the knot line a-b (rounded: near it)
    points.push_back(knots[a] + 0.25 * (knots[b] - knots[a]));
  }
  return points;
}

TEST(EvaluationEquivalence, SharedDagMatchesEachFunctionOnItsOwn) {
  for (int n = 2; n <= 5; ++n) {
    const PlanarTriangulation t = testing::perturbed_grid(3, 0.3, 40 + n);
    const std::vector<KnotCloud> clouds = make_knot_clouds(t, n);
    std::mt19937 rng(n);
    int compared = 0, non_zero = 0;
    for (std::size_t i : {std::size_t{0}, t.triangles.size() / 2}) {
      const Eigen::Vector3i& tri = t.triangles[i];
      const TriangleBasis basis(clouds[tri[0]], clouds[tri[1]], clouds[tri[2]]);
      std::vector<Jet> jets;
      std::vector<double> values;
      SimplexSplineDag::Scratch jet_scratch, value_scratch;
      for (const Eigen::Vector2d& u : probe_points(basis, rng)) {
        for (const TieBreak& tie : {TieBreak{}, TieBreak{Eigen::Vector2d(-0.3, 1.0)}}) {
          basis.evaluate(u, tie, jets, jet_scratch);
          basis.evaluate_values(u, tie, values, value_scratch);
          for (int f = 0; f < basis.size(); ++f) {
            const Jet alone = simplex_spline(basis.knot_set(f), u, tie);
            const double s = basis.scale(f);
            ASSERT_EQ(jets[f].value, s * alone.value) << "n " << n << " function " << f;
            ASSERT_EQ(values[f], jets[f].value) << "n " << n << " function " << f;
            for (int a = 0; a < 2; ++a) ASSERT_EQ(jets[f].gradient[a], s * alone.gradient[a]);
            for (int a = 0; a < 3; ++a) ASSERT_EQ(jets[f].hessian[a], s * alone.hessian[a]);
            ++compared;
            non_zero += jets[f].value != 0.0;
          }
        }
      }
    }
    EXPECT_GT(compared, 500);
    EXPECT_GT(non_zero, compared / 10);  // the probes reach the supports
  }
}

}  // namespace
}  // namespace spline
