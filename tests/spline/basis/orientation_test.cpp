// accurate_det2d (orientation.h): the DAG build's determinants. Its compensated fast path must be
// as accurate as the exact expansion it replaces away from slivers (the correctly rounded value),
// and slivers must still come out within an ulp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "spline/basis/orientation.h"

namespace spline {
namespace {

__extension__ typedef __float128 Quad;  // 113-bit significand: exact reference below

// Coordinates are multiples of 2^-40 below 2^9 in magnitude (50-bit integers): differences fit
// 51 bits, their products 102 and the determinant 103, so the Quad evaluation is exact and its
// rounding to double is the correctly rounded determinant.
constexpr double kGrid = 0x1p-40;

double on_grid(double x) { return std::round(x / kGrid) * kGrid; }

Eigen::Vector2d grid_point(const Eigen::Vector2d& p) { return {on_grid(p.x()), on_grid(p.y())}; }

double rounded_determinant(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                           const Eigen::Vector2d& c) {
  const Quad dx1 = Quad(b.x()) - Quad(a.x()), dy1 = Quad(b.y()) - Quad(a.y());
  const Quad dx2 = Quad(c.x()) - Quad(a.x()), dy2 = Quad(c.y()) - Quad(a.y());
  return static_cast<double>(dx1 * dy2 - dy1 * dx2);
}

double ulps_apart(double value, double reference) {
  const double ulp = std::nextafter(std::abs(reference), INFINITY) - std::abs(reference);
  return std::abs(value - reference) / ulp;
}

TEST(AccurateDet2d, CorrectlyRoundedOnGeneralAndThinTriples) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const double scale = std::pow(10.0, 2.0 * unit(rng) - 1.0);
    const Eigen::Vector2d origin(100.0 * unit(rng), 100.0 * unit(rng));
    const Eigen::Vector2d a = grid_point(origin + scale * Eigen::Vector2d(unit(rng), unit(rng)));
    // Thin: b in a cloud of radius 1e-6 scale around a (two knots of one cloud, a far one).
    const double b_radius = i % 2 == 0 ? scale : 1e-6 * scale;
    const Eigen::Vector2d b = grid_point(a + b_radius * Eigen::Vector2d(unit(rng), unit(rng)));
    const Eigen::Vector2d c = grid_point(origin + scale * Eigen::Vector2d(unit(rng), unit(rng)));
    const double reference = rounded_determinant(a, b, c);
    if (reference == 0.0) continue;
    ASSERT_EQ(accurate_det2d(a, b, c), reference) << i;
  }
}

TEST(AccurateDet2d, NearlyCollinearWithinAnUlp) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const Eigen::Vector2d a = grid_point(Eigen::Vector2d(50.0 * unit(rng), 50.0 * unit(rng)));
    const double length = std::pow(10.0, 2.0 * unit(rng));
    const Eigen::Vector2d b = grid_point(a + length * Eigen::Vector2d(unit(rng), unit(rng)));
    // c on the line a-b up to a few grid steps: the products cancel to 1e-14..1e-10 of their
    // size, on both sides of the fast path's filter (~6e-14).
    const Eigen::Vector2d offset = kGrid * Eigen::Vector2d(std::round(4.0 * unit(rng)), 0.0);
    const Eigen::Vector2d c = grid_point(a + 2.0 * unit(rng) * (b - a)) + offset;
    const double reference = rounded_determinant(a, b, c);
    if (reference == 0.0) {
      ASSERT_EQ(accurate_det2d(a, b, c), 0.0) << i;
      continue;
    }
    ASSERT_LE(ulps_apart(accurate_det2d(a, b, c), reference), 1.0) << i;
  }
}

}  // namespace
}  // namespace spline
