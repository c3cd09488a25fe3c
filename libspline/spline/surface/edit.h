#pragma once
// Editing a SplineSurface by moving the manifold spline's control points: by index, or a smooth
// displacement of a region around a point in space. Only the spline's control points change;
// the fill patches are left as they are (not refitted), so where a moved function reaches a
// rim the patch no longer meets the surface: the report names those fills.
//
// Support. A function of domain face I (any beta) is non-zero only on the domain faces sharing
// a vertex with I: evaluation on a face g combines the functions of the faces sharing a vertex
// with g and no others (ManifoldSplineSpace::reaching_faces; the knot clouds stay inside their
// vertex stars). So after a move the surface is unchanged, bit for bit, on every face outside
// the union of the moved functions' supports (EditReport::affected_faces).
#include <Eigen/Core>
#include <vector>

#include "spline/surface/spline_surface.h"

namespace spline {

/// The support of the functions of domain face `face`: the domain faces sharing a vertex with
/// it (itself included), ascending.
/// \throw ricci::InvalidInputError when `face` is not a domain face of the spline.
[[nodiscard]] std::vector<int> function_support_faces(const SplineSurface& surface, int face);

/// What an edit moved.
struct EditReport {
  std::vector<int> moved_functions;  ///< global function indices, ascending
  std::vector<double> weights;       ///< by moved function: the fraction of the displacement
  /// Domain faces where the surface may have changed (the union of the moved functions'
  /// supports), ascending; everywhere else it is unchanged bit for bit.
  std::vector<int> affected_faces;
  std::vector<int> touched_fills;      ///< fills with a rim edge on an affected face
  std::vector<int> touched_open_rims;  ///< open rims with an edge on an affected face
  double max_displacement = 0.0;       ///< largest control-point move (length)
};

/// Moves control point functions[i] by displacements[i] (an index may repeat: the moves add).
/// \throw ricci::InvalidInputError on unequal sizes, an index outside [0, function count) or a
///        non-finite displacement (the surface is then unchanged).
[[nodiscard]] EditReport move_control_points(SplineSurface& surface,
                                             const std::vector<int>& functions,
                                             const std::vector<Eigen::Vector3d>& displacements);

struct RegionMoveOptions {
  /// The surface over a face is sampled at the (d + 1)(d + 2) / 2 points with barycentric
  /// coordinates (i, j, k) / d, i + j + k = d (d = this; >= 1).
  int samples_per_edge = 4;
  int threads = 2;  ///< evaluation threads (0: all cores)
};

/// Smooth displacement of the surface around `centre`. For each domain face I, d_I is the
/// distance from `centre` to the surface over the support of I's functions (the samples of its
/// faces that are not skipped_faces, i.e. the spline where it is shown); every function of I
/// moves by w(d_I / radius) * displacement with w(s) = (1 - s^2)^3 for s < 1, else 0: a C^2
/// falloff (w, w' and w'' vanish at s = 1), 1 where the support's surface reaches the centre.
/// Functions whose support's surface stays outside the ball do not move.
/// \throw ricci::InvalidInputError on a radius that is not positive and finite, a non-finite
///        centre or displacement, or samples_per_edge < 1.
[[nodiscard]] EditReport move_region(SplineSurface& surface, const Eigen::Vector3d& centre,
                                     double radius, const Eigen::Vector3d& displacement,
                                     const RegionMoveOptions& options = {});

}  // namespace spline
