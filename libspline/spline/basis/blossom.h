#pragma once
// Polynomials of the plane in monomial form and their blossoms (polar forms), the DMS control
// points that reproduce a polynomial, and the inverse map (manifold-splines paper section 5;
// fairing, manifold-splines eq. 14, needs f^J from J's control points and its blossom at I's knot
// sets).
//
// A polynomial p of degree <= n, viewed as degree n, has a unique blossom P(u_1, ..., u_n):
// symmetric, affine in each argument, P(u, ..., u) = p(u). For a monomial x^a y^b,
//     P = sum over disjoint S, T in {1..n}, |S| = a, |T| = b, of prod_{i in S} x_i prod_{j in T}
//     y_j
//         / (n! / (a! b! (n - a - b)!)).
// DMS (1992): sum_I sum_beta P(t_{0,0..beta0-1}, t_{1,0..beta1-1}, t_{2,0..beta2-1}) N_{I,beta} =
// p.
#include <Eigen/Core>
#include <vector>

#include "spline/knots/knot_cloud.h"

namespace spline {

/// p(u) = sum_{a + b <= degree} c_{a,b} X^a Y^b, (X, Y) = axes (u - origin) / scale, with vector
/// coefficients (one column per component). The local frame keeps fits on triangles far from the
/// origin, or thin ones (axes: an affine frame of the triangle), well conditioned.
struct BivariatePolynomial {
  int degree = 0;
  Eigen::MatrixXd coefficients;  ///< monomial_count(degree) rows (monomial_index order), k columns
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double scale = 1.0;
  Eigen::Matrix2d axes = Eigen::Matrix2d::Identity();  ///< invertible
};

/// Number of monomials of degree <= n: (n + 1)(n + 2) / 2.
[[nodiscard]] constexpr int monomial_count(int degree) { return (degree + 1) * (degree + 2) / 2; }

/// Row of X^a Y^b: by total degree t = a + b, then a descending: t (t + 1) / 2 + (t - a).
[[nodiscard]] constexpr int monomial_index(int a, int b) {
  return (a + b) * (a + b + 1) / 2 + b;
}

/// The scalar polynomial x^a y^b (origin 0, scale 1) of the given degree (>= a + b).
[[nodiscard]] BivariatePolynomial monomial(int a, int b, int degree);

/// p(u), one entry per component.
[[nodiscard]] Eigen::VectorXd evaluate(const BivariatePolynomial& p, const Eigen::Vector2d& u);

/// Blossom of p, seen as a polynomial of degree arguments.size() (>= p.degree).
/// \throw ricci::InvalidInputError when arguments.size() < p.degree.
[[nodiscard]] Eigen::VectorXd blossom(const BivariatePolynomial& p,
                                      const std::vector<Eigen::Vector2d>& arguments);

/// Blossom arguments of control point beta of a triangle with vertex clouds c0, c1, c2:
/// (t_{0,0..beta0-1}, t_{1,0..beta1-1}, t_{2,0..beta2-1}).
[[nodiscard]] std::vector<Eigen::Vector2d> control_point_arguments(const KnotCloud& c0,
                                                                   const KnotCloud& c1,
                                                                   const KnotCloud& c2,
                                                                   const Eigen::Vector3i& beta);

/// Control points of one triangle reproducing p: row i is the blossom at the arguments of
/// multi_indices(n)[i]. (n + 1)(n + 2)/2 rows, one column per component.
/// \throw ricci::InvalidInputError on unequal cloud degrees or p.degree above it.
[[nodiscard]] Eigen::MatrixXd triangle_control_points(const BivariatePolynomial& p,
                                                      const KnotCloud& c0, const KnotCloud& c1,
                                                      const KnotCloud& c2);

/// The degree-n polynomial whose control points on the triangle (c0, c1, c2) are the given rows
/// (multi_indices order): inverse of triangle_control_points (the blossom values at the DMS knot
/// sets determine the polynomial when the knot-net conditions hold). Local frame: the affine one
/// taking the triangle's vertices (t_{0,0}, t_{1,0}, t_{2,0}) to (0, 0), (1, 0), (0, 1), moved to
/// their centroid, so that the system's conditioning does not depend on the triangle's shape (a
/// sliver of aspect 1e-5 in a frame of its longest edge made it singular to rounding).
/// \throw ricci::InvalidInputError on a row count other than (n + 1)(n + 2)/2;
///        ricci::SolverError when the knot configuration makes the system singular.
[[nodiscard]] BivariatePolynomial polynomial_from_control_points(const KnotCloud& c0,
                                                                 const KnotCloud& c1,
                                                                 const KnotCloud& c2,
                                                                 const Eigen::MatrixXd& points);

}  // namespace spline
