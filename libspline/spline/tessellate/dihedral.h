#pragma once
// Smoothness of a tessellated surface seen as a user sees it: the angle between the normals of
// every two triangles sharing an edge. A smooth surface sampled finely turns by a few degrees
// per triangle; a fold of the spline (it doubles back within a sample step) shows as an angle
// near 180 degrees, a crease as tens of degrees.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace spline {

struct DihedralReport {
  int edges = 0;  ///< Interior edges measured (two triangles, both non-degenerate).
  double median_deg = 0.0, p99_deg = 0.0, max_deg = 0.0;
  int over_60_deg = 0;  ///< Edges whose triangles' normals differ by more than 60 degrees.
  int over_90_deg = 0;  ///< ... by more than 90 degrees: the surface folds back there.
  /// Where: the edges over 90 degrees (position indices, smaller first), in edge order.
  std::vector<std::array<int, 2>> fold_edges;
};

/// Angles between the normals of the two triangles at every edge shared by exactly two
/// triangles (position indices; degenerate triangles are left out).
[[nodiscard]] DihedralReport dihedral_angles(const std::vector<std::array<int, 3>>& triangles,
                                             const Eigen::MatrixX3d& positions);

/// Where a surface's folds lie (issue 20: a fold next to the cone, on its patch or elsewhere).
struct FoldPlaces {
  int on_patches = 0;  ///< Both ends on a fill patch's triangles.
  int near_cone = 0;   ///< On the spline, midpoint within the given radius of the cone.
  int elsewhere = 0;   ///< On the spline, farther.
  /// Median distance of the spline's fold midpoints from the cone (0 when none).
  double median_cone_distance = 0.0;
};

/// Sorts fold edges (position indices, e.g. DihedralReport::fold_edges) by place: on a patch
/// when both ends are marked in `on_patch` (by position), else near the cone when the edge's
/// midpoint lies within `radius` of `cone`, else elsewhere.
/// \throw ricci::InvalidInputError when on_patch's size is not positions' row count, an index
///        is out of range or radius is negative or not finite.
[[nodiscard]] FoldPlaces fold_places(const std::vector<std::array<int, 2>>& fold_edges,
                                     const Eigen::MatrixX3d& positions,
                                     const std::vector<char>& on_patch,
                                     const Eigen::Vector3d& cone, double radius);

}  // namespace spline
