// Longest-edge bisection (spline/planar/bisect.h): conforming, area-preserving, graded to the
// size asked, angles bounded, and a valid DMS space (partition of unity) on the result.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <utility>

#include "ricci/mesh/errors.h"
#include "spline/basis/planar_space.h"
#include "spline/knots/knot_cloud.h"
#include "spline/planar/bisect.h"
#include "spline/planar/perturbed_grid.h"

namespace spline {
namespace {

double signed_area(const PlanarTriangulation& t, const Eigen::Vector3i& v) {
  const Eigen::Vector2d a = t.positions[v[0]], b = t.positions[v[1]], c = t.positions[v[2]];
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

double total_area(const PlanarTriangulation& t) {
  double sum = 0.0;
  for (const auto& v : t.triangles) sum += signed_area(t, v);
  return sum;
}

// Total length of the edges with one triangle: the outer boundary only when the triangulation
// is conforming (a hanging vertex adds the split edge's length on both sides of it).
double single_sided_length(const PlanarTriangulation& t) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& v : t.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = v[k], b = v[(k + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  double length = 0.0;
  for (const auto& [edge, n] : count) {
    EXPECT_LE(n, 2) << "edge " << edge.first << "-" << edge.second << " in " << n << " triangles";
    if (n == 1) length += (t.positions[edge.first] - t.positions[edge.second]).norm();
  }
  return length;
}

double smallest_angle(const PlanarTriangulation& t) {
  double smallest = M_PI;
  for (const auto& v : t.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = t.positions[v[(k + 1) % 3]] - t.positions[v[k]];
      const Eigen::Vector2d b = t.positions[v[(k + 2) % 3]] - t.positions[v[k]];
      smallest = std::min(smallest, std::acos(a.normalized().dot(b.normalized())));
    }
  }
  return smallest;
}

double longest_edge(const PlanarTriangulation& t, const Eigen::Vector3i& v) {
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (t.positions[v[k]] - t.positions[v[(k + 1) % 3]]).norm());
  return longest;
}

// Graded around a point: fine + distance, unbounded beyond 0.5.
double graded(const Eigen::Vector2d& x) {
  const double size = 0.01 + (x - Eigen::Vector2d(0.3, 0.55)).norm();
  return size < 0.5 ? size : 1e300;
}

TEST(RefineToSize, ConformingAreaPreservingAndGraded) {
  PlanarTriangulation t = perturbed_grid(6, 0.3, 7);
  const double area = total_area(t), boundary = single_sided_length(t);
  const double angle = smallest_angle(t);
  const std::size_t before = t.triangles.size();
  refine_to_size(t, graded);
  EXPECT_GT(t.triangles.size(), before + 100);
  validate(t);  // counter-clockwise, indices in range
  EXPECT_NEAR(total_area(t), area, 1e-12);
  EXPECT_NEAR(single_sided_length(t), boundary, 1e-12);
  for (const auto& v : t.triangles) {
    const Eigen::Vector2d centre =
        (t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0;
    EXPECT_LE(longest_edge(t, v), graded(centre));
  }
  // Rivara: the smallest angle is at least half the initial one.
  EXPECT_GE(smallest_angle(t), 0.5 * angle);
}

TEST(RefineToSize, DmsSpaceOnTheRefinedTriangulationIsAPartitionOfUnity) {
  PlanarTriangulation t = perturbed_grid(4, 0.2, 3);
  refine_to_size(t, [](const Eigen::Vector2d& x) {
    const double size = 0.02 + (x - Eigen::Vector2d(0.5, 0.5)).norm();
    return size < 0.4 ? size : 1e300;
  });
  const PlanarDmsSpace space(t, make_knot_clouds(t, 3, KnotCloudOptions{}));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> inner(0.3, 0.7);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d u(inner(rng), inner(rng));
    double sum = 0.0;
    for (const auto& s : space.evaluate_basis(u)) sum += s.jet.value;
    ASSERT_NEAR(sum, 1.0, 1e-11) << "at " << u.transpose();
  }
}

TEST(RefineToSize, StopsAtTheTriangleCap) {
  PlanarTriangulation t = perturbed_grid(4, 0.2, 3);
  refine_to_size(t, [](const Eigen::Vector2d&) { return 1e-6; }, 500);
  EXPECT_GE(t.triangles.size(), 500u);
  EXPECT_LT(t.triangles.size(), 600u);  // one split adds a path of pairs at most
  validate(t);
}

TEST(RefineToSize, RejectsABadSize) {
  PlanarTriangulation t = perturbed_grid(3, 0.2, 3);
  EXPECT_THROW(refine_to_size(t, [](const Eigen::Vector2d&) { return 0.0; }),
               ricci::InvalidInputError);
  EXPECT_THROW(refine_to_size(t, [](const Eigen::Vector2d&) { return NAN; }),
               ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
