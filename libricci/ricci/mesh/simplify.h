#pragma once
// Reducing a dense scan to a domain mesh of a chosen size with the same topology, and projecting
// points onto a mesh. Bodies use CGAL (in *_cgal.cpp files only).
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct SimplifyOptions {
  /// Number of faces wanted in the result (reached within a few percent).
  int target_faces = 2000;
  /// Isotropic remeshing rounds after the edge collapses, for well-shaped triangles (0 = none).
  int remesh_iterations = 3;
  /// Edge-collapse engine, all Garland-Heckbert plane quadrics with the link condition and no
  /// fold-overs. quadric: the library's own (simplify_quadric.h, cheaper). cgal: CGAL's all the
  /// way. staged: the own collapse down to 4x the target (and at least 16k faces: smaller
  /// inputs are CGAL's all the way), CGAL's for the last collapses, which decide the domain's
  /// shape (docs/design-notes.md, "Simplification").
  enum class Collapse { quadric, staged, cgal };
  Collapse collapse = Collapse::staged;
};

struct SimplifyResult {
  Mesh mesh;
  int faces_before = 0;
  int faces_after = 0;
  double min_angle_deg = 0.0;  ///< Smallest corner angle of the result.
};

/// Garland-Heckbert edge collapses (link condition kept, so the topology cannot change), then
/// isotropic remeshing at the edge length of target_faces equilateral triangles.
/// \pre a closed or open 2-manifold triangle mesh; target_faces >= 4.
/// \throw InvalidInputError for a bad target; TopologyError if the Euler characteristic or
///        boundary count changed (which the link condition should prevent).
[[nodiscard]] SimplifyResult simplify_mesh(const Mesh& dense, const SimplifyOptions& options = {});

/// A point on a mesh: the face, its barycentric coordinates (in the face's halfedge order
/// starting at mesh.halfedge_handle(face)), the 3D point and the distance to the query.
struct SurfacePoint {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// The closest point on `mesh` of every row of `queries` (#Q by 3), by an AABB tree; the queries
/// run on all cores (parallel_for), each into its own slot.
[[nodiscard]] std::vector<SurfacePoint> closest_points(const Mesh& mesh, const Eigen::MatrixX3d& queries);

/// The same for oriented queries (`normals`: a unit normal per query, or a zero row for none):
/// the closest point on a face of `mesh` whose normal makes an angle below 90 degrees with the
/// query's, looked for within `search_radius` of the query, so that a point on one side of a
/// thin part is not placed on the other side; the plain closest point where no face within
/// the radius agrees. \throw InvalidInputError when normals has another number of rows.
[[nodiscard]] std::vector<SurfacePoint> closest_points(const Mesh& mesh,
                                                       const Eigen::MatrixX3d& queries,
                                                       const Eigen::MatrixX3d& normals,
                                                       double search_radius);

}  // namespace ricci
