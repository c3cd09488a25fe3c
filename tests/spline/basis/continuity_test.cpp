// Smoothness of the DMS basis: C^(n-1) across interior domain edges (one-sided exact derivatives
// of all orders through the tie-break), and finite-difference checks of gradients and Hessians.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "spline/basis/planar_fixtures.h"
#include "spline/basis/orientation.h"
#include "spline/basis/planar_space.h"
#include "spline/basis/simplex_spline.h"
#include "spline/knots/knot_cloud.h"

namespace spline {
namespace {

using testing::inner_triangles;
using testing::perturbed_grid;
using testing::random_point_in;

// Distance from u to the nearest line through two knots of the given clouds.
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

std::vector<Eigen::Vector2d> triangle_knots(const PlanarDmsSpace& space, int t) {
  std::vector<Eigen::Vector2d> knots;
  for (int k = 0; k < 3; ++k) {
    const KnotCloud& c = space.clouds()[space.triangulation().triangles[t][k]];
    knots.insert(knots.end(), c.knots.begin(), c.knots.end());
  }
  return knots;
}

// Points on both sides of the line p -> q, about 1e-12 of the edge length away from u, and their
// distances to the line.
struct Straddle {
  Eigen::Vector2d left, right;
  double left_distance, right_distance;
};
Straddle straddle(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& u) {
  const Eigen::Vector2d normal = Eigen::Vector2d(-(q - p).y(), (q - p).x());
  Straddle s{u + 1e-12 * normal, u - 1e-12 * normal, 0.0, 0.0};
  EXPECT_GT(orient2d(p, q, s.left), 0);
  EXPECT_LT(orient2d(p, q, s.right), 0);
  const Eigen::Vector2d unit = normal.normalized();
  s.left_distance = unit.dot(s.left - p);
  s.right_distance = -unit.dot(s.right - p);
  return s;
}

// Jump of the order-k derivative across the line from one-sided values at distances dl, dr:
// a_k - b_k minus the first-order Taylor terms dl a_{k+1} + dr b_{k+1} (residual O(d^2 D^{k+2})).
double jump(const double* a, const double* b, int k, double dl, double dr) {
  return a[k] - b[k] - (dl * a[k + 1] + dr * b[k + 1]);
}

// For every interior edge of inner triangles, at a random point on it: derivatives of order
// 0..n-1 across the edge agree on both sides (1e-12 of the edge length away), for every basis
// function; order n jumps. (A computed point p + s (q - p) is rarely exactly on the line, so the
// exact-on-line tie-break is tested apart, on dyadic knots.)
TEST(DmsContinuity, DerivativesUpToOrderNMinusOneAgreeAcrossEdges) {
  for (int n = 2; n <= 5; ++n) {
    const PlanarTriangulation t = perturbed_grid(5, 0.3, 40 + n);
    const PlanarDmsSpace space(t, make_knot_clouds(t, n));
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> unit(0.2, 0.8);
    double largest_order_n_jump = 0.0;
    int edges = 0;
    for (int i : inner_triangles(t)) {
      const Eigen::Vector3i& tri = t.triangles[static_cast<std::size_t>(i)];
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& p = t.positions[tri[k]];
        const Eigen::Vector2d& q = t.positions[tri[(k + 1) % 3]];
        const Eigen::Vector2d u = p + unit(rng) * (q - p);
        const Eigen::Vector2d normal = Eigen::Vector2d(-(q - p).y(), (q - p).x()).normalized();
        const Straddle side = straddle(p, q, u);
        ++edges;
        for (int tri_id : space.candidate_triangles(u)) {
          const TriangleBasis& basis = space.triangle_basis(tri_id);
          std::vector<double> left, right, scratch;
          basis.evaluate_directional(side.left, normal, n, {}, left, scratch);
          basis.evaluate_directional(side.right, normal, n, {}, right, scratch);
          for (int f = 0; f < basis.size(); ++f) {
            const double* a = &left[static_cast<std::size_t>(f * (n + 1))];
            const double* b = &right[static_cast<std::size_t>(f * (n + 1))];
            for (int order = 0; order < n; ++order) {
              // Rounding in D^k grows with the higher derivatives (a near-collinear knot triple
              // gives D^n ~ 1e12 while D^k ~ 1e-8): eps-level terms L^(j-k) |D^j| (j > k).
              const double scale = std::max({std::abs(a[order]), std::abs(b[order]), 1.0});
              double higher = 0.0;
              for (int j = order + 1; j <= n; ++j) {
                higher += std::pow((q - p).norm(), j - order) *
                          std::max(std::abs(a[j]), std::abs(b[j]));
              }
              ASSERT_LT(std::abs(jump(a, b, order, side.left_distance, side.right_distance)),
                        1e-8 * scale + 1e-14 * higher)
                  << "degree " << n << " order " << order << " triangle " << tri_id;
            }
            const double scale = std::max({std::abs(a[n]), std::abs(b[n]), 1.0});
            largest_order_n_jump = std::max(largest_order_n_jump, std::abs(a[n] - b[n]) / scale);
          }
        }
      }
    }
    EXPECT_GT(edges, 10);
    // The tie-break really picks sides: the degree-n derivative jumps across knot lines.
    EXPECT_GT(largest_order_n_jump, 1e-3) << "degree " << n;
  }
}

// The same for a spline with random control points, through PlanarDmsSpace.
TEST(DmsContinuity, SplineWithRandomControlPointsIsSmoothAcrossEdges) {
  for (int n = 2; n <= 5; ++n) {
    const PlanarTriangulation t = testing::ring_disk(3, 60 + n);
    const PlanarDmsSpace space(t, make_knot_clouds(t, n));
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), inside(0.2, 0.8);
    const Eigen::MatrixXd control =
        Eigen::MatrixXd::NullaryExpr(space.function_count(), 3, [&]() { return unit(rng); });
    for (int i : inner_triangles(t)) {
      const Eigen::Vector3i& tri = t.triangles[static_cast<std::size_t>(i)];
      const Eigen::Vector2d& p = t.positions[tri[0]];
      const Eigen::Vector2d& q = t.positions[tri[1]];
      const Eigen::Vector2d u = p + inside(rng) * (q - p);
      const Eigen::Vector2d normal = Eigen::Vector2d(-(q - p).y(), (q - p).x()).normalized();
      const Straddle side = straddle(p, q, u);
      const Eigen::MatrixXd a = space.evaluate_directional(control, side.left, normal, n);
      const Eigen::MatrixXd b = space.evaluate_directional(control, side.right, normal, n);
      for (int order = 0; order < n; ++order) {
        const double scale = std::max(1.0, a.row(order).norm());
        const Eigen::RowVectorXd difference =
            a.row(order) - b.row(order) -
            (side.left_distance * a.row(order + 1) + side.right_distance * b.row(order + 1));
        ASSERT_LT(difference.norm(), 1e-8 * scale) << "degree " << n << " order " << order;
      }
    }
  }
}

