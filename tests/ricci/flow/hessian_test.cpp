// Every Hessian against central finite differences of the curvature, in all three geometries and
// for all three metrics, at randomly perturbed radii on jittered meshes.
#include <gtest/gtest.h>

#include <random>

#include <ricci/flow/flow_state.h>
#include <ricci/flow/hessian.h>
#include <ricci/metric/circle_packing.h>
#include <ricci/metric/curvature.h>

#include "ricci/test_meshes.h"

namespace ricci {
namespace {

struct Case {
  Geometry geometry;
  Scheme scheme;
};

class HessianTest : public ::testing::TestWithParam<Case> {};

Eigen::VectorXd curvature_at(const MeshTables& t, const CirclePackingMetric& m, const Eigen::VectorXd& u) {
  FlowState s;
  EXPECT_TRUE(evaluate_flow_state(t, m.geometry, m.eta, u, s));
  return s.curvature;
}

TEST_P(HessianTest, MatchesFiniteDifferencesOfCurvature) {
  const auto [g, scheme] = GetParam();
  // S2 needs short edges on a sphere; E2/H2 use a jittered torus (scaled down for H2).
  Mesh mesh = g == Geometry::spherical ? testing::sphere(2) : testing::torus(9, 7);
  testing::jitter(mesh, 0.04, 11);
  const MeshTables t = build_mesh_tables(mesh);
  EdgeLengths l = mesh_edge_lengths(mesh);
  if (g == Geometry::hyperbolic) l *= 0.6;
  CirclePackingMetric m = initial_metric(t, l, g, scheme, RadiusInit::mean);
  // Move away from the initial metric so the test is generic.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-0.05, 0.05);
  Eigen::VectorXd u = u_from_radii(g, m.gamma);
  for (int v = 0; v < u.size(); ++v) u[v] += d(rng);
  m.gamma = radii_from_u(g, u);

  const Eigen::SparseMatrix<double> H = curvature_jacobian(t, m);
  const Eigen::MatrixXd dense = H;
  EXPECT_LT((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
  const double h = 1e-6;
  double worst = 0;
  for (int column = 0; column < t.num_vertices(); column += 3) {
    Eigen::VectorXd up = u, down = u;
    up[column] += h;
    down[column] -= h;
    const Eigen::VectorXd fd = (curvature_at(t, m, up) - curvature_at(t, m, down)) / (2 * h);
    const double scale = dense.col(column).cwiseAbs().maxCoeff();
    worst = std::max(worst, (dense.col(column) - fd).cwiseAbs().maxCoeff() / scale);
  }
  EXPECT_LT(worst, 1e-6) << to_string(g) << " " << to_string(scheme);
  if (g == Geometry::euclidean) {
    // Scaling every radius keeps every angle: H·1 = 0.
    EXPECT_LT((dense * Eigen::VectorXd::Ones(u.size())).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
  }
}

INSTANTIATE_TEST_SUITE_P(AllGeometriesAndMetrics, HessianTest,
                         ::testing::Values(Case{Geometry::euclidean, Scheme::circle_packing},
                                           Case{Geometry::euclidean, Scheme::inversive_distance},
                                           Case{Geometry::euclidean, Scheme::combinatorial},
                                           Case{Geometry::hyperbolic, Scheme::circle_packing},
                                           Case{Geometry::hyperbolic, Scheme::inversive_distance},
                                           Case{Geometry::hyperbolic, Scheme::combinatorial},
                                           Case{Geometry::spherical, Scheme::circle_packing},
                                           Case{Geometry::spherical, Scheme::inversive_distance},
                                           Case{Geometry::spherical, Scheme::combinatorial}));

}  // namespace
}  // namespace ricci
