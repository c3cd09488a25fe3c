#include "spline/tessellate/dihedral.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "ricci/mesh/errors.h"
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

FoldPlaces fold_places(const std::vector<std::array<int, 2>>& fold_edges,
                       const Eigen::MatrixX3d& positions, const std::vector<char>& on_patch,
                       const Eigen::Vector3d& cone, double radius) {
  const auto n = static_cast<int>(positions.rows());
  if (static_cast<int>(on_patch.size()) != n || !(radius >= 0.0) || !std::isfinite(radius)) {
    throw ricci::InvalidInputError("fold_places: " + std::to_string(on_patch.size()) +
                                   " patch marks for " + std::to_string(n) +
                                   " positions, radius " + std::to_string(radius));
  }
  FoldPlaces places;
  std::vector<double> distances;
  for (const auto& e : fold_edges) {
    if (e[0] < 0 || e[0] >= n || e[1] < 0 || e[1] >= n)
      throw ricci::InvalidInputError("fold_places: a fold edge's position is out of range");
    if (on_patch[static_cast<std::size_t>(e[0])] && on_patch[static_cast<std::size_t>(e[1])]) {
      ++places.on_patches;
      continue;
    }
    const Eigen::Vector3d mid = 0.5 * (positions.row(e[0]) + positions.row(e[1])).transpose();
    const double d = (mid - cone).norm();
    distances.push_back(d);
    ++(d <= radius ? places.near_cone : places.elsewhere);
  }
  if (!distances.empty()) {
    const auto middle = distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2);
    std::nth_element(distances.begin(), middle, distances.end());
    places.median_cone_distance = *middle;
  }
  return places;
}

}  // namespace spline
