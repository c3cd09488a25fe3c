#include <gtest/gtest.h>

#include <cmath>

#include <ricci/flow/flow.h>
#include <ricci/flow/targets.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <ricci/metric/curvature.h>

#include "ricci/test_meshes.h"
#include "test_paths.h"

namespace ricci {
namespace {


void expect_finite(const FlowResult& r) {
  EXPECT_TRUE(r.lengths.allFinite());
  EXPECT_TRUE(r.curvature.allFinite());
  EXPECT_TRUE(r.u.allFinite());
}

// E2 flat metric on genus 1: the acceptance check (≤ 15 Newton iterations, < 1e-10).
class FlatTorusTest : public ::testing::TestWithParam<const char*> {};

TEST_P(FlatTorusTest, ConvergesInFewNewtonIterations) {
  const std::string name = GetParam();
  const Mesh mesh =
      name == "procedural" ? testing::torus(40, 25) : read_mesh(msp_test::test_mesh(name));
  FlowOptions options;
  options.fall_back_to_other_metrics = true;
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::euclidean), options);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-10);
  EXPECT_LE(r.iterations, 15);
  expect_finite(r);
  // The reported curvature is the metric's own.
  const MeshTables t = build_mesh_tables(mesh);
  EXPECT_LT(vertex_curvature(t, r.lengths, Geometry::euclidean).cwiseAbs().maxCoeff(), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Genus1, FlatTorusTest,
                         ::testing::Values("procedural", "closed_g1/kitten_nf20k.off.gz",
                                           "closed_g1/rocker-arm.off.gz", "closed_g1/knot1.off.gz",
                                           "closed_g1/elk.off"));

TEST(Flow, InversiveDistanceConvergesOnKittenWithoutFallback) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g1/kitten_nf20k.off.gz"));
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::euclidean));
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(r.metric.scheme, Scheme::inversive_distance);
  EXPECT_TRUE(r.failed_attempts.empty());
  // Quadratic convergence: each of the last steps at least squares the error (up to a factor).
  const auto& h = r.error_history;
  ASSERT_GE(h.size(), 3u);
  EXPECT_LT(h[h.size() - 2], 10 * h[h.size() - 3] * h[h.size() - 3] + 1e-12);
}

// H2 uniformization of genus 2 and 3: K = 0 at every vertex, the faces carry the curvature.
class HyperbolicTest : public ::testing::TestWithParam<const char*> {};

TEST_P(HyperbolicTest, UniformizationSatisfiesGaussBonnet) {
  const Mesh mesh = read_mesh(msp_test::test_mesh(GetParam()));
  FlowOptions options;
  options.geometry = Geometry::hyperbolic;
  options.fall_back_to_other_metrics = true;
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::hyperbolic), options);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-10);
  const MeshTables t = build_mesh_tables(mesh);
  const double area = face_areas(t, r.lengths, Geometry::hyperbolic).sum();
  // Σ K - Σ A = 2πχ with K = 0: the hyperbolic area is -2πχ = 4π(g - 1).
  EXPECT_NEAR(r.curvature.sum() - area, 2 * M_PI * t.euler_characteristic, 1e-8);
  EXPECT_NEAR(area, -2 * M_PI * t.euler_characteristic, 1e-8);
  expect_finite(r);
}

INSTANTIATE_TEST_SUITE_P(Genus2And3, HyperbolicTest,
                         ::testing::Values("closed_g2/eight.off", "closed_g3/genus3.off.gz",
                                           "closed_g3/helmet.off"));

TEST(Flow, SphericalEitherConvergesOrSaysWhy) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g0/knight_decimated.off"));
  FlowOptions options;
  options.geometry = Geometry::spherical;
  options.tolerance = 1e-8;
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::spherical), options);
  expect_finite(r);
  if (r.converged()) {
    EXPECT_LT(r.max_error, 1e-8);
  } else {
    EXPECT_NE(r.message.find("S2"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("worst vertices"), std::string::npos);
  }
}

TEST(Flow, SphericalUniformizationOfAGenus0Model) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g0/bunny_npm_closed.off"));
  FlowOptions options;
  options.geometry = Geometry::spherical;
  options.tolerance = 1e-8;
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::spherical), options);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-8);
  const MeshTables t = build_mesh_tables(mesh);
  // Σ K + Σ A = 4π with K = 0: the triangles tile the unit sphere.
  EXPECT_NEAR(face_areas(t, r.lengths, Geometry::spherical).sum(), 4 * M_PI, 1e-6);
}

TEST(Flow, SphericalConvergesOnARoundSphere) {
  // The octahedral sphere's own metric is close to the uniformization: Newton gets there.
  const Mesh mesh = testing::sphere(3);
  FlowOptions options;
  options.geometry = Geometry::spherical;
  options.tolerance = 1e-8;
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::spherical), options);
  ASSERT_TRUE(r.converged()) << r.message;
  const MeshTables t = build_mesh_tables(mesh);
  EXPECT_NEAR(face_areas(t, r.lengths, Geometry::spherical).sum(), 4 * M_PI, 1e-6);
}

