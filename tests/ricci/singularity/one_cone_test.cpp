#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ricci/flow/flow.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/singularity/one_cone.h"

namespace {

ricci::Mesh shared_model(const std::string& relative) {
  return ricci::read_mesh(std::string(MSP_SHARED_MODELS) + "/" + relative);
}

// Runs the flow on the problem and checks the curvature reached its target everywhere.
ricci::FlowResult expect_flow_reaches_target(const ricci::OneConeProblem& problem) {
  ricci::FlowResult r = ricci::solve_one_cone_flow(problem, ricci::one_cone_flow_options());
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-9);
  return r;
}

TEST(OneCone, GenusTwoGetsOneConeOfCurvatureTwoPiChi) {
  auto mesh = shared_model("closed_g2/eight.off");
  auto problem = ricci::prepare_one_cone(mesh, 5);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::SingleCone);
  EXPECT_EQ(problem.genus, 2);
  EXPECT_GE(problem.mesh.valence(problem.mesh.vertex_handle(problem.cone)), 12u);
  EXPECT_DOUBLE_EQ(problem.targets.curvature[problem.cone], -4 * M_PI);
  auto r = expect_flow_reaches_target(problem);
  // Cone angle 2*pi - K = 2*pi*(2g - 1).
  EXPECT_NEAR(2 * M_PI - r.curvature[problem.cone], 6 * M_PI, 1e-9);
}

TEST(OneCone, GenusThreeConeAngleIsTenPi) {
  auto mesh = shared_model("closed_g3/genus3.off");
  auto problem = ricci::prepare_one_cone(mesh, 100);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::SingleCone);
  auto r = expect_flow_reaches_target(problem);
  EXPECT_NEAR(2 * M_PI - r.curvature[problem.cone], 10 * M_PI, 1e-9);
}

TEST(OneCone, GenusOneIsAFlatTorusWithoutCone) {
  auto problem = ricci::prepare_one_cone(shared_model("closed_g1/knot1.off"), 0);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::FlatTorus);
  EXPECT_EQ(problem.cone, -1);
  EXPECT_NEAR(problem.targets.curvature.cwiseAbs().maxCoeff(), 0.0, 0.0);
  expect_flow_reaches_target(problem);
}

TEST(OneCone, GenusZeroRemovesTheStarAndBendsTheNewBoundary) {
  auto mesh = shared_model("closed_g0/knight_decimated.off");
  auto problem = ricci::prepare_one_cone(mesh, 7);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::PuncturedSphere);
  EXPECT_EQ(problem.mesh.n_vertices() + 1, mesh.n_vertices());
  EXPECT_EQ(ricci::count_boundary_loops(problem.mesh), 1);
  EXPECT_NEAR(problem.targets.curvature.sum(), 2 * M_PI, 1e-12);
  expect_flow_reaches_target(problem);
}

TEST(OneCone, OpenSurfacePushesCurvatureToTheBoundary) {
  auto mesh = shared_model("open/head.off");
  auto problem = ricci::prepare_one_cone(mesh, -1);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::OpenSurface);
  EXPECT_EQ(problem.boundary_loops, 3);
  EXPECT_NEAR(problem.targets.curvature.sum(), 2 * M_PI * -1, 1e-9);  // chi = 2 - 0 - 3
  expect_flow_reaches_target(problem);
}

TEST(OneCone, VertexOutOfRangeIsRefused) {
  EXPECT_THROW((void)ricci::prepare_one_cone(shared_model("closed_g2/eight.off"), 100000),
               ricci::InvalidInputError);
}

}  // namespace
