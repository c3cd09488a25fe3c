#pragma once
// Distortion of a metric against the mesh's own (3D) geometry, computed from edge lengths alone
// (no layout needed): the manifold-splines paper's area distortion, corner-angle ratios, and the
// quasi-conformal distortion of the piecewise-linear map between the two metrics.
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct DistortionOptions {
  /// Faces to leave out (e.g. the cone's one-ring, outside the spline domain); indexed by face
  /// index, empty = use every face.
  std::vector<bool> excluded_faces;
  /// Leave out (and count in DistortionReport::skipped_faces) the faces whose 3D triangle is
  /// degenerate instead of throwing: an intrinsic triangulation's faces span chords of the
  /// surface, three of whose vertices may lie on a line.
  bool skip_degenerate = false;
};

struct DistortionReport {
  /// sum_f (log S_f - log s_f)^2 / |F|, areas normalised to total 1 (paper, section 4, step 1).
  double area_distortion = 0.0;
  /// Corner angle in the metric divided by the 3D corner angle: 5th, 50th, 95th percentiles.
  double angle_ratio_p05 = 1.0, angle_ratio_p50 = 1.0, angle_ratio_p95 = 1.0;
  /// Quasi-conformal distortion sigma_max / sigma_min of the per-face affine map: mean, max.
  double quasi_conformal_mean = 1.0, quasi_conformal_max = 1.0;
  /// Mean weighted by the faces' 3D areas (the convention of Crane's group's tools (BFF, CEPS):
  /// sum_f A_f qc_f / sum_f A_f), where slivers count by their area.
  double quasi_conformal_area_mean = 1.0;
  /// Its median and 95th percentile (the mean is dominated by a few slivers on scanned meshes).
  double quasi_conformal_p50 = 1.0, quasi_conformal_p95 = 1.0;
  int faces = 0;  ///< Faces measured.
  int skipped_faces = 0;  ///< Degenerate faces left out (DistortionOptions::skip_degenerate).
};

/// Compares the metric `lengths` (by edge index, Euclidean background) with the mesh's 3D one.
/// \pre lengths.size() == mesh.n_edges() and every face satisfies the triangle inequality in both.
/// \throw InvalidInputError on size mismatch or a degenerate face (unless skip_degenerate).
[[nodiscard]] DistortionReport measure_distortion(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                                  const DistortionOptions& options = {});

}  // namespace ricci