TEST(Flow, OpenSurfaceWithBoundaryCurvatureSpreadByLength) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("open/head.off"));
  FlowOptions options;
  options.fall_back_to_other_metrics = true;
  const Targets targets = boundary_target(mesh, BoundaryMode::spread_by_length);
  const MeshTables t = build_mesh_tables(mesh);
  EXPECT_NEAR(targets.curvature.sum(), 2 * M_PI * t.euler_characteristic, 1e-12);
  const FlowResult r = flow(mesh, targets, options);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-10);
}

TEST(Flow, ScalingTheMeshChangesNothingButTheScale) {
  Mesh mesh = read_mesh(msp_test::test_mesh("closed_g1/knot1.off.gz"));
  const FlowResult a = flow(mesh, uniform_target(mesh, Geometry::euclidean));
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * 1e3);
  const FlowResult b = flow(mesh, uniform_target(mesh, Geometry::euclidean));
  ASSERT_TRUE(a.converged() && b.converged());
  EXPECT_EQ(a.iterations, b.iterations);
  const MeshTables t = build_mesh_tables(mesh);
  const Eigen::MatrixX3d angles_a = corner_angles(t, a.lengths, Geometry::euclidean);
  const Eigen::MatrixX3d angles_b = corner_angles(t, b.lengths, Geometry::euclidean);
  EXPECT_LT((angles_a - angles_b).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(((b.lengths / 1e3 - a.lengths).array() / a.lengths.array()).abs().maxCoeff(), 1e-9);
}

TEST(Flow, GradientDescentReachesTheNewtonAnswer) {
  const Mesh mesh = testing::torus(12, 8);
  FlowOptions options;
  options.tolerance = 1e-9;
  const FlowResult newton = flow(mesh, uniform_target(mesh, Geometry::euclidean), options);
  options.method = FlowMethod::gradient_descent;
  const FlowResult gradient = flow(mesh, uniform_target(mesh, Geometry::euclidean), options);
  ASSERT_TRUE(newton.converged() && gradient.converged()) << gradient.message;
  EXPECT_GT(gradient.iterations, 10 * newton.iterations);
  EXPECT_LT(((gradient.lengths - newton.lengths).array() / newton.lengths.array()).abs().maxCoeff(), 1e-7);
}

TEST(Flow, ProgressIsReportedEveryNewtonIteration) {
  const Mesh mesh = testing::torus(12, 8);
  FlowOptions options;
  int calls = 0;
  options.progress = [&](const FlowProgress& p) {
    ++calls;
    EXPECT_EQ(p.iteration, calls);
  };
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::euclidean), options);
  EXPECT_EQ(calls, r.iterations);
}

TEST(Targets, GaussBonnetViolationsAreRefusedBeforeAnyWork) {
  const Mesh torus = testing::torus(10, 6);
  Targets bad{Eigen::VectorXd::Zero(torus.n_vertices())};
  bad.curvature[3] = 0.1;
  EXPECT_THROW((void)flow(torus, bad), InfeasibleTargetError);
  const Mesh eight = read_mesh(msp_test::test_mesh("closed_g2/eight.off"));
  EXPECT_THROW((void)uniform_target(eight, Geometry::euclidean), InfeasibleTargetError);
  // H2 needs Σ K̄ > 2πχ: a flat one-cone target has Σ K̄ = 2πχ exactly.
  FlowOptions h2;
  h2.geometry = Geometry::hyperbolic;
  try {
    (void)flow(eight, single_cone_target(eight, 0), h2);
    FAIL() << "expected InfeasibleTargetError";
  } catch (const InfeasibleTargetError& e) {
    EXPECT_NE(std::string(e.what()).find("2πχ"), std::string::npos) << e.what();
  }
  Targets cone = single_cone_target(eight, 0);
  cone.curvature[1] = 7.0;  // a cone angle below zero
  EXPECT_THROW((void)flow(eight, cone), InfeasibleTargetError);
}

TEST(Targets, ConeNeedingMoreValenceAsksForValenceModification) {
  const Mesh eight = read_mesh(msp_test::test_mesh("closed_g2/eight.off"));
  FlowOptions options;
  options.scheme = Scheme::circle_packing;
  try {
    (void)flow(eight, single_cone_target(eight, 0), options);
    FAIL() << "expected InfeasibleTargetError";
  } catch (const InfeasibleTargetError& e) {
    EXPECT_NE(std::string(e.what()).find("valence modification"), std::string::npos) << e.what();
  }
}

