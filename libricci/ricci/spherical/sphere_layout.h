#pragma once
// Conformal embedding of a genus-0 closed surface on the unit sphere from its spherical
// uniformization metric (discrete-surface-ricci-flow §V, S2 background): faces are placed one by
// one, each new vertex by a rotation of the known edge's end in the sphere's tangent plane, then
// the embedding is normalised by a Möbius map of the sphere so its vertex centroid is at 0.
#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct SphereLayoutOptions {
  int seed_face = 0;
  /// Move the vertex centroid to the origin by a conformal map of S2 (Möbius normalisation);
  /// the layout stays conformal but no longer isometric to the flow metric.
  bool centre = false;
  int max_centring_iterations = 50;
};

struct SphereLayoutResult {
  Eigen::MatrixX3d positions;  ///< #V by 3 unit vectors.
  double min_orientation = 0.0;  ///< min over faces of det(p_a, p_b, p_c) (> 0: outward).
  int flipped_faces = 0;
  /// max over edges of |d_S(p_i, p_j) - l_ij| / l_ij (only meaningful without centring).
  double max_relative_length_error = 0.0;
  double max_radius_error = 0.0;  ///< max | |p| - 1 |.
  double centroid_norm = 0.0;     ///< |mean of the positions|.
};

/// \pre closed, connected, genus 0; spherical lengths (by edge index) satisfying the spherical
///      triangle inequality (perimeter < 2π) in every face.
/// \throw InvalidInputError on bad lengths or seed; TopologyError for open or unreachable faces.
[[nodiscard]] SphereLayoutResult layout_sphere(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                               const SphereLayoutOptions& options = {});

/// The great-circle distance between unit vectors (atan2 form, accurate at all angles).
[[nodiscard]] double sphere_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace ricci
