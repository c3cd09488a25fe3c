#include <gtest/gtest.h>

#include <string>

#include "ricci/flow/continuation.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/curvature.h"
#include "ricci/singularity/one_cone.h"

namespace {

// The energy is convex, so walking the target in stages ends at the direct flow's metric.
TEST(Continuation, EndsAtTheDirectFlowsMetric) {
  const ricci::Mesh mesh = ricci::read_mesh(std::string(MSP_SHARED_MODELS) + "/closed_g2/eight.off");
  const ricci::OneConeProblem problem = ricci::prepare_one_cone(mesh, 5);
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const ricci::CirclePackingMetric initial =
      ricci::cone_tangent_metric(t, ricci::mesh_edge_lengths(problem.mesh), problem.cone, 3, ricci::RadiusInit::Mean);
  const ricci::FlowResult direct = ricci::flow(t, initial, problem.targets, ricci::one_cone_flow_options());
  ricci::ContinuationOptions stages;
  stages.stages = 4;
  const ricci::FlowResult walked =
      ricci::flow_by_continuation(t, initial, problem.targets, ricci::one_cone_flow_options(), stages);
  ASSERT_TRUE(direct.converged()) << direct.message;
  ASSERT_TRUE(walked.converged()) << walked.message;
  EXPECT_LT(walked.max_error, 1e-10);
  EXPECT_EQ(walked.target, problem.targets.curvature);
  EXPECT_GT(walked.iterations, direct.iterations / 2);  // summed over the stages
  EXPECT_LT((walked.lengths - direct.lengths).cwiseAbs().maxCoeff(), 1e-8 * direct.lengths.maxCoeff());
  const Eigen::VectorXd k = ricci::vertex_curvature(t, walked.lengths, ricci::Geometry::Euclidean);
  EXPECT_LT((k - problem.targets.curvature).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Continuation, OneStageIsThePlainFlow) {
  const ricci::Mesh mesh = ricci::read_mesh(std::string(MSP_SHARED_MODELS) + "/closed_g2/eight.off");
  const ricci::OneConeProblem problem = ricci::prepare_one_cone(mesh, 5);
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const ricci::CirclePackingMetric initial =
      ricci::cone_tangent_metric(t, ricci::mesh_edge_lengths(problem.mesh), problem.cone, 3, ricci::RadiusInit::Mean);
  const ricci::FlowResult direct = ricci::flow(t, initial, problem.targets, ricci::one_cone_flow_options());
  const ricci::FlowResult one = ricci::flow_by_continuation(t, initial, problem.targets, ricci::one_cone_flow_options(),
                                                            ricci::ContinuationOptions{1});
  EXPECT_EQ(one.iterations, direct.iterations);
  EXPECT_EQ(one.lengths, direct.lengths);
}

}  // namespace
