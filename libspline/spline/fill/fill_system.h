#pragma once
// Internal to hole filling: pieces shared by the height-field patch (hole_fill.cpp) and the
// parametric G1 patch (parametric_fill.cpp): the thin-plate quadrature, the patch's spline space
// over a triangle grid, D laid out on a circle, rim names for messages.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "spline/basis/planar_space.h"
#include "spline/fill/hole_fill.h"
#include "spline/fill/patch_domain.h"

namespace spline::fill_detail {

/// A quadrature point of a triangle: barycentric coordinates, weight relative to the area.
struct QuadraturePoint {
  Eigen::Vector3d bary;
  double weight;
};

/// Thin-plate quadrature points of one triangle: Dunavant's 6-point rule (exact for degree 4)
/// on the triangle and again on its corner sub-triangles of ratio 0.3 and 0.1. Why the corners:
/// a DMS spline can carry spikes within the knot clouds (radius < inradius / 2 around each
/// vertex) that no point of the plain rule sees, and the fit would leave them in.
[[nodiscard]] std::vector<QuadraturePoint> thin_plate_rule();
/// Dunavant's 6-point rule alone, its weights scaled to thin_plate_rule's total (whose corner
/// points add 0.3 of the area): the same energy for a polynomial piece, without the corners.
[[nodiscard]] std::vector<QuadraturePoint> thin_plate_plain_rule();

/// "cone hole of 24 edges starting at face 17": names a rim in messages.
[[nodiscard]] std::string rim_name(const Rim& rim);

/// The patch's planar DMS space: a triangle grid of side `spacing` over the box of `boundary`
/// with a margin of two sides (so every function reaching D is present: partition of unity),
/// refined by longest-edge bisection (planar/bisect.h) around `corners` (D's rim vertices) to
/// sides of spacing / corner_refinement there, growing by the distance from the nearest corner (FillOptions::corner_refinement says why; <= 1: no refinement).
[[nodiscard]] std::shared_ptr<const PlanarDmsSpace> patch_space(
    const std::vector<Eigen::Vector2d>& boundary, double spacing, int degree,
    const KnotCloudOptions& knots, const std::vector<Eigen::Vector2d>& corners = {},
    int corner_refinement = 1);
/// The same with a refinement per corner (refinements[c] for corners[c]): the triangle sides
/// at a point are the smallest of spacing / refinements[c] + its distance from corners[c],
/// that distance times outside_grading at points outside the closed polygon `boundary` (where
/// the patch is not evaluated; 1: the same grading everywhere). With a finite keep_distance
/// >= 0, the grid keeps only the triangles whose centroid lies in `boundary` or within
/// keep_distance of it (before the refinement; plus those a vertex needs to keep one fan).
/// \pre refinements.size() == corners.size(), outside_grading >= 1.
[[nodiscard]] std::shared_ptr<const PlanarDmsSpace> patch_space(
    const std::vector<Eigen::Vector2d>& boundary, double spacing, int degree,
    const KnotCloudOptions& knots, const std::vector<Eigen::Vector2d>& corners,
    const std::vector<int>& refinements, double outside_grading = 1.0,
    double keep_distance = INFINITY);

/// patch_space's keep_distance for FillOptions::grid_margin at grid side `spacing` (infinite
/// when the margin is negative: the whole box).
[[nodiscard]] double grid_keep_distance(const FillOptions& options, double spacing);

/// By triangle of `space`, nonzero where its thin plate may take thin_plate_plain_rule: its
/// centroid lies outside the closed polygon `boundary` (D), more than `distance` from it. No
/// function reaching D is then nonzero there, and D is where the patch is evaluated, so the
/// spikes inside knot clouds that thin_plate_rule's corner points catch do not matter there.
/// A negative distance: none.
[[nodiscard]] std::vector<char> plain_rule_triangles(const PlanarDmsSpace& space,
                                                     const std::vector<Eigen::Vector2d>& boundary,
                                                     double distance);

/// Lays D out on a circle (radius: the rim's 3D length / 2 pi, so D's lengths are about the
/// surface's): rim edge j becomes the chord corners[j] -> corners[j + 1], clockwise in rim
/// order, each edge's angle mixing its share of the 3D length (0.8) with an equal share (0.2) so
/// that no edge takes half the circle (D stays convex and non-degenerate). Sets fill.corners,
/// boundary_points/boundary_tangents (q + 1 points per edge, linear), origin (the rim's mean
/// point), normal (mean rim normal) and center (0). Returns D's boundary counter-clockwise.
/// \throw ricci::InvalidInputError when the rim has zero length.
[[nodiscard]] std::vector<Eigen::Vector2d> layout_on_circle(
    const std::vector<std::vector<RimSample>>& samples, HoleFill& fill);

/// Rows of a least-squares problem whose unknowns are one scalar per basis function, with three
/// right-hand sides (x, y, z or one used column).
struct System {
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<Eigen::Vector3d> targets;  ///< one column per right-hand side

