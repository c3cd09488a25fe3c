#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ricci/flow/flow.h"
#include "ricci/metric/curvature.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/neighbourhoods.h"
#include "ricci/mesh/primitives.h"
#include "ricci/singularity/one_cone.h"
#include "test_paths.h"

namespace {

ricci::Mesh read_test_mesh(const std::string& relative) {
  return ricci::read_mesh(msp_test::test_mesh(relative));
}

// Runs the flow on the problem and checks the curvature reached its target everywhere.
ricci::FlowResult expect_flow_reaches_target(const ricci::OneConeProblem& problem) {
  ricci::FlowResult r = ricci::solve_one_cone_flow(problem, ricci::one_cone_flow_options());
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-9);
  return r;
}

TEST(OneCone, GenusTwoGetsOneConeOfCurvatureTwoPiChi) {
  auto mesh = read_test_mesh("closed_g2/eight.off");
  auto problem = ricci::prepare_one_cone(mesh, 5);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::SingleCone);
  EXPECT_EQ(problem.genus, 2);
  EXPECT_GE(problem.mesh.valence(problem.mesh.vertex_handle(problem.cone)), 12u);
  EXPECT_DOUBLE_EQ(problem.targets.curvature[problem.cone], -4 * M_PI);
  auto r = expect_flow_reaches_target(problem);
  // Cone angle 2*pi - K = 2*pi*(2g - 1).
  EXPECT_NEAR(2 * M_PI - r.curvature[problem.cone], 6 * M_PI, 1e-9);
}

// The thin-handle flags computed earlier (beside the choice) prepare the problem the function
// prepares from the mesh alone: with every face wrapped (a tube three edges around) and none.
TEST(OneCone, GivenNonDiskFacesPrepareTheSameProblem) {
  const ricci::Mesh thin = ricci::make_torus(24, 3, 2.0, 0.5);
  const auto own = ricci::prepare_one_cone(thin, 0);
  const auto given =
      ricci::prepare_one_cone(thin, 0, {}, ricci::non_disk_face_neighbourhoods(thin));
  EXPECT_GT(own.subdivisions, 0);
  EXPECT_EQ(given.subdivisions, own.subdivisions);
  EXPECT_EQ(given.mesh.n_faces(), own.mesh.n_faces());
  EXPECT_EQ(given.input_vertex, own.input_vertex);
  EXPECT_EQ(given.targets.curvature, own.targets.curvature);
  const auto eight = read_test_mesh("closed_g2/eight.off");
  const auto cone = ricci::prepare_one_cone(eight, 5);
  const auto flagged =
      ricci::prepare_one_cone(eight, 5, {}, ricci::non_disk_face_neighbourhoods(eight));
  EXPECT_EQ(flagged.subdivisions, 0);
  EXPECT_EQ(flagged.cone, cone.cone);
  EXPECT_EQ(flagged.valence_splits, cone.valence_splits);
  EXPECT_EQ(flagged.mesh.n_faces(), cone.mesh.n_faces());
  EXPECT_EQ(flagged.targets.curvature, cone.targets.curvature);
  EXPECT_THROW((void)ricci::prepare_one_cone(eight, 5, {}, std::vector<char>(3, 0)),
               ricci::InvalidInputError);
}

TEST(OneCone, GenusThreeConeAngleIsTenPi) {
  auto mesh = read_test_mesh("closed_g3/genus3.off.gz");
  auto problem = ricci::prepare_one_cone(mesh, 100);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::SingleCone);
  auto r = expect_flow_reaches_target(problem);
  EXPECT_NEAR(2 * M_PI - r.curvature[problem.cone], 10 * M_PI, 1e-9);
}

