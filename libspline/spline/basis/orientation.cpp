#include "spline/basis/orientation.h"

#include <cmath>
#include <initializer_list>
#include <limits>

namespace spline {
namespace {

// Exact arithmetic on floating-point expansions (Shewchuk 1997): a sum of doubles kept as a
// non-overlapping sequence of increasing magnitude, so that its sign is the sign of its largest
// component. Only reached when the fast filter cannot decide, i.e. on (nearly) collinear input.
struct Expansion {
  double terms[16];
  int size = 0;

  void add(double b) {
    int out = 0;
    double q = b;
    for (int i = 0; i < size; ++i) {
      const double sum = q + terms[i];
      const double b_virtual = sum - q;
      const double a_virtual = sum - b_virtual;
      const double error = (q - a_virtual) + (terms[i] - b_virtual);
      q = sum;
      if (error != 0.0) terms[out++] = error;
    }
    if (q != 0.0) terms[out++] = q;
    size = out;
  }
  void add_product(double a, double b) {
    const double p = a * b;
    add(std::fma(a, b, -p));  // exact rounding error of the product
    add(p);
  }
  double approximate() const {  // smallest first: the sum is accurate to a few ulps
    double sum = 0.0;
    for (int i = 0; i < size; ++i) sum += terms[i];
    return sum;
  }
  int sign() const {
    if (size == 0) return 0;
    return terms[size - 1] > 0.0 ? 1 : -1;
  }
};

constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2.0;  // 2^-53
// Shewchuk's bound for orient2d evaluated as (ax-cx)(by-cy) - (ay-cy)(bx-cx).
constexpr double kOrientBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

// (a - b) - difference exactly, for difference = fl(a - b) (Knuth's two-sum, branch free).
double two_diff_error(double a, double b, double difference) {
  const double b_virtual = a - difference;
  const double a_virtual = difference + b_virtual;
  return (a - a_virtual) + (b_virtual - b);
}

// Error of accurate_det2d's compensated sum before its last rounding, over |l| + |r| (the two
// products' magnitudes): the dropped second-order term ex1 ey2 - ey1 ex2 (<= 2 eps^2) and the
// rounding of the corrections (four first-order products and five sums of terms each <= 2 eps:
// <= 20 eps^2 together), with room to spare.
constexpr double kCompensatedBound = 32.0 * kEpsilon * kEpsilon;
// The compensated value is taken when that error is below 1/16 ulp of it (eps / 16 relative):
// the result is then the correctly rounded determinant or its neighbour, as the expansion's.
constexpr double kCompensatedMargin = kEpsilon / 16.0;

// det[b - a, c - a] expanded into six exact products.
Expansion exact_det2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  Expansion e;
  e.add_product(a.x(), b.y());
  e.add_product(-a.x(), c.y());
  e.add_product(-a.y(), b.x());
  e.add_product(a.y(), c.x());
  e.add_product(b.x(), c.y());
  e.add_product(-b.y(), c.x());
  return e;
}

}  // namespace

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double left = (a.x() - c.x()) * (b.y() - c.y());
  const double right = (a.y() - c.y()) * (b.x() - c.x());
  const double det = left - right;
  const double bound = kOrientBound * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return sign_of(det);
  return exact_det2d(a, b, c).sign();
}

double accurate_det2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      const Eigen::Vector2d& c) {
  // The exact expansion costs ~500 instructions (12 error-free terms merged one by one) and was
  // ~60% of building a DAG. Away from slivers a compensated evaluation is as accurate: the
  // differences' and products' rounding errors (error-free, by two-diff and fma) enter as
  // first-order corrections, leaving an error below kCompensatedBound (|l| + |r|), which the
  // filter keeps under a sixteenth of an ulp of the result before the last rounding.
  const double dx1 = b.x() - a.x(), dy1 = b.y() - a.y();
  const double dx2 = c.x() - a.x(), dy2 = c.y() - a.y();
  const double ex1 = two_diff_error(b.x(), a.x(), dx1), ey1 = two_diff_error(b.y(), a.y(), dy1);
  const double ex2 = two_diff_error(c.x(), a.x(), dx2), ey2 = two_diff_error(c.y(), a.y(), dy2);
  const double left = dx1 * dy2, right = dy1 * dx2;
  const double left_error = std::fma(dx1, dy2, -left), right_error = std::fma(dy1, dx2, -right);
  const double head = left - right;
  const double head_error = two_diff_error(left, right, head);
  const double first_order = (dx1 * ey2 + ex1 * dy2) - (dy1 * ex2 + ey1 * dx2);
  const double correction = ((head_error + left_error) - right_error) + first_order;
  const double det = head + correction;
  const double scale = std::abs(left) + std::abs(right);
  if (std::abs(det) * kCompensatedMargin > kCompensatedBound * scale) return det;
  return exact_det2d(a, b, c).approximate();  // slivers: the terms cancel
}

int cross_sign(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& d) {
  const double left = (q.x() - p.x()) * d.y();
  const double right = (q.y() - p.y()) * d.x();
  const double value = left - right;
  // The orient2d bound covers a product of two rounded differences; one exact factor errs less.
  const double bound = kOrientBound * (std::abs(left) + std::abs(right));
  if (value > bound || -value > bound) return sign_of(value);
  Expansion e;
  e.add_product(q.x(), d.y());
  e.add_product(-p.x(), d.y());
  e.add_product(-q.y(), d.x());
  e.add_product(p.y(), d.x());
  return e.sign();
}

bool left_of(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& u,
             const TieBreak& tie) {
  const int side = orient2d(p, q, u);
  if (side != 0) return side > 0;
  // u is on the line: orient(p, q, u + eps d + eps^2 d_perp) = eps cross(q-p, d)
  // + eps^2 cross(q-p, d_perp), and cross(q-p, d_perp) = (q-p).d.
  const int first = cross_sign(p, q, tie.direction);
  if (first != 0) return first > 0;
  const Eigen::Vector2d perp(-tie.direction.y(), tie.direction.x());
  return cross_sign(p, q, perp) > 0;
}

bool in_half_open_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                           const Eigen::Vector2d& c, const Eigen::Vector2d& u,
                           const TieBreak& tie) {
  return left_of(a, b, u, tie) && left_of(b, c, u, tie) && left_of(c, a, u, tie);
}

}  // namespace spline
