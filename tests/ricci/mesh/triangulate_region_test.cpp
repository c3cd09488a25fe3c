#include "ricci/mesh/triangulate_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "ricci/mesh/errors.h"

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double polygon_area(const std::vector<Eigen::Vector2d>& p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * sum;
}

// A comb: a bar with `teeth` deep slots cut into it (far from star-shaped), counter-clockwise,
// each side sampled every `step`.
std::vector<Eigen::Vector2d> comb(int teeth, double step) {
  std::vector<Eigen::Vector2d> corners{{0, 0}, {2.0 * teeth - 1, 0}};
  for (int t = teeth - 1; t >= 0; --t) {
    corners.emplace_back(2.0 * t + 1, 4);
    corners.emplace_back(2.0 * t, 4);
    if (t > 0) {
      corners.emplace_back(2.0 * t, 1);
      corners.emplace_back(2.0 * t - 1, 1);
    }
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d a = corners[i], b = corners[(i + 1) % corners.size()];
    const int n = std::max(1, static_cast<int>(std::lround((b - a).norm() / step)));
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / n));
  }
  return out;
}

TEST(TriangulateRegion, CombIsCoveredOnceWithItsBoundaryKeptAndInnerPoints) {
  const auto boundary = comb(4, 0.1);
  const auto t = ricci::triangulate_region(boundary, 0.1);
  ASSERT_GT(t.positions.size(), boundary.size());
  for (std::size_t i = 0; i < boundary.size(); ++i) EXPECT_EQ(t.positions[i], boundary[i]);
  // Every triangle counter-clockwise, areas summing to the polygon's: the inside, once.
  double area = 0.0;
  std::map<std::pair<int, int>, int> edges;
  for (const auto& tri : t.triangles) {
    const double a = 0.5 * cross(t.positions[tri[1]] - t.positions[tri[0]],
                                 t.positions[tri[2]] - t.positions[tri[0]]);
    EXPECT_GT(a, 0.0);
    area += a;
    for (int k = 0; k < 3; ++k) ++edges[{tri[k], tri[(k + 1) % 3]}];
  }
  EXPECT_NEAR(area, polygon_area(boundary), 1e-12 * polygon_area(boundary));
  // Each side of the polygon is an edge of exactly one triangle, in the polygon's direction;
  // every other edge is shared by two triangles in opposite directions.
  const int n = static_cast<int>(boundary.size());
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    const bool side = edge.first < n && edge.second == (edge.first + 1) % n;
    EXPECT_EQ(edges.count({edge.second, edge.first}) == 0, side);
  }
  for (int i = 0; i < n; ++i) EXPECT_EQ(edges.count({i, (i + 1) % n}), 1u);
  // Inner points keep half a spacing from the boundary.
  for (std::size_t i = boundary.size(); i < t.positions.size(); ++i) {
    for (const auto& b : boundary) EXPECT_GT((t.positions[i] - b).norm(), 0.05 - 1e-12);
  }
}

TEST(TriangulateRegion, RefusesBadPolygons) {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NO_THROW((void)ricci::triangulate_region(square, 0.25));
  const std::vector<Eigen::Vector2d> clockwise(square.rbegin(), square.rend());
  EXPECT_THROW((void)ricci::triangulate_region(clockwise, 0.25), ricci::InvalidInputError);
  const std::vector<Eigen::Vector2d> bowtie{{0, 0}, {1, 1}, {2, 0}, {2, 1}, {1, 0}, {0, 1.5}};
  EXPECT_THROW((void)ricci::triangulate_region(bowtie, 0.25), ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::triangulate_region({{0, 0}, {1, 0}}, 0.25), ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::triangulate_region(square, 0.0), ricci::InvalidInputError);
}

}  // namespace