// The first single-cone metric: Thurston's angles of the mesh except tangent circles on every
// edge within 3 rings of the cone; on genus3_100k it is the one that converges (bench one-cone).
TEST(OneCone, ConeTangentMetricIsTangentNearTheConeAndTheMeshsPackingElsewhere) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("closed_g3/genus3.off.gz"), 100);
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const ricci::EdgeLengths lengths = ricci::mesh_edge_lengths(problem.mesh);
  const auto packing =
      ricci::initial_metric(t, lengths, ricci::Geometry::euclidean, ricci::Scheme::circle_packing,
                            ricci::RadiusInit::mean);
  const auto blended =
      ricci::cone_tangent_metric(t, lengths, problem.cone, 3, ricci::RadiusInit::mean);
  std::vector<char> near(problem.mesh.n_vertices(), 0);  // within 2 rings: its edges reach ring 3
  near[problem.cone] = 1;
  for (auto v : ricci::ring_neighbourhood(problem.mesh, problem.mesh.vertex_handle(problem.cone), 2)) near[v.idx()] = 1;
  int tangent = 0;
  for (int e = 0; e < t.num_edges(); ++e) {
    if (near[t.edge_vertices(e, 0)] || near[t.edge_vertices(e, 1)]) {
      EXPECT_EQ(blended.eta[e], 1.0) << e;
      ++tangent;
    } else {
      EXPECT_EQ(blended.eta[e], packing.eta[e]) << e;
    }
  }
  EXPECT_GT(tangent, 3 * 20);  // the cone alone has valence >= 20
  EXPECT_EQ(blended.gamma, packing.gamma);
  auto r = expect_flow_reaches_target(problem);
  EXPECT_TRUE(r.failed_attempts.empty()) << r.failed_attempts.front();
  EXPECT_NEAR(2 * M_PI - r.curvature[problem.cone], 10 * M_PI, 1e-9);
}

// Inversive distance far from the cone reproduces the mesh there; Thurston's angles near it are
// that inversive distance clamped to [0, pi/2], with the same radii.
TEST(OneCone, ConeRingMetricKeepsTheMeshFarFromTheConeAndClampsNearIt) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 5);
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const ricci::EdgeLengths lengths = ricci::mesh_edge_lengths(problem.mesh);
  const auto inversive =
      ricci::initial_metric(t, lengths, ricci::Geometry::euclidean,
                            ricci::Scheme::inversive_distance, ricci::RadiusInit::mean);
  const ricci::ConeRingMetric rule{ricci::Scheme::inversive_distance, ricci::Scheme::circle_packing,
                                   4, ricci::RadiusInit::mean};
  const auto mixed = ricci::cone_ring_metric(t, lengths, problem.cone, rule);
  EXPECT_EQ(mixed.gamma, inversive.gamma);
  std::vector<char> near(problem.mesh.n_vertices(), 0);  // within 3 rings: its edges reach ring 4
  near[problem.cone] = 1;
  for (auto v : ricci::ring_neighbourhood(problem.mesh, problem.mesh.vertex_handle(problem.cone), 3)) near[v.idx()] = 1;
  const ricci::EdgeLengths mixed_lengths = ricci::circle_packing_lengths(t, mixed);
  int clamped = 0;
  for (int e = 0; e < t.num_edges(); ++e) {
    if (near[t.edge_vertices(e, 0)] || near[t.edge_vertices(e, 1)]) {
      EXPECT_EQ(mixed.eta[e], std::clamp(inversive.eta[e], 0.0, 1.0)) << e;
      clamped += mixed.eta[e] != inversive.eta[e];
    } else {
      EXPECT_EQ(mixed.eta[e], inversive.eta[e]) << e;
      EXPECT_NEAR(mixed_lengths[e], lengths[e], 1e-12 * lengths[e]) << e;
    }
  }
  EXPECT_GT(clamped, 0);
  EXPECT_EQ(ricci::to_string(rule), "inversive-distance/mean, circle-packing within 4 rings of the cone");
}

TEST(OneCone, ConeRingMetricClampsTheEdgesOfNeedles) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 5);
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const ricci::EdgeLengths lengths = ricci::mesh_edge_lengths(problem.mesh);
  ricci::ConeRingMetric rule{ricci::Scheme::inversive_distance, ricci::Scheme::combinatorial, 1,
                             ricci::RadiusInit::mean};
  rule.needle_angle = 0.5;  // radians: most of the eight's faces
  const auto mixed = ricci::cone_ring_metric(t, lengths, problem.cone, rule);
  const Eigen::MatrixX3d angles = ricci::corner_angles(t, lengths, ricci::Geometry::euclidean);
  int needles = 0;
  for (int f = 0; f < t.num_faces(); ++f) {
    if (angles.row(f).minCoeff() >= rule.needle_angle) continue;
    ++needles;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mixed.eta[t.face_edges(f, k)], 1.0) << f;  // tangent
  }
  EXPECT_GT(needles, 0);
}