// Knots with dyadic coordinates: points exactly on a knot line, one-sided derivatives through the
// tie-break equal the limits from each side, and orders < n agree.
TEST(DmsContinuity, TieBreakGivesOneSidedDerivativesOnKnotLines) {
  for (int n = 2; n <= 5; ++n) {
    std::vector<Eigen::Vector2d> knots = {{0, 0}, {4, 0}, {1, 3}, {3, -2}, {2, 2.5}, {0.5, -1.5},
                                          {3.5, 1.25}, {1.75, -0.75}};
    knots.resize(static_cast<std::size_t>(n + 3));
    const Eigen::Vector2d u(1.5, 0.0);  // on the knot line y = 0 through knots 0 and 1
    const Eigen::Vector2d d(0.0, 1.0);
    const std::vector<double> up = simplex_spline_directional(knots, u, d, n, TieBreak{d});
    const std::vector<double> down = simplex_spline_directional(knots, u, d, n, TieBreak{-d});
    const std::vector<double> above = simplex_spline_directional(knots, u + 1e-13 * d, d, n);
    const std::vector<double> below = simplex_spline_directional(knots, u - 1e-13 * d, d, n);
    for (int k = 0; k <= n; ++k) {
      const double scale = std::max({std::abs(up[k]), std::abs(down[k]), 1e-3});
      EXPECT_NEAR(up[k], above[k], 1e-9 * scale) << "degree " << n << " order " << k;
      EXPECT_NEAR(down[k], below[k], 1e-9 * scale) << "degree " << n << " order " << k;
      if (k < n) {
        EXPECT_NEAR(up[k], down[k], 1e-9 * scale) << "degree " << n << " order " << k;
      }
    }
    EXPECT_GT(std::abs(up[n] - down[n]), 1e-6) << "degree " << n;
  }
}

