#pragma once
// The spline's exact polynomial pieces as triangular Bezier patches.
//
// Over a domain face the DMS spline is NOT one polynomial. Each basis function N_{J,beta} is a
// simplex spline of the n + 3 knots V_beta^J, a polynomial of degree n on each region that the
// segments between two of those knots cut out, and those segments cross the face: segments
// between the clouds of two corners run along the edges within a cloud radius of them
// (t_{i,0} t_{j,0} is the edge itself), and segments within a cloud, or along the neighbouring
// faces' edges, cross the corners' neighbourhoods. Only the face's core, farther than the cloud
// radius from its edges, is one polynomial. (The paper's "piecewise polynomial" is this.)
//
// So each face is split into polynomial cells: starting from the face, every convex cell that a
// knot segment of a function reaching the face crosses is cut along that segment's line. The
// result is convex cells on each of which the spline is one polynomial (a refinement of the
// segments' arrangement), each fanned into triangles: one Bezier patch per triangle. A patch's
// control points are the blossom values P(c_0^b0, c_1^b1, c_2^b2) of the piece at its triangle's
// corners c_k (b in multi_indices(n) order). The piece P is taken exactly from the spline at its
// cell's centre: its partial derivatives of every order up to n, from the simplex splines'
// directional derivatives along n + 1 directions (a Taylor expansion, no fitting).
//
// Precision: the patches reproduce the spline to rounding (tested: 1e-12 of the bounding-box
// diagonal at random points of every face). Next to knot segments cells can be very thin (1e-5
// of an edge); a Bezier patch over such a sliver carries its control points' rounding into its
// k-th derivative across the sliver amplified by about (length / width)^k.
//
// Frames: a patch's corners are given in barycentric coordinates of its domain face (corner
// order of manifold_space.h), so the export does not depend on a chart: patch point lambda (its
// own barycentric coordinates) is the face point corners * lambda.
//
// Left out: faces outside the spline's domain or skipped (SplineSurface::skipped_faces) and the
// fill patches (planar DMS splines over a curved domain D, cut the same way by their knot
// segments and by D's boundary curve: not exported).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "spline/surface/spline_surface.h"

namespace spline {

struct BezierOptions {
  int threads = 0;  ///< 0 = hardware concurrency
};

/// One polynomial piece of the spline over a triangle inside a domain face.
struct BezierPatch {
  int face = -1;
  std::array<int, 3> vertices{-1, -1, -1};  ///< domain vertices of the face's corners
  /// Columns: the patch triangle's corners in the face's barycentric coordinates.
  Eigen::Matrix3d corners = Eigen::Matrix3d::Identity();
  Eigen::MatrixX3d control_points;  ///< (n + 1)(n + 2) / 2 rows, multi_indices(n) order
};

struct BezierExport {
  int degree = 0;
  std::vector<BezierPatch> patches;  ///< by face ascending; a face's patches cover it
  int faces = 0;                     ///< domain faces exported
  int knot_segments = 0;             ///< knot segments cutting the exported faces (with repeats)
};

/// The Bezier patches of every tessellated domain face (see the header comment).
/// \throw as ManifoldSplineSpace::evaluate_basis.
[[nodiscard]] BezierExport bezier_patches(const SplineSurface& surface,
                                          const BezierOptions& options = {});

/// Triangles (columns: corners in `face`'s barycentric coordinates) covering the face, on each of
/// which the spline is one polynomial.
/// \throw ricci::InvalidInputError for a face outside the spline's domain.
[[nodiscard]] std::vector<Eigen::Matrix3d> polynomial_cells(const ManifoldSplineSpace& space,
                                                            int face);

/// The blossom of a degree-n Bezier triangle at n arguments given in its barycentric
/// coordinates (points: sum 1; directions: sum 0).
/// \throw ricci::InvalidInputError on a control-point count other than (n + 1)(n + 2) / 2 or an
///        argument count other than n.
[[nodiscard]] Eigen::Vector3d bezier_blossom(const Eigen::MatrixX3d& control_points, int degree,
                                             const std::vector<Eigen::Vector3d>& arguments);

/// The patch at barycentric point lambda (de Casteljau).
[[nodiscard]] Eigen::Vector3d evaluate_bezier(const Eigen::MatrixX3d& control_points, int degree,
                                              const Eigen::Vector3d& lambda);

/// k-th directional derivative (k <= n) at lambda along a barycentric direction (sum 0):
/// n! / (n - k)! times the blossom at (lambda^(n - k), direction^k).
[[nodiscard]] Eigen::Vector3d bezier_derivative(const Eigen::MatrixX3d& control_points,
                                                int degree, const Eigen::Vector3d& lambda,
                                                const Eigen::Vector3d& direction, int order);

}  // namespace spline