// Shrunk radii make every inversive distance >= 0 and still reproduce the mesh far from the cone;
// faces that mix clamped and free weights and fail the triangle inequality join the clamped side,
// so the initial metric is valid (genus2_10k at 6 rings breaks faces without that).
TEST(OneCone, ConeRingMetricWithNonnegativeInversiveDistancesIsAValidMetric) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("bench/genus2_10k.obj.gz"), 0);
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const ricci::EdgeLengths lengths = ricci::mesh_edge_lengths(problem.mesh);
  const auto mean =
      ricci::initial_metric(t, lengths, ricci::Geometry::euclidean,
                            ricci::Scheme::inversive_distance, ricci::RadiusInit::mean);
  ricci::ConeRingMetric rule{ricci::Scheme::inversive_distance, ricci::Scheme::circle_packing, 6,
                             ricci::RadiusInit::mean};
  rule.nonnegative_inversive_distance = true;
  const auto metric = ricci::cone_ring_metric(t, lengths, problem.cone, rule);
  EXPECT_GE(metric.eta.minCoeff(), 0.0);
  EXPECT_LT(mean.eta.minCoeff(), 0.0);  // the mesh's own radii overlap by more than a right angle
  EXPECT_TRUE((metric.gamma.array() <= mean.gamma.array()).all());
  const ricci::EdgeLengths l = ricci::circle_packing_lengths(t, metric);
  int reproduced = 0;
  for (int e = 0; e < t.num_edges(); ++e) reproduced += std::abs(l[e] - lengths[e]) <= 1e-12 * lengths[e];
  EXPECT_GT(reproduced, t.num_edges() * 9 / 10);
  EXPECT_NO_THROW((void)ricci::corner_angles(t, l, ricci::Geometry::euclidean));
}

TEST(OneCone, ConeRingFlowReachesTheConeAndRefusesOtherProblems) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 5);
  const std::vector<ricci::ConeRingMetric> rules = {{ricci::Scheme::inversive_distance,
                                                     ricci::Scheme::combinatorial, 3,
                                                     ricci::RadiusInit::mean}};
  const ricci::FlowResult r = ricci::solve_cone_ring_flow(problem, rules, ricci::one_cone_flow_options());
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.max_error, 1e-9);
  EXPECT_NEAR(2 * M_PI - r.curvature[problem.cone], 6 * M_PI, 1e-9);
  EXPECT_TRUE(r.failed_attempts.empty());
  auto torus = ricci::prepare_one_cone(read_test_mesh("closed_g1/knot1.off.gz"), 0);
  EXPECT_THROW((void)ricci::solve_cone_ring_flow(torus, rules, ricci::one_cone_flow_options()),
               ricci::InvalidInputError);
}

TEST(OneCone, GenusOneIsAFlatTorusWithoutCone) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("closed_g1/knot1.off.gz"), 0);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::FlatTorus);
  EXPECT_EQ(problem.cone, -1);
  EXPECT_NEAR(problem.targets.curvature.cwiseAbs().maxCoeff(), 0.0, 0.0);
  expect_flow_reaches_target(problem);
}

TEST(OneCone, GenusZeroRemovesTheStarAndBendsTheNewBoundary) {
  auto mesh = read_test_mesh("closed_g0/knight_decimated.off");
  auto problem = ricci::prepare_one_cone(mesh, 7);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::PuncturedSphere);
  EXPECT_EQ(problem.mesh.n_vertices() + 1, mesh.n_vertices());
  EXPECT_EQ(ricci::surface_topology(problem.mesh).boundary_loops, 1);
  EXPECT_NEAR(problem.targets.curvature.sum(), 2 * M_PI, 1e-12);
  expect_flow_reaches_target(problem);
}

