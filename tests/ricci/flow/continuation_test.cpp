#include <gtest/gtest.h>

#include <memory>
#include <string>

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

TEST(Continuation, OneStageIsThePlainFlow) {
  const EightCone eight;
  const ricci::FlowResult one = eight.by_continuation(1);
  EXPECT_EQ(one.iterations, eight.direct.iterations);
  EXPECT_EQ(one.lengths, eight.direct.lengths);
}

}  // namespace
