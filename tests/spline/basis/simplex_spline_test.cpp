// Simplex splines: normalisation (integral), recurrence identities, exact derivatives vs finite
// differences, half-open base case, degenerate knots.
#include "spline/basis/simplex_spline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ricci/mesh/errors.h"

namespace spline {
namespace {

std::vector<Eigen::Vector2d> random_knots(int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> knots;
  for (int i = 0; i < count; ++i) knots.emplace_back(unit(rng), unit(rng));
  return knots;
}

std::uint32_t all_of(std::size_t count) { return (1u << count) - 1u; }

// Distance from u to the nearest line through two knots: finite differences need a margin.
double distance_to_knot_lines(const std::vector<Eigen::Vector2d>& knots, const Eigen::Vector2d& u) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < knots.size(); ++i) {
    for (std::size_t j = i + 1; j < knots.size(); ++j) {
      const Eigen::Vector2d e = (knots[j] - knots[i]).normalized();
      const Eigen::Vector2d w = u - knots[i];
      d = std::min(d, std::abs(e.x() * w.y() - e.y() * w.x()));
    }
  }
  return d;
}

TEST(SimplexSpline, BaseCaseIsInverseDeterminantInsideOnly) {
  const std::vector<Eigen::Vector2d> knots = {{0, 0}, {2, 0}, {0, 1}};  // |d| = 2
  EXPECT_DOUBLE_EQ(simplex_spline(knots, {0.5, 0.25}).value, 0.5);
  EXPECT_DOUBLE_EQ(simplex_spline(knots, {1.5, 0.5}).value, 0.0);
  // Order of knots does not matter (clockwise input is reoriented).
  EXPECT_DOUBLE_EQ(simplex_spline({{0, 0}, {0, 1}, {2, 0}}, {0.5, 0.25}).value, 0.5);
}

// Integral of the standard simplex spline (n+1)(n+2) M_DMS is 1: midpoint rule on a fine grid.
TEST(SimplexSpline, StandardNormalisationIntegratesToOne) {
  std::mt19937 rng(7);
  for (int n = 1; n <= 5; ++n) {
    const std::vector<Eigen::Vector2d> knots = random_knots(n + 3, rng);
    SimplexSplineDag dag(knots);
    const int root = dag.add(all_of(knots.size()));
    Eigen::Vector2d lo = knots[0], hi = knots[0];
    for (const auto& k : knots) lo = lo.cwiseMin(k), hi = hi.cwiseMax(k);
    const int cells = 400;
    const Eigen::Vector2d h = (hi - lo) / cells;
    std::vector<double> table;
    double integral = 0.0;
    for (int j = 0; j < cells; ++j) {
      for (int i = 0; i < cells; ++i) {
        const Eigen::Vector2d u = lo + Eigen::Vector2d((i + 0.5) * h.x(), (j + 0.5) * h.y());
        dag.evaluate_directional(u, Eigen::Vector2d(1, 0), 0, TieBreak{}, table);
        integral += table[static_cast<std::size_t>(root)];
      }
    }
    integral *= h.x() * h.y() * standard_simplex_spline_factor(n);
    EXPECT_NEAR(integral, 1.0, 2e-4) << "degree " << n;
  }
}

// The recurrence holds for every independent triple, not only the one the DAG picked.
TEST(SimplexSpline, RecurrenceHoldsForAnyTriple) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.2, 0.8);
  for (int n = 1; n <= 5; ++n) {
    const std::vector<Eigen::Vector2d> knots = random_knots(n + 3, rng);
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::Vector2d u(unit(rng), unit(rng));
      const double full = simplex_spline(knots, u).value;
      // Triple (0, 1, 2): barycentric coordinates of u.
      const Eigen::Vector2d e1 = knots[1] - knots[0], e2 = knots[2] - knots[0], w = u - knots[0];
      const double det = e1.x() * e2.y() - e1.y() * e2.x();
      const double lb = (w.x() * e2.y() - w.y() * e2.x()) / det;
      const double lc = (e1.x() * w.y() - e1.y() * w.x()) / det;
      const double lambda[3] = {1.0 - lb - lc, lb, lc};
      double sum = 0.0;
      for (int a = 0; a < 3; ++a) {
        std::vector<Eigen::Vector2d> rest = knots;
        rest.erase(rest.begin() + a);
        sum += lambda[a] * simplex_spline(rest, u).value;
      }
      EXPECT_NEAR(sum, full, 1e-10 * (1.0 + std::abs(full))) << "degree " << n;
    }
  }
}

