#include "spline/tessellate/dihedral.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "ricci/mesh/mesh.h"
#include "spline/tessellate/triangle_sides.h"

namespace spline {

DihedralReport dihedral_angles(const std::vector<std::array<int, 3>>& triangles,
                               const Eigen::MatrixX3d& positions) {
  std::vector<Eigen::Vector3d> normals(triangles.size());
  std::vector<char> degenerate(triangles.size(), 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Eigen::Vector3d a = positions.row(tri[0]), b = positions.row(tri[1]),
                          c = positions.row(tri[2]);
    normals[t] = (b - a).cross(c - a);
    degenerate[t] = !(normals[t].norm() > 0.0);
  }
  // Each directed edge (a, b) with its triangle, sorted so an edge's two sides meet.
  const std::vector<std::pair<std::uint64_t, int>> sides =
      sorted_triangle_sides(triangles, degenerate, static_cast<int>(positions.rows()));
  std::vector<double> angles;
  DihedralReport report;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].first == sides[i].first) ++j;
    if (j - i == 2) {
      const double angle =
          ricci::angle_between(normals[sides[i].second], normals[sides[i + 1].second]);
      angles.push_back(angle * 180.0 / M_PI);
      if (angles.back() > 90.0) {
        report.fold_edges.push_back({static_cast<int>(sides[i].first >> 32),
                                     static_cast<int>(sides[i].first & 0xffffffffu)});
      }
    }
    i = j;
  }
  report.edges = static_cast<int>(angles.size());
  if (angles.empty()) return report;
  for (double a : angles) {
    report.over_60_deg += a > 60.0;
    report.over_90_deg += a > 90.0;
  }
  const auto at = [&](double q) {
    const auto k = static_cast<std::size_t>(q * static_cast<double>(angles.size() - 1));
    std::nth_element(angles.begin(), angles.begin() + static_cast<std::ptrdiff_t>(k), angles.end());
    return angles[k];
  };
  report.median_deg = at(0.5);
  report.p99_deg = at(0.99);
  report.max_deg = *std::max_element(angles.begin(), angles.end());
  return report;
}

}  // namespace spline
