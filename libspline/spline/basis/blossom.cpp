#include "spline/basis/blossom.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/basis/multi_index.h"

namespace spline {
namespace {

// multinomial(n; a, b, n - a - b) = C(n, a) C(n - a, b) by row monomial_index(a, b), each an
// exact integer in double (every partial product is one).
std::vector<double> make_multinomials(int n) {
  std::vector<double> table(static_cast<std::size_t>(monomial_count(n)));
  for (int t = 0; t <= n; ++t) {
    for (int a = t; a >= 0; --a) {
      const int b = t - a;
      double multinomial = 1.0;
      for (int i = 1; i <= a; ++i) multinomial = multinomial * (n - a + i) / i;
      for (int i = 1; i <= b; ++i) multinomial = multinomial * (n - a - b + i) / i;
      table[static_cast<std::size_t>(monomial_index(a, b))] = multinomial;
    }
  }
  return table;
}

// The table for n arguments: built once per n up to kCachedArguments (blossoms are taken per
// constraint row and per collocation row, about a million times per fit; recomputing the table
// each time was a third of their cost), else built on the spot.
constexpr int kCachedArguments = 16;
const std::vector<double>& multinomials(int n, std::vector<double>& spare) {
  static const std::vector<std::vector<double>> cached = [] {
    std::vector<std::vector<double>> tables;
    for (int k = 0; k <= kCachedArguments; ++k) tables.push_back(make_multinomials(k));
    return tables;
  }();
  if (n <= kCachedArguments) return cached[static_cast<std::size_t>(n)];
  spare = make_multinomials(n);
  return spare;
}

// Elementary symmetric sums E(a, b) = sum over disjoint S, T (|S| = a, |T| = b) of
// prod_S X_i prod_T Y_j, each divided by the multinomial n! / (a! b! (n-a-b)!): the blossoms of
// all monomials X^a Y^b at once (row monomial_index(a, b)).
Eigen::VectorXd monomial_blossoms(const std::vector<Eigen::Vector2d>& local) {
  const int n = static_cast<int>(local.size());
  Eigen::VectorXd e = Eigen::VectorXd::Zero(monomial_count(n));
  e[0] = 1.0;
  for (const Eigen::Vector2d& arg : local) {
    for (int t = n; t >= 1; --t) {  // descending: each argument is used at most once
      // Rows of total degree t start at t (t + 1) / 2, those of t - 1 at (t - 1) t / 2.
      double* row = e.data() + t * (t + 1) / 2;
      const double* lower = e.data() + (t - 1) * t / 2;
      for (int a = t; a >= 0; --a) {
        const int b = t - a;  // row[b] is X^a Y^b; lower[b] is X^(a-1) Y^b, lower[b-1] X^a Y^(b-1)
        double add = 0.0;
        if (a > 0) add += arg.x() * lower[b];
        if (b > 0) add += arg.y() * lower[b - 1];
        row[b] += add;
      }
    }
  }
  std::vector<double> spare;
  const std::vector<double>& divisors = multinomials(n, spare);
  for (Eigen::Index i = 0; i < e.size(); ++i) e[i] /= divisors[static_cast<std::size_t>(i)];
  return e;
}

std::vector<Eigen::Vector2d> to_local(const BivariatePolynomial& p,
                                      const std::vector<Eigen::Vector2d>& points) {
  std::vector<Eigen::Vector2d> local;
  local.reserve(points.size());
  for (const Eigen::Vector2d& u : points) local.push_back(p.axes * (u - p.origin) / p.scale);
  return local;
}

void check_polynomial(const BivariatePolynomial& p) {
  if (p.degree < 0 || p.coefficients.rows() != monomial_count(p.degree) || !(p.scale > 0.0)) {
    throw ricci::InvalidInputError("bivariate polynomial: coefficient rows do not match degree " +
                                   std::to_string(p.degree) + " or scale is not positive");
  }
}

}  // namespace

BivariatePolynomial monomial(int a, int b, int degree) {
  if (a < 0 || b < 0 || a + b > degree) {
    throw ricci::InvalidInputError("monomial: exponents (" + std::to_string(a) + ", " +
                                   std::to_string(b) + ") exceed degree " +
                                   std::to_string(degree));
  }
  BivariatePolynomial p;
  p.degree = degree;
  p.coefficients = Eigen::MatrixXd::Zero(monomial_count(degree), 1);
  p.coefficients(monomial_index(a, b), 0) = 1.0;
  return p;
}

Eigen::VectorXd evaluate(const BivariatePolynomial& p, const Eigen::Vector2d& u) {
  return blossom(p, std::vector<Eigen::Vector2d>(static_cast<std::size_t>(p.degree), u));
}

Eigen::VectorXd blossom(const BivariatePolynomial& p,
                        const std::vector<Eigen::Vector2d>& arguments) {
  check_polynomial(p);
  const int n = static_cast<int>(arguments.size());
  if (n < p.degree) {
    throw ricci::InvalidInputError("blossom: " + std::to_string(n) +
                                   " arguments for a polynomial of degree " +
                                   std::to_string(p.degree));
  }
  const Eigen::VectorXd e = monomial_blossoms(to_local(p, arguments));
  // Monomials of p's degree are a prefix of those of degree n (rows ordered by total degree).
  return p.coefficients.transpose() * e.head(monomial_count(p.degree));
}

std::vector<Eigen::Vector2d> control_point_arguments(const KnotCloud& c0, const KnotCloud& c1,
                                                     const KnotCloud& c2,
                                                     const Eigen::Vector3i& beta) {
  std::vector<Eigen::Vector2d> args;
  args.reserve(static_cast<std::size_t>(std::max(0, beta.sum())));
  const KnotCloud* clouds[3] = {&c0, &c1, &c2};
  for (int v = 0; v < 3; ++v) {
    if (beta[v] < 0 || beta[v] > clouds[v]->degree()) {
      throw ricci::InvalidInputError("control point arguments: beta exceeds the cloud size");
    }
    for (int j = 0; j < beta[v]; ++j) args.push_back(clouds[v]->knots[static_cast<std::size_t>(j)]);
  }
  return args;
}

Eigen::MatrixXd triangle_control_points(const BivariatePolynomial& p, const KnotCloud& c0,
                                        const KnotCloud& c1, const KnotCloud& c2) {
  const int n = c0.degree();
  if (c1.degree() != n || c2.degree() != n || p.degree > n) {
    throw ricci::InvalidInputError("triangle control points: unequal cloud degrees or polynomial "
                                   "degree above the spline degree");
  }
  const std::vector<Eigen::Vector3i> betas = multi_indices(n);
  Eigen::MatrixXd result(static_cast<Eigen::Index>(betas.size()), p.coefficients.cols());
  for (std::size_t i = 0; i < betas.size(); ++i) {
    result.row(static_cast<Eigen::Index>(i)) =
        blossom(p, control_point_arguments(c0, c1, c2, betas[i])).transpose();
  }
  return result;
}

BivariatePolynomial polynomial_from_control_points(const KnotCloud& c0, const KnotCloud& c1,
                                                   const KnotCloud& c2,
                                                   const Eigen::MatrixXd& points) {
  const int n = c0.degree();
  const int count = multi_index_count(n);
  if (c1.degree() != n || c2.degree() != n || points.rows() != count) {
    throw ricci::InvalidInputError("polynomial from control points: expected " +
                                   std::to_string(count) + " rows and equal cloud degrees");
  }
  BivariatePolynomial p;
  p.degree = n;
  const Eigen::Vector2d& a = c0.knots[0];
  const Eigen::Vector2d& b = c1.knots[0];
  const Eigen::Vector2d& c = c2.knots[0];
  p.origin = (a + b + c) / 3.0;
  Eigen::Matrix2d edges;
  edges << b - a, c - a;
  p.axes = edges.inverse();
  if (!p.axes.allFinite()) {
    throw ricci::SolverError("polynomial from control points: degenerate knot triangle");
  }
  // Row beta: blossoms of all monomials at beta's arguments (the B-patch collocation matrix).
  const std::vector<Eigen::Vector3i> betas = multi_indices(n);
  Eigen::MatrixXd matrix(count, count);
  for (int i = 0; i < count; ++i) {
    matrix.row(i) =
        monomial_blossoms(to_local(p, control_point_arguments(c0, c1, c2, betas[static_cast<std::size_t>(i)])))
            .transpose();
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(matrix);
  if (!lu.isInvertible()) {
    throw ricci::SolverError("polynomial from control points: the knot configuration gives a "
                             "singular blossom system");
  }
  p.coefficients = lu.solve(points);
  if (!p.coefficients.allFinite()) {
    throw ricci::SolverError("polynomial from control points: non-finite coefficients");
  }
  return p;
}

}  // namespace spline
