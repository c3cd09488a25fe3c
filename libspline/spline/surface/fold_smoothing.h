#pragma once
// The smoothing floor of fit_surface's fold rounds: raised fairing on the domain faces around
// the folds, tapered to nothing over a few rings so the fairing has no step at its border.
#include <Eigen/Core>
#include <vector>

#include "ricci/mesh/mesh.h"

namespace spline {

struct FoldSmoothingOptions {
  /// The floor (FitOptions::smoothing's unit, dimensionless) on the flagged faces and on those
  /// within `rings` rings of edge neighbours of them.
  double level = 1e-2;
  int rings = 2;
  /// Beyond `rings` the floor falls by this factor per ring, in (0, 1], over `taper_rings`
  /// rings, then is 0; 0 rings: a step from `level` to the fit's own smoothing at the border
  /// of the raised faces. The step can fold the surface at that border (a jagged scan), the
  /// taper raises the RMS sooner; fit_surface tries both.
  double taper = 1.0 / 3.0;
  int taper_rings = 0;
};

/// Rings of edge neighbours between each face of `domain` and the faces flagged in `faces`
/// (by face index; 0 on a flagged face), counted up to `max_rings`; -1 beyond.
/// \throw ricci::InvalidInputError when faces.size() is not domain.n_faces() or max_rings < 0.
[[nodiscard]] std::vector<int> rings_from_faces(const ricci::Mesh& domain,
                                                const std::vector<char>& faces, int max_rings);

/// The smoothing floor by face of `domain` around the faces flagged in `folded`:
/// level * taper^max(0, ring - rings) within rings + taper_rings rings of a flagged face, 0
/// beyond (ring as rings_from_faces counts it).
/// \throw ricci::InvalidInputError when folded.size() is not domain.n_faces(), level <= 0,
/// taper outside (0, 1] or a ring count is negative.
[[nodiscard]] std::vector<double> fold_smoothing_floor(const ricci::Mesh& domain,
                                                       const std::vector<char>& folded,
                                                       const FoldSmoothingOptions& options = {});

/// Midpoints of the edges of `mesh` where it folds itself: the normals of the edge's two
/// triangles differ by more than 90 degrees (dihedral_angles, tessellate/dihedral.h, so a scan
/// and the surface fitted to it are judged alike). A jagged scan folds at such edges, and a
/// spline that follows it folds there too.
[[nodiscard]] std::vector<Eigen::Vector3d> mesh_fold_points(const ricci::Mesh& mesh);

/// Whether every point of `points` lies within `radius` of a point of `near` (true when
/// `points` is empty).
[[nodiscard]] bool all_within(const std::vector<Eigen::Vector3d>& points,
                              const std::vector<Eigen::Vector3d>& near, double radius);

}  // namespace spline
