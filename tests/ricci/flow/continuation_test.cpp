#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "ricci/flow/continuation.h"
#include "ricci/flow/linear_solver.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/curvature.h"
#include "ricci/singularity/one_cone.h"
#include "test_paths.h"

namespace {

// The 6 pi cone of the eight at vertex 5, its cone-tangent metric and the direct flow from it.
struct EightCone {
  ricci::OneConeProblem problem =
      ricci::prepare_one_cone(ricci::read_mesh(msp_test::test_mesh("closed_g2/eight.off")), 5);
  ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  ricci::CirclePackingMetric initial = ricci::cone_tangent_metric(
      t, ricci::mesh_edge_lengths(problem.mesh), problem.cone, 3, ricci::RadiusInit::mean);
  ricci::FlowResult direct = ricci::flow(t, initial, problem.targets, ricci::one_cone_flow_options());

  [[nodiscard]] ricci::FlowResult by_continuation(int stages) const {
    return ricci::flow_by_continuation(t, initial, problem.targets, ricci::one_cone_flow_options(),
                                       ricci::ContinuationOptions{stages});
  }
};

// The energy is convex, so walking the target in stages ends at the direct flow's metric.
TEST(Continuation, EndsAtTheDirectFlowsMetric) {
  const EightCone eight;
  const ricci::OneConeProblem& problem = eight.problem;
  const ricci::FlowResult& direct = eight.direct;
  const ricci::FlowResult walked = eight.by_continuation(4);
  ASSERT_TRUE(direct.converged()) << direct.message;
  ASSERT_TRUE(walked.converged()) << walked.message;
  EXPECT_LT(walked.max_error, 1e-10);
  EXPECT_EQ(walked.target, problem.targets.curvature);
  EXPECT_GT(walked.iterations, direct.iterations / 2);  // summed over the stages
  EXPECT_LT((walked.lengths - direct.lengths).cwiseAbs().maxCoeff(), 1e-8 * direct.lengths.maxCoeff());
  const Eigen::VectorXd k =
      ricci::vertex_curvature(eight.t, walked.lengths, ricci::Geometry::euclidean);
  EXPECT_LT((k - problem.targets.curvature).cwiseAbs().maxCoeff(), 1e-9);
}

// The stages share one symbolic analysis (FlowOptions::factorization_cache), and a shared
// analysis changes nothing: the plain flow with a cache that already holds it gives the same
// metric bit for bit.
TEST(Continuation, StagesShareOneSymbolicAnalysis) {
  const EightCone eight;
  ricci::FlowOptions options = ricci::one_cone_flow_options();
  options.factorization_cache = std::make_shared<ricci::FactorizationCache>();
  const ricci::FlowResult walked = ricci::flow_by_continuation(
      eight.t, eight.initial, eight.problem.targets, options, ricci::ContinuationOptions{4});
  ASSERT_TRUE(walked.converged()) << walked.message;
  EXPECT_EQ(options.factorization_cache->analyses(), 1);
  EXPECT_EQ(options.factorization_cache->reuses(), 3);
  const ricci::FlowResult again = ricci::flow(eight.t, eight.initial, eight.problem.targets, options);
  EXPECT_EQ(options.factorization_cache->analyses(), 1);
  EXPECT_EQ(again.lengths, eight.direct.lengths);
  EXPECT_EQ(again.timings.analysis, 0.0);
}

TEST(FactorizationCache, AnalysesAgainForAnotherPattern) {
  ricci::FactorizationCache cache;
  Eigen::SparseMatrix<double> a(3, 3), b(3, 3);
  a.insert(0, 0) = 2;
  a.insert(1, 1) = 2;
  a.insert(2, 2) = 2;
  a.insert(1, 0) = -1;
  a.makeCompressed();
  b = a;
  b.insert(2, 1) = -1;
  b.makeCompressed();
  double seconds = 0;
  const auto first = cache.get(ricci::LinearSolver::eigen_llt, a, seconds);
  EXPECT_EQ(cache.get(ricci::LinearSolver::eigen_llt, a, seconds), first);
  const auto other = cache.get(ricci::LinearSolver::eigen_llt, b, seconds);
  EXPECT_NE(other, first);
  EXPECT_NE(cache.get(ricci::LinearSolver::eigen_ldlt, b, seconds), other);
  EXPECT_EQ(cache.analyses(), 3);
  EXPECT_EQ(cache.reuses(), 1);
  ASSERT_TRUE(other->factorize(b));
  const Eigen::Vector3d x = other->solve(Eigen::Vector3d(1, 0, 1));
  EXPECT_LT((b.selfadjointView<Eigen::Lower>() * x - Eigen::Vector3d(1, 0, 1)).norm(), 1e-14);
}

// The lower triangle of the n x n grid graph's Laplacian plus the identity, its vertices
// relabelled by `label` (vertex (i, j) becomes label[i n + j]).
Eigen::SparseMatrix<double> grid_matrix(int n, const std::vector<int>& label) {
  std::vector<Eigen::Triplet<double>> t;
  const auto add = [&](int a, int b) {
    const int x = label[static_cast<size_t>(a)], y = label[static_cast<size_t>(b)];
    t.emplace_back(std::max(x, y), std::min(x, y), -1.0);
    t.emplace_back(x, x, 1.0);
    t.emplace_back(y, y, 1.0);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int v = label[static_cast<size_t>(i * n + j)];
      t.emplace_back(v, v, 1.0);
      if (j + 1 < n) add(i * n + j, i * n + j + 1);
      if (i + 1 < n) add(i * n + j, (i + 1) * n + j);
    }
  }
  Eigen::SparseMatrix<double> m(n * n, n * n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

// Three patterns of one size for the cache: the 40 x 40 grid, the grid with one more edge (a
// diagonal of the first square: a flip, which the grid's ordering fits) and the grid with its
// vertices relabelled (the grid's ordering is arbitrary for it); a cache, and whether a
// factorisation from it solves its system.
class CachedOrdering : public ::testing::Test {
 protected:
  static constexpr int n = 40;

  CachedOrdering()
      : grid(grid_matrix(n, labels(1))), relabelled(grid_matrix(n, labels(613))) {
    grid_and_edge = grid;
    grid_and_edge.insert(n + 1, 0) = -0.5;
    grid_and_edge.coeffRef(0, 0) += 0.5;
    grid_and_edge.coeffRef(n + 1, n + 1) += 0.5;
    grid_and_edge.makeCompressed();
  }

  // Vertex k labelled (k * step) mod n^2 (613 is prime to 1600: a permutation).
  static std::vector<int> labels(size_t step) {
    std::vector<int> label(static_cast<size_t>(n * n));
    for (size_t k = 0; k < label.size(); ++k) {
      label[k] = static_cast<int>((k * step) % label.size());
    }
    return label;
  }

  bool solves(const Eigen::SparseMatrix<double>& m,
              ricci::OrderingReuse reuse = ricci::OrderingReuse::until_rejected) {
    const auto f = cache.get(ricci::LinearSolver::cholmod_supernodal, m, seconds, reuse);
    if (!f->factorize(m)) return false;
    const Eigen::VectorXd x = f->solve(rhs);
    return (m.selfadjointView<Eigen::Lower>() * x - rhs).norm() < 1e-10 * rhs.norm();
  }

  const Eigen::SparseMatrix<double> grid, relabelled;
  Eigen::SparseMatrix<double> grid_and_edge;
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n * n, -1.0, 1.0);
  ricci::FactorizationCache cache;
  double seconds = 0;
};

// A new pattern of the same size takes the cached ordering when it fits (one more edge), is
// ordered afresh when it does not (the vertices relabelled), and after that rejection the
// cache no longer tries: every later pattern is ordered afresh. Each factorisation solves its
// system either way.
TEST_F(CachedOrdering, StopsOfferingTheOrderingOnceRejected) {
  EXPECT_TRUE(solves(grid));
  EXPECT_TRUE(solves(grid_and_edge));
  EXPECT_EQ(cache.orderings_reused(), 1);
  EXPECT_EQ(cache.orderings_rejected(), 0);
  EXPECT_TRUE(solves(relabelled));
  EXPECT_EQ(cache.orderings_reused(), 1);
  EXPECT_EQ(cache.orderings_rejected(), 1);
  EXPECT_TRUE(solves(grid));
  EXPECT_TRUE(solves(grid_and_edge));
  EXPECT_EQ(cache.orderings_reused(), 1);
  EXPECT_EQ(cache.orderings_rejected(), 1);
  EXPECT_EQ(cache.analyses(), 5);
}

// The caller's word (OrderingReuse) overrides the cache's rule: `offer` tries the cached
// ordering after a rejection, `skip` orders afresh a pattern the ordering would fit.
TEST_F(CachedOrdering, CallerDecidesWhetherTheOrderingIsOffered) {
  using ricci::OrderingReuse;
  EXPECT_TRUE(solves(grid, OrderingReuse::until_rejected));
  EXPECT_TRUE(solves(relabelled, OrderingReuse::until_rejected));
  EXPECT_EQ(cache.orderings_rejected(), 1);
  EXPECT_TRUE(solves(grid, OrderingReuse::skip));  // fresh: nothing tried
  EXPECT_EQ(cache.orderings_reused(), 0);
  EXPECT_EQ(cache.orderings_rejected(), 1);
  EXPECT_TRUE(solves(grid_and_edge, OrderingReuse::offer));  // tried after the rejection: fits
  EXPECT_EQ(cache.orderings_reused(), 1);
  EXPECT_TRUE(solves(grid, OrderingReuse::skip));
  EXPECT_EQ(cache.orderings_reused(), 1);
  EXPECT_EQ(cache.orderings_rejected(), 1);
  EXPECT_EQ(cache.analyses(), 5);
}

TEST(Continuation, OneStageIsThePlainFlow) {
  const EightCone eight;
  const ricci::FlowResult one = eight.by_continuation(1);
  EXPECT_EQ(one.iterations, eight.direct.iterations);
  EXPECT_EQ(one.lengths, eight.direct.lengths);
}

}  // namespace