// Central differences at steps h and h/2, Richardson-extrapolated: the O(h^2) error term, which
// near-collinear knot triples make large (D^4 ~ 1e9), cancels exactly on a polynomial piece of
// degree <= 4 and leaves O(h^4 D^6) otherwise; points stay 200 h away from every knot line.
TEST(DmsContinuity, BasisGradientsAndHessiansMatchFiniteDifferences) {
  for (int n = 2; n <= 5; ++n) {
    const PlanarTriangulation t = perturbed_grid(4, 0.3, 80 + n);
    const PlanarDmsSpace space(t, make_knot_clouds(t, n));
    std::mt19937 rng(n);
    const double h = 1e-6;
    int checked = 0;
    for (int i = 0; i < space.triangle_count() && checked < 40; ++i) {
      const Eigen::Vector2d u = random_point_in(t, i, rng);
      for (int tri_id : space.candidate_triangles(u)) {
        if (distance_to_knot_lines(triangle_knots(space, tri_id), u) < 200 * h) continue;
        ++checked;
        const TriangleBasis& basis = space.triangle_basis(tri_id);
        std::vector<Jet> jets;
        SimplexSplineDag::Scratch scratch;
        basis.evaluate(u, {}, jets, scratch);
        // Relative to the largest derivatives among the triangle's functions at u (a function
        // nearly zero at u still carries the rounding of its neighbours' scale).
        double scale = 0.0;
        for (const Jet& j : jets) scale = std::max(scale, j.hessian.norm() + j.gradient.norm());
        for (int axis = 0; axis < 2; ++axis) {
          std::vector<Jet> differences[2];  // (F(u + s e) - F(u - s e)) / 2s for s = h, h/2
          for (int level = 0; level < 2; ++level) {
            const double step = level == 0 ? h : 0.5 * h;
            std::vector<Jet> plus, minus;
            basis.evaluate(u + step * Eigen::Vector2d::Unit(axis), {}, plus, scratch);
            basis.evaluate(u - step * Eigen::Vector2d::Unit(axis), {}, minus, scratch);
            for (std::size_t f = 0; f < jets.size(); ++f) {
              Jet d;
              d.value = (plus[f].value - minus[f].value) / (2 * step);
              d.gradient = (plus[f].gradient - minus[f].gradient) / (2 * step);
              differences[level].push_back(d);
            }
          }
          for (std::size_t f = 0; f < jets.size(); ++f) {
            const double fd_value =
                (4.0 * differences[1][f].value - differences[0][f].value) / 3.0;
            const Eigen::Vector2d fd_gradient =
                (4.0 * differences[1][f].gradient - differences[0][f].gradient) / 3.0;
            EXPECT_NEAR(fd_value, jets[f].gradient[axis],
                        1e-6 * (jets[f].gradient.norm() + 1e-3 * scale))
                << "degree " << n;
            const Eigen::Vector2d exact =
                axis == 0 ? Eigen::Vector2d(jets[f].hessian[0], jets[f].hessian[1])
                          : Eigen::Vector2d(jets[f].hessian[1], jets[f].hessian[2]);
            EXPECT_LE((fd_gradient - exact).norm(), 1e-6 * (jets[f].hessian.norm() + 1e-3 * scale))
                << "degree " << n;
          }
        }
      }
    }
    EXPECT_GE(checked, 20) << "degree " << n;
  }
}

}  // namespace
}  // namespace spline
