#pragma once
// The spline's domain mesh with a density that follows what the spline must resolve: a uniform
// simplification of the scan, then red-green 1-to-4 splits where the scan departs most from the
// domain (detail within a face; or, optionally, where the surface turns sharply across a domain
// edge) or a part is thin for the local edge length (thin rims, legs, ears, handles), new
// vertices placed on the scan, a tangential relaxation, the total aimed at a face count.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace spline {

/// Where split_domain_faces puts its new interior vertices.
enum class SplitPlacement {
  /// Each on the closest point of the scan on a face facing the same way (within two edge
  /// lengths).
  closest_point,
  /// The same, then for each flagged face the vertex among its corners and new midpoints
  /// nearest to the foot of its farthest scan vertex (of the scan vertices whose closest
  /// domain face it is) goes onto that scan vertex, unless that turns a face by 90 degrees or
  /// more from the scan's normal: the domain reaches tips and soles a coarse base cut across,
  /// which a closest point within two edge lengths does not (adaptive_domain's relaxation
  /// keeps these vertices).
  farthest_point,
};

struct AdaptiveDomainOptions {
  /// The total is aimed at the face count of the uniform domain (ricci::simplify_mesh) of this
  /// target, which the remeshing overshoots on thin parts (reached within ~10%).
  int target_faces = 2000;
  /// Share of target_faces given to the uniform base mesh; the rest goes to the splits.
  double base_share = 0.6;
  /// With split_by normal_turn: a face is split where its normal and a neighbour's differ by
  /// more than this (degrees).
  double max_turn_deg = 20.0;
  /// ... or where the part is thinner (ricci::face_thickness) than this many of the face's
  /// mean edge lengths.
  double min_thickness_edges = 3.0;
  int max_levels = 2;  ///< Split rounds (each may split a face created by the one before).
  /// What marks a face for splitting (besides thickness). normal_turn: a turn over
  /// max_turn_deg to a neighbour. deviation: the scan departs from the face more than from the
  /// mean face (squared distances of the scan's vertices to their closest domain face, summed
  /// by face): detail smaller than a face is seen, but so is every smooth bend. quadric_residual:
  /// the same sum of what a quadric height field over the face's neighbourhood misses of the
  /// scan (the bend a cubic spline follows anyway is not counted).
  enum class SplitBy { normal_turn, deviation, quadric_residual };
  SplitBy split_by = SplitBy::deviation;
  /// Tangential relaxation rounds after the splits: each interior vertex half-way to its
  /// neighbours' mean in its tangent plane, then onto the scan (evens out the red-green
  /// closures' obtuse halves and the 4:1 size steps).
  int relax_iterations = 2;
  /// Where the splits put their new vertices (split_domain_faces).
  SplitPlacement placement = SplitPlacement::farthest_point;
};

struct AdaptiveDomain {
  ricci::Mesh mesh;
  int base_faces = 0;            ///< Faces of the uniform base mesh the splits started from.
  std::vector<int> split_faces;  ///< Faces flagged for splitting, by level.
};

/// The adaptive domain of `dense`: ricci::simplify_mesh to base_share * target_faces faces,
/// then up to max_levels rounds splitting the faces whose sizing score (the scan's deviation
/// or normal turn, min_thickness_edges * edge length over thickness) exceeds 1, highest first,
/// while the total stays below the uniform domain's; when few faces need splitting the base is
/// rebuilt larger once, so the total comes near it; then relax_iterations relaxation rounds.
/// Same topology as `dense`.
/// \pre `dense` a closed or open 2-manifold triangle mesh.
/// \throw ricci::InvalidInputError for target_faces < 4, base_share outside (0, 1],
///        max_turn_deg <= 0, min_thickness_edges < 0, max_levels < 0 or relax_iterations < 0;
///        as ricci::simplify_mesh.
[[nodiscard]] AdaptiveDomain adaptive_domain(const ricci::Mesh& dense,
                                             const AdaptiveDomainOptions& options = {});

/// `domain` with the faces flagged in `refine` (by face index) split 1-to-4 and their
/// neighbours closed red-green (ricci::subdivide_midpoint_locally); the new interior vertices
/// are moved onto `dense` as `placement` says, so the finer domain follows the scan. Boundary
/// midpoints stay on their edges. A move that turns a face over (or flattens it) is undone.
/// \throw ricci::InvalidInputError if `refine` has the wrong size.
[[nodiscard]] ricci::Mesh split_domain_faces(
    const ricci::Mesh& domain, const ricci::Mesh& dense, const std::vector<char>& refine,
    SplitPlacement placement = SplitPlacement::closest_point);

}  // namespace spline