// first_metric skips the head of the metric order (the singularity choice's descents); the
// converged metric's position in that order is read back from its name.
TEST(OneCone, FirstMetricSkipsTheHeadOfTheOrder) {
  for (auto kind : {ricci::OneConeKind::SingleCone, ricci::OneConeKind::PuncturedSphere}) {
    EXPECT_EQ(ricci::metric_order_position(kind, "no such metric"), -1);
  }
  auto problem = ricci::prepare_one_cone(read_test_mesh("closed_g0/knight_decimated.off"), 7);
  const auto order = ricci::one_cone_metric_order(problem.kind);
  ASSERT_GE(order.size(), 3u);
  const ricci::FlowOptions options = ricci::one_cone_flow_options();
  const ricci::FlowResult all = ricci::solve_one_cone_flow(problem, options);
  ASSERT_TRUE(all.converged());
  const int position = ricci::metric_order_position(problem.kind, all.metric_name);
  ASSERT_GE(position, 0);
  ASSERT_EQ(all.failed_attempts.size(), static_cast<size_t>(position));
  // Starting at the metric that converged: the same metric and lengths, no failed run.
  const ricci::FlowResult direct = ricci::solve_one_cone_flow(problem, options, false, position);
  ASSERT_TRUE(direct.converged());
  EXPECT_EQ(direct.metric_name, all.metric_name);
  EXPECT_TRUE(direct.failed_attempts.empty());
  EXPECT_LT(direct.linear_work.factorizations, all.linear_work.factorizations + (position == 0));
  ASSERT_EQ(direct.lengths.size(), all.lengths.size());
  EXPECT_LT((direct.lengths - all.lengths).cwiseAbs().maxCoeff(),
            1e-8 * all.lengths.cwiseAbs().maxCoeff());
  // Past the end: the last metric of the order is still tried.
  const ricci::FlowResult last = ricci::solve_one_cone_flow(problem, options, false, 99);
  EXPECT_EQ(ricci::metric_order_position(problem.kind, last.metric_name),
            static_cast<int>(order.size()) - 1);
}

TEST(OneCone, OpenSurfacePushesCurvatureToTheBoundary) {
  auto mesh = read_test_mesh("open/head.off");
  auto problem = ricci::prepare_one_cone(mesh, -1);
  EXPECT_EQ(problem.kind, ricci::OneConeKind::OpenSurface);
  EXPECT_EQ(problem.boundary_loops, 3);
  EXPECT_NEAR(problem.targets.curvature.sum(), 2 * M_PI * -1, 1e-9);  // chi = 2 - 0 - 3
  expect_flow_reaches_target(problem);
}

TEST(OneCone, VertexOutOfRangeIsRefused) {
  EXPECT_THROW((void)ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 100000),
               ricci::InvalidInputError);
}

}  // namespace

namespace {

TEST(OneCone, CircleDomainTargetMakesRoundHoles) {
  auto mesh = read_test_mesh("open/holes.off.gz");  // genus 0, 7 boundary loops
  auto targets = ricci::boundary_target(mesh, ricci::BoundaryMode::circle_domain);
  auto tables = ricci::build_mesh_tables(mesh);
  ASSERT_EQ(tables.boundary_loops.size(), 7u);
  EXPECT_NEAR(targets.curvature.sum(), 2 * M_PI * tables.euler_characteristic, 1e-9);
  int round_holes = 0;
  for (const auto& loop : tables.boundary_loops) {
    double sum = 0;
    for (int v : loop) sum += targets.curvature[v];
    if (std::abs(sum + 2 * M_PI) < 1e-9) {
      ++round_holes;
    } else {
      EXPECT_NEAR(sum, 2 * M_PI, 1e-9);  // the outer loop of a genus-0 domain
    }
  }
  EXPECT_EQ(round_holes, 6);
}

TEST(OneCone, ScanWithManyHolesFallsBackToACircleDomain) {
  auto problem = ricci::prepare_one_cone(read_test_mesh("open/mech-holes-shark.off.gz"), -1);
  auto r = expect_flow_reaches_target(problem);
  EXPECT_FALSE(r.failed_attempts.empty());  // spread by length fails on this scan
}

}  // namespace
