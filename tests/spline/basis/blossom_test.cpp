// Blossoms of bivariate polynomials: diagonal, symmetry, multi-affinity, the control points of a
// triangle and their inverse (the polynomial f^J that fairing needs).
#include "spline/basis/blossom.h"

#include <gtest/gtest.h>

#include <random>

#include "ricci/mesh/errors.h"
#include "spline/basis/multi_index.h"
#include "spline/knots/knot_cloud.h"

namespace spline {
namespace {

BivariatePolynomial random_polynomial(int degree, int components, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  BivariatePolynomial p;
  p.degree = degree;
  p.origin = Eigen::Vector2d(unit(rng), unit(rng));
  p.scale = 0.5 + 0.5 * (unit(rng) + 1.0);
  p.coefficients = Eigen::MatrixXd::NullaryExpr(monomial_count(degree), components,
                                                [&]() { return unit(rng); });
  return p;
}

std::vector<Eigen::Vector2d> random_points(int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < count; ++i) points.emplace_back(unit(rng), unit(rng));
  return points;
}

TEST(Blossom, DiagonalIsThePolynomial) {
  std::mt19937 rng(1);
  for (int n = 0; n <= 6; ++n) {
    const BivariatePolynomial p = random_polynomial(n, 2, rng);
    for (const Eigen::Vector2d& u : random_points(5, rng)) {
      // Direct evaluation of sum c_ab X^a Y^b.
      const Eigen::Vector2d local = (u - p.origin) / p.scale;
      Eigen::Vector2d direct = Eigen::Vector2d::Zero();
      for (int a = 0; a <= n; ++a) {
        for (int b = 0; a + b <= n; ++b) {
          direct += p.coefficients.row(monomial_index(a, b)).transpose() *
                    std::pow(local.x(), a) * std::pow(local.y(), b);
        }
      }
      EXPECT_LT((evaluate(p, u) - direct).norm(), 1e-12);
      // Degree raising: the blossom with more arguments has the same diagonal.
      EXPECT_LT((blossom(p, std::vector<Eigen::Vector2d>(n + 2, u)) - direct).norm(), 1e-12);
    }
  }
}

TEST(Blossom, SymmetricAndAffineInEachArgument) {
  std::mt19937 rng(2);
  for (int n = 1; n <= 5; ++n) {
    const BivariatePolynomial p = random_polynomial(n, 1, rng);
    std::vector<Eigen::Vector2d> args = random_points(n, rng);
    const double value = blossom(p, args)[0];
    std::vector<Eigen::Vector2d> reversed(args.rbegin(), args.rend());
    EXPECT_NEAR(blossom(p, reversed)[0], value, 1e-12);
    // Affine in the first argument: P(a x + (1-a) y, ...) = a P(x, ...) + (1-a) P(y, ...).
    const Eigen::Vector2d x = random_points(1, rng)[0], y = random_points(1, rng)[0];
    const double alpha = 0.3;
    args[0] = alpha * x + (1 - alpha) * y;
    const double mixed = blossom(p, args)[0];
    args[0] = x;
    const double at_x = blossom(p, args)[0];
    args[0] = y;
    const double at_y = blossom(p, args)[0];
    EXPECT_NEAR(mixed, alpha * at_x + (1 - alpha) * at_y, 1e-12);
  }
}

TEST(Blossom, MonomialBlossomIsTheSymmetrisedProduct) {
  // x^2 y as a cubic: P = (x1 x2 y3 + x1 x3 y2 + x2 x3 y1) / 3.
  const BivariatePolynomial p = monomial(2, 1, 3);
  const std::vector<Eigen::Vector2d> a = {{1, 2}, {3, 5}, {7, 11}};
  const double expected = (1 * 3 * 11 + 1 * 7 * 5 + 3 * 7 * 2) / 3.0;
  EXPECT_NEAR(blossom(p, a)[0], expected, 1e-12);
}

TEST(Blossom, ControlPointsOfATriangleDetermineThePolynomial) {
  std::mt19937 rng(3);
  for (int n = 1; n <= 5; ++n) {
    // A triangle far from the origin with small clouds: the local frame keeps the solve accurate.
    const Eigen::Vector2d a(100.0, 50.0), b(101.0, 50.2), c(100.3, 51.1);
    const std::vector<Eigen::Vector2d> ring_a = {b, c}, ring_b = {c, a}, ring_c = {a, b};
    const KnotCloud ca = make_knot_cloud(n, 0, a, ring_a, false);
    const KnotCloud cb = make_knot_cloud(n, 1, b, ring_b, false);
    const KnotCloud cc = make_knot_cloud(n, 2, c, ring_c, false);
    BivariatePolynomial p = random_polynomial(n, 3, rng);
    p.origin = Eigen::Vector2d(100.5, 50.5);
    const Eigen::MatrixXd control = triangle_control_points(p, ca, cb, cc);
    ASSERT_EQ(control.rows(), multi_index_count(n));
    const BivariatePolynomial back = polynomial_from_control_points(ca, cb, cc, control);
    for (const Eigen::Vector2d& offset : random_points(5, rng)) {
      const Eigen::Vector2d u = a + offset;
      EXPECT_LT((evaluate(back, u) - evaluate(p, u)).norm(), 1e-9) << "degree " << n;
    }
    // And its blossom at the knot sets reproduces the control points.
    EXPECT_LT((triangle_control_points(back, ca, cb, cc) - control).norm(), 1e-9);
  }
}

TEST(Blossom, ControlPointsOfASliverDetermineThePolynomial) {
  // turbine.off's (genus 11) face next to its cone, in its own frame: edges of 3e-16, height
  // 4.7e-21 (aspect 1.5e-5). In a frame of its longest edge the cubic's system was singular to
  // rounding; the triangle's affine frame makes it as well conditioned as an equilateral one.
  std::mt19937 rng(4);
  const Eigen::Vector2d a(3.0266047945132405e-16, 0.0), b(3.0263196015008438e-16,
                                                             4.6559958505361001e-21),
      c(0.0, 0.0);
  const std::vector<Eigen::Vector2d> ring_a = {b, c}, ring_b = {c, a}, ring_c = {a, b};
  for (int n = 1; n <= 5; ++n) {
    const KnotCloud ca = make_knot_cloud(n, 0, a, ring_a, false);
    const KnotCloud cb = make_knot_cloud(n, 1, b, ring_b, false);
    const KnotCloud cc = make_knot_cloud(n, 2, c, ring_c, false);
    const Eigen::MatrixXd control = Eigen::MatrixXd::NullaryExpr(
        multi_index_count(n), 3, [&]() { return std::uniform_real_distribution<double>(-1, 1)(rng); });
    const BivariatePolynomial p = polynomial_from_control_points(ca, cb, cc, control);
    EXPECT_LT((triangle_control_points(p, ca, cb, cc) - control).norm(), 1e-9) << "degree " << n;
  }
}

TEST(Blossom, RejectsBadInput) {
  EXPECT_THROW(monomial(3, 1, 3), ricci::InvalidInputError);
  const BivariatePolynomial p = monomial(1, 1, 2);
  EXPECT_THROW(blossom(p, {Eigen::Vector2d::Zero()}), ricci::InvalidInputError);
  BivariatePolynomial bad = p;
  bad.coefficients.resize(2, 1);
  EXPECT_THROW(evaluate(bad, Eigen::Vector2d::Zero()), ricci::InvalidInputError);
  const KnotCloud c1{{{0, 0}, {0.1, 0}}}, c2{{{1, 0}, {1.1, 0}, {1, 0.1}}};
  EXPECT_THROW(triangle_control_points(p, c1, c1, c2), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
