#pragma once
// Triangulating the inside of a simple planar polygon (a hole patch's parameter domain that is not
// star-shaped, so no fan or nested rings from one centre fits it).
#include <Eigen/Core>
#include <vector>

namespace ricci {

/// A triangulation of the region inside a polygon.
struct RegionTriangulation {
  /// The polygon's points first, in their order (index i is boundary[i]), then interior points.
  std::vector<Eigen::Vector2d> positions;
  std::vector<Eigen::Vector3i> triangles;  ///< counter-clockwise
};

/// Triangulates the inside of the simple counter-clockwise polygon `boundary`, with interior
/// points on an equilateral lattice of side `spacing` (those at least spacing / 2 from the
/// boundary): the constrained Delaunay triangulation (CGAL) holding every side of the polygon
/// as an edge, with no point added on the sides.
/// \throw InvalidInputError when the polygon has fewer than 3 points, repeats a point, is not
///        simple or not counter-clockwise, or spacing is not positive and finite; or when the
///        lattice would exceed 4 million points.
[[nodiscard]] RegionTriangulation triangulate_region(const std::vector<Eigen::Vector2d>& boundary,
                                                     double spacing);

}  // namespace ricci