  [[nodiscard]] int next_row() const { return static_cast<int>(targets.size()); }

  /// The row weight * (D_d f - target); direction nullptr: the value f.
  void add(const std::vector<BasisSample>& basis, const PlanarDmsSpace& space,
           const Eigen::Vector2d* direction, const Eigen::Vector3d& target, double weight);
};

/// Rows whose sum of squares is weight * the thin-plate energy int |H|^2 (thin_plate_rule) over
/// the triangles of the space, leaving out the quadrature points where the partition of unity
/// fails (the grid's outer margin): three rows per point (f_xx, sqrt 2 f_xy, f_yy).
void add_thin_plate_rows(System& system, const PlanarDmsSpace& space, double weight);

/// The Gram matrix R^T R of those rows (R: the rows add_thin_plate_rows adds), function_count()
/// square, both triangles, without forming R: summed point by point into dense blocks of
/// triangle pairs, in parallel. Equal to R^T R up to rounding; entries that are exactly zero
/// are left out. With `plus` (function_count() square, compressed), returns *plus + R^T R,
/// entry for entry as Eigen's sparse sum would give it. With `plain` (by triangle), the
/// triangles flagged nonzero take thin_plate_plain_rule instead (plain_rule_triangles).
[[nodiscard]] Eigen::SparseMatrix<double> thin_plate_normal(
    const PlanarDmsSpace& space, double weight,
    const Eigen::SparseMatrix<double>* plus = nullptr, const std::vector<char>* plain = nullptr);

/// The normal equations of `system`'s rows plus weight * the thin-plate energy
/// (thin_plate_normal; weight 0: none): A^T A + weight T, function_count() square, and A^T b
/// (one column per right-hand side).
struct NormalEquations {
  Eigen::SparseMatrix<double> matrix;
  Eigen::MatrixX3d rhs;
};
/// `plain`: as thin_plate_normal's.
[[nodiscard]] NormalEquations normal_equations(const System& system, const PlanarDmsSpace& space,
                                               double thin_plate,
                                               const std::vector<char>* plain = nullptr);

/// Solves normal * x = rhs (symmetric positive definite, both triangles stored; each column of
/// rhs a right-hand side) by a supernodal Cholesky factorisation (AMD ordering) and one step of
/// iterative refinement.
/// \throw ricci::SolverError ("the normal equations of the <what> are not positive definite")
///        when the factorisation fails, or when the solution is not finite.
[[nodiscard]] Eigen::MatrixXd solve_normal_equations(const Eigen::SparseMatrix<double>& normal,
                                                     const Eigen::MatrixXd& rhs,
                                                     const std::string& what);

/// The control points of the identity map (x, y) -> (x, y) of the space's plane: one row of two
/// coordinates per function; exact, so a patch built on them is affine where they are.
[[nodiscard]] Eigen::MatrixXd identity_control_points(const PlanarDmsSpace& space);

/// Lays D out as the rim developed into the plane: a curve through q + 1 points per rim edge
/// with the 3D distances between consecutive samples, turning between them as the rim turns on
/// the surface (the signed angle between consecutive derivatives about the normal, at the
/// corners too), plus the hole's curvature spread evenly by arc length so that D turns once, the
/// closing gap then removed linearly in arc length. boundary_tangents: dD/dt with |dD/dt| =
/// |dS/dt|. Why: at a corner the patch's Jacobian maps D's two edge directions to the
/// surface's, and a linear map keeping the orientation keeps an angle convex or reflex; along an
/// edge it rotates as the rim's tangent does. A convex D (layout_on_circle) folds the patch at
/// the reflex corners of a scalloped rim.
/// Sets what layout_on_circle sets (center: a point D is star-shaped from, else the mean of
/// D's boundary points). Returns D's boundary counter-clockwise, or an empty vector when it is
/// not simple.
[[nodiscard]] std::vector<Eigen::Vector2d> layout_by_development(
    const std::vector<std::vector<RimSample>>& samples, HoleFill& fill);

/// The parametric G1 patch (parametric_fill.cpp; hole_fill.h says what it solves), refined
/// refinements[j] times at rim vertex j (patch_space).
/// \pre refinements.size() == the rim's edge count.
/// \throw ricci::InvalidInputError when the rim has zero length; ricci::SolverError when the
///        normal equations cannot be factorised.
[[nodiscard]] HoleFill fill_parametric(const Rim& rim,
                                       const std::vector<std::vector<RimSample>>& samples,
                                       const FillOptions& options,
                                       const std::vector<int>& refinements);

}  // namespace spline::fill_detail
