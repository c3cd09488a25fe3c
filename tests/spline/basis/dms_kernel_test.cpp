// The three-pass evaluation of a simplex-spline DAG (SimplexSplineDag::evaluate_roots,
// evaluate_root_gradients and evaluate_root_values: values of the unculled nodes with vectorised
// box culling, gradients of the roots and their children, Hessians of the roots) against the reference one-pass recurrence
// (SimplexSplineDag::evaluate, a jet per node) bit for bit, and against a plain recursion written
// here (no DAG, no culling) to rounding: on random, grid-aligned (collinear triples, points on knot
// lines and box edges) and clustered knots, degrees 1 to 5, several roots per DAG.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "spline/basis/simplex_spline.h"

namespace spline {
namespace {

std::uint64_t bits_of(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Bit equality (also tells +0 from -0 and compares NaNs by payload).
::testing::AssertionResult same_bits(const Jet& a, const Jet& b) {
  bool same = bits_of(a.value) == bits_of(b.value);
  for (int k = 0; k < 2; ++k) same = same && bits_of(a.gradient[k]) == bits_of(b.gradient[k]);
  for (int k = 0; k < 3; ++k) same = same && bits_of(a.hessian[k]) == bits_of(b.hessian[k]);
  if (same) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "value " << a.value << " vs " << b.value << ", gradient " << a.gradient.transpose()
         << " vs " << b.gradient.transpose() << ", Hessian " << a.hessian.transpose() << " vs "
         << b.hessian.transpose();
}

// Micchelli's recurrence by plain recursion over knot subsets (DMS normalisation, see
// simplex_spline.h): M = sum_a lambda_a M(X \ x_a), grad M = n sum_a grad(lambda_a) M(X \ x_a),
// Hess M = n sum_a grad(lambda_a) grad M(X \ x_a)^T (symmetric), for the triple of largest area.
// Also the same sums of absolute values (the size of the terms, which bounds the rounding: near
// the edges of a support the terms of thin triples cancel to far below their size).
struct Plain {
  Jet jet;
  double value_size = 0.0, gradient_size = 0.0, hessian_size = 0.0;
};

Plain recursive_jet(const std::vector<Eigen::Vector2d>& x, const Eigen::Vector2d& u,
                    const TieBreak& tie) {
  const int count = static_cast<int>(x.size());
  int best[3] = {-1, -1, -1};
  double best_area = 0.0;
  for (int a = 0; a < count; ++a) {
    for (int b = a + 1; b < count; ++b) {
      for (int c = b + 1; c < count; ++c) {
        const double area = std::abs(accurate_det2d(x[a], x[b], x[c]));
        if (area > best_area) best_area = area, best[0] = a, best[1] = b, best[2] = c;
      }
    }
  }
  Plain plain;
  Jet& jet = plain.jet;
  if (best[0] < 0) return plain;  // collinear: zero as a function
  const Eigen::Vector2d &a = x[best[0]], &b = x[best[1]], &c = x[best[2]];
  if (count == 3) {
    const bool ccw = orient2d(a, b, c) > 0;
    if (ccw ? in_half_open_triangle(a, b, c, u, tie) : in_half_open_triangle(a, c, b, u, tie)) {
      jet.value = 1.0 / best_area;
    }
    plain.value_size = jet.value;
    return plain;
  }
  const double det = accurate_det2d(a, b, c);
  // grad(lambda_k) = rot(x_{k+2} - x_{k+1}) / det, lambda_k(u) = grad(lambda_k) . (u - x_{k+1}).
  const Eigen::Vector2d corners[3] = {a, b, c};
  const double n = count - 3;
  double hxx = 0.0, hxy = 0.0, hyy = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d e = corners[(k + 2) % 3] - corners[(k + 1) % 3];
    const Eigen::Vector2d g = Eigen::Vector2d(-e.y(), e.x()) / det;
    std::vector<Eigen::Vector2d> rest = x;
    rest.erase(rest.begin() + best[k]);
    const Plain child = recursive_jet(rest, u, tie);
    const double lambda = g.dot(u - corners[(k + 1) % 3]);
    jet.value += lambda * child.jet.value;
    jet.gradient += n * g * child.jet.value;
    hxx += n * g.x() * child.jet.gradient.x();
    hxy += n * 0.5 * (g.x() * child.jet.gradient.y() + g.y() * child.jet.gradient.x());
    hyy += n * g.y() * child.jet.gradient.y();
    // lambda's own rounding is relative to g and u - x, not to lambda (near x's edge, ~0).
    const double lambda_size = g.norm() * (u - corners[(k + 1) % 3]).norm();
    plain.value_size += lambda_size * child.value_size;
    plain.gradient_size += n * g.norm() * child.value_size;
    plain.hessian_size += n * g.norm() * child.gradient_size;
  }
  jet.hessian = Eigen::Vector3d(hxx, hxy, hyy);
  return plain;
}

struct Configuration {
  const char* name;
  std::vector<Eigen::Vector2d> knots;
};

// Knot sets of 3 (n + 1) knots, as a triangle basis has: random in the unit square, on an integer
// grid (many collinear triples and zero nodes; knot lines through grid points), and three clouds
// of radius 0.02 around the corners of a triangle (thin triples).
std::vector<Configuration> configurations(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int count = 3 * (n + 1);
  Configuration random{"random", {}}, grid{"grid", {}}, clouds{"clouds", {}};
  std::uniform_int_distribution<int> cell(0, 4);
  const Eigen::Vector2d corners[3] = {{0.1, 0.1}, {0.9, 0.2}, {0.4, 0.85}};
  for (int i = 0; i < count; ++i) {
    random.knots.emplace_back(unit(rng), unit(rng));
    Eigen::Vector2d g(cell(rng), cell(rng));
    while (std::find(grid.knots.begin(), grid.knots.end(), g) != grid.knots.end()) {
      g = Eigen::Vector2d(cell(rng), cell(rng));
    }
    grid.knots.push_back(g);
    const double angle = 6.283185307179586 * unit(rng);
    clouds.knots.push_back(corners[i / (n + 1)] +
                           (i % (n + 1) == 0 ? 0.0 : 0.02 * unit(rng)) *
                               Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return {random, grid, clouds};
}

// Points in and around the knots' box, at every knot, on lines through knot pairs, on the box's
// edges and corners, one double ulp beside knots (same float, other side in double), far outside.
std::vector<Eigen::Vector2d> probe_points(const std::vector<Eigen::Vector2d>& knots,
                                          std::mt19937& rng) {
  Eigen::Vector2d lo = knots[0], hi = knots[0];
  for (const Eigen::Vector2d& k : knots) lo = lo.cwiseMin(k), hi = hi.cwiseMax(k);
  std::uniform_real_distribution<double> unit(-0.1, 1.1);
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 40; ++k) {
    points.push_back(lo + Eigen::Vector2d(unit(rng), unit(rng)).cwiseProduct(hi - lo));
  }
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < knots.size(); ++a) {
    const std::size_t b = (a * 7 + 5) % knots.size();
    points.push_back(knots[a]);
    points.push_back(0.5 * (knots[a] + knots[b]));
    points.push_back(knots[a] + 0.25 * (knots[b] - knots[a]));
    points.emplace_back(std::nextafter(knots[a].x(), -inf), knots[a].y());
    points.emplace_back(knots[a].x(), std::nextafter(knots[a].y(), inf));
    points.emplace_back(knots[a].x(), lo.y() + (hi.y() - lo.y()) * unit(rng));  // on its x line
  }
  points.emplace_back(lo.x(), hi.y());
  points.emplace_back(hi.x(), 0.5 * (lo.y() + hi.y()));
  points.emplace_back(std::nextafter(lo.x(), -inf), lo.y());
  points.push_back(hi + (hi - lo));
  return points;
}

// Roots as a triangle basis adds them (every V_beta of degree n) plus a few more of other sizes:
// a root whose children are roots, and one of degree n - 1.
std::vector<std::uint32_t> root_masks(int n, std::mt19937& rng) {
  std::vector<std::uint32_t> masks;
  for (int b0 = 0; b0 <= n; ++b0) {
    for (int b1 = 0; b0 + b1 <= n; ++b1) {
      const int beta[3] = {b0, b1, n - b0 - b1};
      std::uint32_t mask = 0;
      for (int v = 0; v < 3; ++v) {
        for (int j = 0; j <= beta[v]; ++j) mask |= 1u << (v * (n + 1) + j);
      }
      masks.push_back(mask);
    }
  }
  const int count = 3 * (n + 1);
  std::uniform_int_distribution<int> knot(0, count - 1);
  std::uint32_t bigger = masks[0];
  while (__builtin_popcount(bigger) < n + 4) bigger |= 1u << knot(rng);
  masks.push_back(bigger);
  masks.push_back(bigger & (bigger - 1));  // one knot fewer: may be one of bigger's children
  std::uint32_t smaller = bigger;
  while (__builtin_popcount(smaller) > n + 2) smaller &= smaller - 1;
  masks.push_back(smaller);
  return masks;
}

TEST(DmsKernel, RootsEqualTheReferenceRecurrenceBitForBit) {
  SimplexSplineDag::Scratch scratch;  // shared by DAGs of every size, as a thread's is
  std::vector<Jet> roots, reference, first;
  std::vector<double> values;
  for (int n = 1; n <= 5; ++n) {
    std::mt19937 rng(100 + n);
    for (const Configuration& config : configurations(n, rng)) {
      SimplexSplineDag dag(config.knots);
      std::vector<int> ids;
      for (const std::uint32_t mask : root_masks(n, rng)) ids.push_back(dag.add(mask));
      dag.release_index();
      int non_zero = 0, on_hessian = 0, points = 0;
      for (const Eigen::Vector2d& u : probe_points(config.knots, rng)) {
        for (const TieBreak& tie : {TieBreak{}, TieBreak{Eigen::Vector2d(-0.3, 1.0)}}) {
          dag.evaluate(u, tie, reference);
          dag.evaluate_roots(u, tie, scratch, roots);
          dag.evaluate_root_values(u, tie, scratch, values);
          dag.evaluate_root_gradients(u, tie, scratch, first);
          ASSERT_EQ(roots.size(), ids.size());
          ASSERT_EQ(values.size(), ids.size());
          ASSERT_EQ(first.size(), ids.size());
          for (std::size_t i = 0; i < ids.size(); ++i) {
            const Jet& expected = reference[static_cast<std::size_t>(ids[i])];
            ASSERT_TRUE(same_bits(roots[i], expected))
                << config.name << " n " << n << " root " << i << " at " << u.transpose();
            ASSERT_EQ(bits_of(values[i]), bits_of(expected.value)) << config.name << " n " << n;
            // Values and gradients: the reference's bits; the Hessian is not computed (+0).
            Jet without_hessian = expected;
            without_hessian.hessian.setZero();
            ASSERT_TRUE(same_bits(first[i], without_hessian))
                << config.name << " n " << n << " root " << i << " at " << u.transpose();
            non_zero += expected.value != 0.0;
            on_hessian += !expected.hessian.isZero(0.0);
          }
          ++points;
        }
      }
      // The probes reach the supports and the second derivatives (degree >= 2).
      EXPECT_GT(non_zero, points) << config.name << " n " << n;
      if (n >= 2) {
        EXPECT_GT(on_hessian, points / 2) << config.name << " n " << n;
      }
    }
  }
}

TEST(DmsKernel, RootsMatchAPlainRecursionToRounding) {
  SimplexSplineDag::Scratch scratch;
  std::vector<Jet> roots;
  for (int n = 1; n <= 5; ++n) {
    std::mt19937 rng(200 + n);
    for (const Configuration& config : configurations(n, rng)) {
      SimplexSplineDag dag(config.knots);
      const std::vector<std::uint32_t> masks = root_masks(n, rng);
      for (const std::uint32_t mask : masks) dag.add(mask);
      std::vector<std::vector<Eigen::Vector2d>> sets;
      for (const std::uint32_t mask : masks) {
        sets.emplace_back();
        for (std::size_t k = 0; k < config.knots.size(); ++k) {
          if (mask & (1u << k)) sets.back().push_back(config.knots[k]);
        }
      }
      std::vector<Eigen::Vector2d> points = probe_points(config.knots, rng);
      points.resize(std::min<std::size_t>(points.size(), 70));  // the recursion is exponential
      for (const Eigen::Vector2d& u : points) {
        const TieBreak tie{Eigen::Vector2d(0.6, 0.8)};
        dag.evaluate_roots(u, tie, scratch, roots);
        for (std::size_t i = 0; i < masks.size(); ++i) {
          const Plain plain = recursive_jet(sets[i], u, tie);
          // Both evaluations round each term by a few ulps (lambda anchored elsewhere, another
          // order of sums): 1e-13 of the terms' size is ~500 ulps, far below any wrong term.
          const double tolerance[3] = {1e-13 * plain.value_size, 1e-13 * plain.gradient_size,
                                       1e-13 * plain.hessian_size};
          EXPECT_NEAR(roots[i].value, plain.jet.value, tolerance[0]) << config.name << " " << n;
          for (int a = 0; a < 2; ++a) {
            EXPECT_NEAR(roots[i].gradient[a], plain.jet.gradient[a], tolerance[1]) << config.name;
          }
          for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(roots[i].hessian[a], plain.jet.hessian[a], tolerance[2]) << config.name;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace spline
