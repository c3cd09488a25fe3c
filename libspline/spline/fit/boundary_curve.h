#pragma once
// The boundary curve of an open scan as data of the least-squares fit: the surface's boundary
// (the domain's boundary edges, inside the collar) pulled onto the scan's boundary curve, and
// the scan's boundary vertices parameterised on the domain's boundary. A fit to the scan's points
// alone places the spline's boundary wherever the points around it and the smoothing put it,
// which on small holes and sharp boundary corners is a percent of the diagonal from the scan's.
#include <Eigen/Core>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

struct BoundaryCurveOptions {
  /// Samples per domain boundary edge (its start vertex and equally spaced interior points).
  int samples_per_edge = 4;
  /// Each boundary point enters the fit this many times (its weight against an ordinary point);
  /// 0: no boundary points. Heavier weights follow a scan's jagged boundary into folds.
  int weight = 2;
  /// Where the domain's boundary stays farther than this from the scan's (a fraction of the
  /// scan's bounding-box diagonal; follow_boundary could not move it there), no point is added:
  /// pulled that far across the domain, the spline folds (mech-holes-shark.off).
  double max_gap = 0.005;
  /// Rounds of refits after the fit: each multiplies the weight of the samples the spline still
  /// misses by more than `tolerance` (a fraction of the scan's bounding-box diagonal) by
  /// `reweight_factor`. A smooth boundary the spline rounds off (a polygonal hole's corners) is
  /// pulled in; a jagged scan boundary, which the spline cannot follow without folding, keeps
  /// the light weight where it is met.
  int reweight_rounds = 3;
  double tolerance = 0.004;
  int reweight_factor = 4;
};

struct BoundaryCurvePoints {
  /// Points to add to the fit: samples of the domain's boundary edges (parameters on the edge)
  /// with the nearest point of the scan's boundary curve as target, then the scan's boundary
  /// vertices at their parameters, each repeated `weight` times.
  std::vector<DomainPoint> parameters;
  Eigen::MatrixX3d points;
  int samples = 0;  ///< distinct points (the first `samples` rows; the others repeat them)
  /// The scan's boundary vertices (indices of `dense`) and their parameters: the nearest point of
  /// the domain's boundary edges.
  std::vector<int> scan_vertices;
  std::vector<DomainPoint> scan_vertex_parameters;
};

/// The boundary data of a fit of `dense` over a spline on `domain` (its faces indexed as the
/// space's). The surface's faces are those with surface_faces[f] != 0 (all when empty); its
/// boundary edges are the edges of a surface face whose other side is no surface face or none.
/// Empty when either mesh has no boundary or the weight is 0.
/// \pre domain carries the space's faces; surface_faces is empty or has one flag per face.
/// \throw ricci::InvalidInputError for samples_per_edge < 1, weight < 0 or a size mismatch.
[[nodiscard]] BoundaryCurvePoints boundary_curve_points(const ricci::Mesh& domain,
                                                        const std::vector<char>& surface_faces,
                                                        const ricci::Mesh& dense,
                                                        const BoundaryCurveOptions& options = {});

/// The samples (of `boundary`'s first `samples` rows) where `spline` lies farther than
/// `distance` from the target, repeated `copies` times each, to be added to the fit.
[[nodiscard]] BoundaryCurvePoints missed_boundary_points(const ManifoldSpline& spline,
                                                         const BoundaryCurvePoints& boundary,
                                                         double distance, int copies);

}  // namespace spline