TEST(SimplexSpline, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.1, 0.9);
  for (int n = 2; n <= 5; ++n) {
    const std::vector<Eigen::Vector2d> knots = random_knots(n + 3, rng);
    int checked = 0;
    while (checked < 8) {
      const Eigen::Vector2d u(unit(rng), unit(rng));
      if (distance_to_knot_lines(knots, u) < 1e-3) continue;
      const Jet jet = simplex_spline(knots, u);
      if (jet.value == 0.0) continue;
      ++checked;
      const double h = 1e-6;
      for (int axis = 0; axis < 2; ++axis) {
        const Eigen::Vector2d e = Eigen::Vector2d::Unit(axis) * h;
        const Jet plus = simplex_spline(knots, u + e), minus = simplex_spline(knots, u - e);
        const double scale_g = jet.gradient.norm() + std::abs(jet.value);
        EXPECT_NEAR((plus.value - minus.value) / (2 * h), jet.gradient[axis], 1e-6 * scale_g);
        const Eigen::Vector2d fd_hess = (plus.gradient - minus.gradient) / (2 * h);
        const double scale_h = jet.hessian.norm() + jet.gradient.norm();
        const Eigen::Vector2d exact = axis == 0 ? Eigen::Vector2d(jet.hessian[0], jet.hessian[1])
                                                : Eigen::Vector2d(jet.hessian[1], jet.hessian[2]);
        EXPECT_NEAR((fd_hess - exact).norm(), 0.0, 1e-6 * scale_h) << "degree " << n;
      }
    }
  }
}

TEST(SimplexSpline, DirectionalDerivativesAgreeWithJetAndEachOther) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.2, 0.8);
  for (int n = 2; n <= 5; ++n) {
    const std::vector<Eigen::Vector2d> knots = random_knots(n + 3, rng);
    const Eigen::Vector2d u(unit(rng), unit(rng));
    const Eigen::Vector2d d = Eigen::Vector2d(unit(rng), -unit(rng)).normalized();
    const Jet jet = simplex_spline(knots, u);
    const std::vector<double> dd = simplex_spline_directional(knots, u, d, n);
    EXPECT_NEAR(dd[0], jet.value, 1e-12 * (1 + std::abs(jet.value)));
    EXPECT_NEAR(dd[1], jet.gradient.dot(d), 1e-10 * (1 + jet.gradient.norm()));
    const double second = jet.hessian[0] * d.x() * d.x() + 2 * jet.hessian[1] * d.x() * d.y() +
                          jet.hessian[2] * d.y() * d.y();
    EXPECT_NEAR(dd[2], second, 1e-9 * (1 + jet.hessian.norm()));
    // Order k+1 is the derivative of order k (finite difference along d, away from knot lines).
    if (distance_to_knot_lines(knots, u) > 1e-3) {
      const double h = 1e-6;
      const std::vector<double> plus = simplex_spline_directional(knots, u + h * d, d, n);
      const std::vector<double> minus = simplex_spline_directional(knots, u - h * d, d, n);
      for (int k = 0; k < n; ++k) {
        EXPECT_NEAR((plus[k] - minus[k]) / (2 * h), dd[k + 1],
                    1e-5 * (std::abs(dd[k + 1]) + std::abs(dd[k]) + 1.0))
            << "degree " << n << " order " << k + 1;
      }
    }
  }
}

TEST(SimplexSpline, CollinearKnotsGiveZeroAndNearlyCollinearStayFinite) {
  const std::vector<Eigen::Vector2d> line = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {0.5, 0.5}};
  EXPECT_EQ(simplex_spline(line, {1.0, 1.0}).value, 0.0);
  EXPECT_EQ(simplex_spline(line, {1.0, 1.2}).value, 0.0);
  std::vector<Eigen::Vector2d> almost = {{0, 0}, {1, 1e-13}, {2, -1e-13}, {0.3, 1}, {0.7, 0.9}};
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(-0.5, 2.5);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d u(unit(rng), unit(rng) * 0.5);
    const Jet jet = simplex_spline(almost, u);
    EXPECT_TRUE(std::isfinite(jet.value) && jet.gradient.allFinite() && jet.hessian.allFinite());
  }
  // A knot on the segment axis, exactly at the evaluation point.
  const Jet on = simplex_spline(almost, {1.0, 1e-13});
  EXPECT_TRUE(std::isfinite(on.value) && on.gradient.allFinite() && on.hessian.allFinite());
}

TEST(SimplexSpline, RejectsBadInput) {
  EXPECT_THROW(simplex_spline({{0, 0}, {1, 0}}, {0, 0}), ricci::InvalidInputError);
  EXPECT_THROW(simplex_spline({{0, 0}, {1, 0}, {0, NAN}}, {0, 0}), ricci::InvalidInputError);
  EXPECT_THROW(SimplexSplineDag(std::vector<Eigen::Vector2d>(33, Eigen::Vector2d::Zero())),
               ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