TEST(Targets, HelpersDistributeCurvature) {
  const Mesh eight = read_mesh(msp_test::test_mesh("closed_g2/eight.off"));
  const Targets cone = single_cone_target(eight, 5);
  EXPECT_DOUBLE_EQ(cone.curvature[5], -4 * M_PI);
  EXPECT_EQ(cone.curvature.cwiseAbs().sum(), 4 * M_PI);
  const Targets cones = cones_target(eight, {{1, -2 * M_PI}, {2, -2 * M_PI}});
  EXPECT_DOUBLE_EQ(cones.curvature.sum(), -4 * M_PI);
  EXPECT_THROW((void)cones_target(eight, {{1, 1.0}, {1, 1.0}}), InvalidInputError);
  EXPECT_THROW((void)single_cone_target(eight, -1), InvalidInputError);
  const Mesh head = read_mesh(msp_test::test_mesh("open/head.off"));
  const Targets loop = boundary_target(head, BoundaryMode::one_loop);
  const MeshTables t = build_mesh_tables(head);
  EXPECT_NEAR(loop.curvature.sum(), 2 * M_PI * t.euler_characteristic, 1e-12);
  int nonzero = 0;
  for (int v = 0; v < loop.curvature.size(); ++v) nonzero += loop.curvature[v] != 0;
  EXPECT_LT(nonzero, static_cast<int>(t.boundary_loops[0].size() + t.boundary_loops[1].size() +
                                      t.boundary_loops[2].size()));
  EXPECT_THROW((void)boundary_target(eight, BoundaryMode::spread_by_length), InvalidInputError);
}

TEST(Flow, UnreachableTargetReturnsAStatusNamingTheWorstVertices) {
  // elk's inversive-distance metric has no flat solution with intact triangles.
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g1/elk.off"));
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::euclidean));
  ASSERT_FALSE(r.converged());
  EXPECT_EQ(r.status, FlowStatus::triangle_inequality);
  EXPECT_NE(r.message.find("worst vertices"), std::string::npos);
  EXPECT_NE(r.message.find("valence modification"), std::string::npos);
  expect_finite(r);
}

TEST(Flow, IterationBudgetIsAStatus) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g1/knot1.off.gz"));
  FlowOptions options;
  options.max_newton_iterations = 1;
  const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::euclidean), options);
  EXPECT_EQ(r.status, FlowStatus::max_iterations);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LT(r.error_history[1], r.error_history[0]);
}

TEST(Flow, EverySolverGivesTheSameMetric) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g2/eight.off"));
  FlowOptions options;
  options.geometry = Geometry::hyperbolic;
  EdgeLengths reference;
  for (auto solver : {LinearSolver::eigen_ldlt, LinearSolver::eigen_llt,
                      LinearSolver::cholmod_supernodal, LinearSolver::cholmod_simplicial}) {
    options.solver = solver;
    const FlowResult r = flow(mesh, uniform_target(mesh, Geometry::hyperbolic), options);
    ASSERT_TRUE(r.converged()) << to_string(solver);
    EXPECT_EQ(r.solver, solver);
    if (reference.size() == 0) reference = r.lengths;
    EXPECT_LT((r.lengths - reference).cwiseAbs().maxCoeff(), 1e-9) << to_string(solver);
  }
}

}  // namespace
}  // namespace ricci

// parse_target: the specs of `msp flow --target` and the Python flow, and the refusals.
TEST(ParseTarget, NamesTheTargetsAndRefusesOtherSpecs) {
  const ricci::Mesh torus = ricci::make_torus(12, 8, 2.0, 0.7);
  const auto uniform = ricci::parse_target("uniform", torus, ricci::Geometry::euclidean);
  EXPECT_EQ(uniform.curvature, ricci::uniform_target(torus, ricci::Geometry::euclidean).curvature);
  const ricci::Mesh disk = ricci::make_disk(4, 12);
  EXPECT_EQ(ricci::parse_target("boundary-loop", disk, ricci::Geometry::euclidean).curvature,
            ricci::boundary_target(disk, ricci::BoundaryMode::one_loop).curvature);
  const ricci::Mesh sphere = ricci::make_icosphere(2);
  const auto cone = ricci::parse_target("cone:7", sphere, ricci::Geometry::euclidean);
  EXPECT_NEAR(cone.curvature[7], 4 * M_PI, 1e-12);
  EXPECT_NEAR(cone.curvature.sum(), 4 * M_PI, 1e-12);
  for (const char* bad : {"cone:", "cone:x", "cone:7x", "cones", ""}) {
    EXPECT_THROW((void)ricci::parse_target(bad, sphere, ricci::Geometry::euclidean),
                 ricci::InvalidInputError)
        << bad;
  }
  EXPECT_THROW((void)ricci::parse_target("cone:100000", sphere, ricci::Geometry::euclidean),
               ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::parse_target("uniform", sphere, ricci::Geometry::euclidean),
               ricci::InfeasibleTargetError);  // a sphere has no flat metric
}
