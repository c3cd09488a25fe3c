#pragma once
// Internal to hole filling: the patch's planar domain D (a convex polygon) and triangulations of
// nested copies of it (the patch's spline triangulation and its tessellation).
#include <Eigen/Core>
#include <vector>

#include "spline/fill/hole_fill.h"
#include "spline/planar/triangulation.h"

namespace spline::fill_detail {

[[nodiscard]] double polygon_perimeter(const std::vector<Eigen::Vector2d>& polygon);
/// The mean of the polygon's points.
[[nodiscard]] Eigen::Vector2d polygon_mean(const std::vector<Eigen::Vector2d>& polygon);
/// Signed area (positive counter-clockwise).
[[nodiscard]] double polygon_area(const std::vector<Eigen::Vector2d>& polygon);

/// n points by arc length along the closed polygon scaled by s about `center`, from its corner 0.
[[nodiscard]] std::vector<Eigen::Vector2d> sample_scaled_polygon(
    const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& center, double scale,
    int n);

/// Triangulates the region bounded by `outer` (counter-clockwise points on a convex curve around
/// `center`) with rings = copies of the convex counter-clockwise `shape` scaled about `center`
/// by `scales` (decreasing, below the outer ring's), then a fan to the centre. Ring r gets about
/// perimeter(shape) * scales[r] / spacing points. Vertex i of the result is outer[i] for
/// i < outer.size(); triangles are counter-clockwise, each diagonal the shorter valid one.
[[nodiscard]] PlanarTriangulation nested_rings(const std::vector<Eigen::Vector2d>& outer,
                                               const std::vector<Eigen::Vector2d>& shape,
                                               const Eigen::Vector2d& center,
                                               const std::vector<double>& scales, double spacing);

/// A regular grid of equilateral triangles (side `spacing`, counter-clockwise) covering the box
/// [lo, hi]. Its knot clouds are jittered by make_knot_cloud, which breaks the grid's
/// coincidences.
[[nodiscard]] PlanarTriangulation triangle_grid(const Eigen::Vector2d& lo,
                                                const Eigen::Vector2d& hi, double spacing);

/// A closed polygon with its edges bucketed by cells of a given size, for inside tests and
/// distances of many points (the patch grid's triangles) in about constant time each.
class PolygonRegion {
 public:
  /// \pre polygon.size() >= 3, cell > 0.
  PolygonRegion(const std::vector<Eigen::Vector2d>& polygon, double cell);
  /// Inside the polygon (crossing number: a simple polygon's interior, either orientation).
  [[nodiscard]] bool contains(const Eigen::Vector2d& p) const;
  /// The distance from p to the polygon's edges when it is below `limit`, else `limit`.
  [[nodiscard]] double distance(const Eigen::Vector2d& p, double limit) const;

 private:
  [[nodiscard]] double edge_distance(int edge, const Eigen::Vector2d& p) const;
  std::vector<Eigen::Vector2d> points_;
  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<std::vector<int>> strips_;  ///< by cell row: the edges whose y range meets it
  std::vector<std::vector<int>> cells_;   ///< by cell: the edges whose box meets it
};

/// True when the closed polygon has no two non-adjacent edges meeting.
[[nodiscard]] bool is_simple(const std::vector<Eigen::Vector2d>& polygon);

/// Smallest sine of the angle each edge of the closed polygon subtends from c: positive iff the
/// counter-clockwise polygon is star-shaped from c.
[[nodiscard]] double star_margin(const std::vector<Eigen::Vector2d>& polygon,
                                 const Eigen::Vector2d& c);

/// A point from which the closed counter-clockwise polygon is star-shaped (every edge seen
/// counter-clockwise), tried among the area centroid, the vertex mean and a grid of points of its
/// box; the best by the smallest normalised turn. False when none.
[[nodiscard]] bool star_center(const std::vector<Eigen::Vector2d>& polygon,
                               Eigen::Vector2d& center);

/// Scales s = start, start - step, ... down to the last above 0.75 step (the fan then closes the
/// rest: its triangles are about one ring step high).
[[nodiscard]] std::vector<double> ring_scales(double start, double step);

/// A rim edge in its face's chart: the chart, the edge's end points there, and the tie-break
/// that evaluates points on the edge one-sided, in the face (towards its opposite corner).
struct RimChartEdge {
  int chart = -1;
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
  TieBreak tie;
};
[[nodiscard]] RimChartEdge rim_chart_edge(const ManifoldSplineSpace& space, const RimEdge& edge);

/// The surrounding surface at rim sample (edge, t), evaluated in the edge's face one-sided
/// (tie-break towards the face's interior), with the edge's chart geometry.
struct RimSample {
  SurfaceJet jet;
  Eigen::Vector3d outward_derivative;  ///< dS along the chart's unit normal leaving the face
  Eigen::Vector3d along_derivative;    ///< dS/dt along the rim edge
  double chart_length = 0.0;           ///< the rim edge's length in the chart
};
[[nodiscard]] RimSample sample_rim(const ManifoldSpline& spline, const RimEdge& edge, double t);

/// Where a rim edge is sampled to meet or measure a seam: t = i / per_edge (i = 0..per_edge);
/// in the kRimEndIntervals intervals next to each end kRimEndRefinement times as densely; and
/// in the first and last of those finer intervals kRimEndSamples more, halving towards the end.
/// Next to a rim vertex the surface's normal can turn within its knot cloud, over a sliver far
/// narrower than 1 / per_edge. Sorted ascending, no repeats. \pre per_edge >= 1.
inline constexpr int kRimEndIntervals = 4;
inline constexpr int kRimEndRefinement = 8;
inline constexpr int kRimEndSamples = 12;
[[nodiscard]] std::vector<double> rim_edge_parameters(int per_edge);

/// The parameters measure_seam samples rim edge `edge` of `fill` at: rim_edge_parameters(
/// per_edge) and those its refinement adds where the surface's or the patch's normal turns fast
/// between them. Sorted ascending.
[[nodiscard]] std::vector<double> seam_parameters(const ManifoldSpline& spline,
                                                  const HoleFill& fill, int edge, int per_edge);

}  // namespace spline::fill_detail
