// Extended-precision polish of a hyperbolic metric: angles, convergence, uniqueness in the
// conformal class, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <ricci/flow/flow.h>
#include <ricci/hyperbolic/polish_h2.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include "test_paths.h"

namespace ricci {
namespace {

TEST(HyperbolicAnglesL, EquilateralAndDefect) {
  // Equilateral side l: cos θ = cosh l / (1 + cosh l) (hyperbolic law of cosines).
  for (long double l : {1e-4L, 0.3L, 2.0L}) {
    const long double sides[3] = {l, l, l};
    long double theta[3];
    ASSERT_TRUE(hyperbolic_angles_l(sides, theta));
    const long double expected = std::acos(std::cosh(l) / (1.0L + std::cosh(l)));
    for (long double t : theta) EXPECT_LT(std::abs(t - expected), 1e-17L) << static_cast<double>(l);
  }
  // A right-angled-ish scalene triangle: every angle agrees with the law of cosines.
  const long double l[3] = {0.7L, 0.9L, 1.1L};
  long double theta[3];
  ASSERT_TRUE(hyperbolic_angles_l(l, theta));
  for (int k = 0; k < 3; ++k) {
    const long double a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
    const long double cos_k =
        (std::cosh(b) * std::cosh(c) - std::cosh(a)) / (std::sinh(b) * std::sinh(c));
    EXPECT_LT(std::abs(std::cos(theta[k]) - cos_k), 1e-17L);
  }
  EXPECT_LT(theta[0] + theta[1] + theta[2], 3.141592653589793238L);
  const long double bad[3] = {1.0L, 0.3L, 0.4L};
  EXPECT_FALSE(hyperbolic_angles_l(bad, theta));
}

TEST(HyperbolicAnglesQ, AgreeWithTheLawOfCosinesInQuadPrecision) {
  if (!has_quad_transcendentals()) GTEST_SKIP() << "built without libquadmath";
  const RealQ l[3] = {RealQ(0.7L), RealQ(0.9L), RealQ(1.1L)};
  RealQ theta[3];
  ASSERT_TRUE(hyperbolic_angles_q(l, theta));
  const auto cosh_q = [](RealQ x) { return (exp_q(x) + 1 / exp_q(x)) / 2; };
  for (int k = 0; k < 3; ++k) {
    const RealQ a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
    const RealQ cos_k = (cosh_q(b) * cosh_q(c) - cosh_q(a)) / (sinh_q(b) * sinh_q(c));
    const RealQ difference = cos_q(theta[k]) - cos_k;
    EXPECT_LT(static_cast<double>(difference < 0 ? -difference : difference), 1e-31);
  }
  // The long double angles agree to their own precision, and the area is positive.
  const long double ll[3] = {0.7L, 0.9L, 1.1L};
  long double tl[3];
  ASSERT_TRUE(hyperbolic_angles_l(ll, tl));
  for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(static_cast<double>(theta[k] - tl[k])), 1e-17);
  EXPECT_GT(static_cast<double>(pi_q() - theta[0] - theta[1] - theta[2]), 0.1);
  const RealQ bad[3] = {RealQ(1.0), RealQ(0.3), RealQ(0.4)};
  EXPECT_FALSE(hyperbolic_angles_q(bad, theta));
}

struct Flowed {
  Mesh mesh;
  FlowResult flow;
};

Flowed flowed_eight() {
  Flowed f{read_mesh(msp_test::test_mesh("closed_g2/eight_cgal.off")), {}};
  FlowOptions o;
  o.geometry = Geometry::hyperbolic;
  o.tolerance = 1e-12;
  f.flow = flow(f.mesh, uniform_target(f.mesh, Geometry::hyperbolic), o);
  return f;
}

TEST(PolishH2, RemovesTheFlowsDefectsWithATinyChange) {
  const Flowed f = flowed_eight();
  ASSERT_TRUE(f.flow.converged());
  const PolishH2Result p = polish_h2_lengths(f.mesh, f.flow.lengths, f.flow.target);
  EXPECT_GT(p.error_before, 1e-16);  // the flow stops at double's floor
  EXPECT_LT(p.error_after, 1e-17);
  EXPECT_GE(p.iterations, 1);
  for (Eigen::Index e = 0; e < p.lengths.size(); ++e) {
    EXPECT_LT(std::abs(static_cast<double>(p.lengths[e]) - f.flow.lengths[e]) / f.flow.lengths[e],
              1e-12);
  }
}

TEST(PolishH2, ReachesQuadPrecisionInAFewSteps) {
  // The Jacobian is exact (factored once in double), so each step gains ~14 digits: the flow's
  // 1e-14 becomes quad precision's floor in two or three steps.
  if (!has_quad_transcendentals()) GTEST_SKIP() << "built without libquadmath";
  const Flowed f = flowed_eight();
  ASSERT_TRUE(f.flow.converged());
  const PolishH2Result p = polish_h2_lengths(f.mesh, f.flow.lengths, f.flow.target);
  EXPECT_LT(p.error_after, 1e-28);
  EXPECT_LE(p.iterations, 3);
  ASSERT_EQ(p.quad_lengths.size(), static_cast<size_t>(p.lengths.size()));
  for (size_t e = 0; e < p.quad_lengths.size(); ++e) {
    EXPECT_EQ(static_cast<long double>(p.quad_lengths[e]), p.lengths[static_cast<Eigen::Index>(e)]);
  }
  // A tighter tolerance than quad precision reaches stops where it stops improving, no worse.
  PolishH2Options strict;
  strict.tolerance = 0.0;
  const PolishH2Result q = polish_h2_lengths(f.mesh, f.flow.lengths, f.flow.target, strict);
  EXPECT_LE(q.error_after, p.error_after);
}

TEST(PolishH2, ConformalPerturbationConvergesBackToTheSameMetric) {
  // The hyperbolic vertex-scaling energy is strictly convex: the metric with curvature K̄ in a
  // conformal class is unique, so a conformally perturbed start polishes back to it.
  const Flowed f = flowed_eight();
  ASSERT_TRUE(f.flow.converged());
  const PolishH2Result reference = polish_h2_lengths(f.mesh, f.flow.lengths, f.flow.target);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1e-6, 1e-6);
  Eigen::VectorXd u(f.mesh.n_vertices());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = noise(rng);
  Eigen::VectorXd perturbed(f.flow.lengths.size());
  for (auto e : f.mesh.edges()) {
    const auto h = f.mesh.halfedge_handle(e, 0);
    const double s = std::exp(
        0.5 * (u[f.mesh.from_vertex_handle(h).idx()] + u[f.mesh.to_vertex_handle(h).idx()]));
    perturbed[e.idx()] = 2.0 * std::asinh(s * std::sinh(0.5 * f.flow.lengths[e.idx()]));
  }
  PolishH2Options options;
  options.max_iterations = 30;
  const PolishH2Result p = polish_h2_lengths(f.mesh, perturbed, f.flow.target, options);
  EXPECT_GT(p.error_before, 1e-8);
  EXPECT_LT(p.error_after, 1e-17);
  double worst = 0.0;
  for (Eigen::Index e = 0; e < p.lengths.size(); ++e) {
    worst = std::max(worst, static_cast<double>(std::abs(p.lengths[e] - reference.lengths[e]) /
                                                reference.lengths[e]));
  }
  EXPECT_LT(worst, 1e-15);
}

TEST(PolishH2, BadInputThrows) {
  const Flowed f = flowed_eight();
  EXPECT_THROW((void)polish_h2_lengths(f.mesh, Eigen::VectorXd::Ones(3), f.flow.target),
               InvalidInputError);
  Eigen::VectorXd broken = f.flow.lengths;
  const auto h = f.mesh.halfedge_handle(FaceHandle(0));
  broken[f.mesh.edge_handle(h).idx()] = 100.0;  // longer than the other two sides together
  EXPECT_THROW((void)polish_h2_lengths(f.mesh, broken, f.flow.target), InvalidInputError);
}

}  // namespace
}  // namespace ricci
