#pragma once
// The Loop subdivision limit surface of a triangle control mesh, evaluated through OpenSubdiv
// (feature-adaptive patches: quartic box splines where regular, Gregory triangles at the isolated
// extraordinary vertices). OpenSubdiv stays inside loop_surface.cpp.
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "ricci/mesh/mesh.h"

namespace spline {

/// A point of the limit surface in the parametrisation of one control face: with the face's
/// corners c0, c1, c2 in the order of mesh.fv_range(face), (u, v) are the barycentric weights
/// of c1 and c2 (c0 gets 1 - u - v), i.e. OpenSubdiv's ptex coordinates of a triangle.
struct LoopLocation {
  int face = -1;
  double u = 0.0;
  double v = 0.0;
};

/// Position and first partial derivatives (per unit of u and v) at a LoopLocation.
struct LoopPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();
};

struct LoopSurfaceOptions {
  /// Depth of adaptive refinement around extraordinary vertices; the Gregory end caps sit at this
  /// depth, so dyadic points of level <= isolation_level are exact limit points. 1..10.
  int isolation_level = 3;
};

/// The limit surface of a fixed control-mesh connectivity, as a linear map of the control points.
/// Boundaries are smooth B-spline curves through the boundary (VTX_BOUNDARY_EDGE_ONLY).
class LoopSurface {
 public:
  /// \pre `control` is a triangle 2-manifold (closed or open) with at least 4 vertices.
  /// \throw ricci::InvalidInputError on a non-triangle face, too few vertices or a bad level.
  explicit LoopSurface(const ricci::Mesh& control, const LoopSurfaceOptions& options = {});
  ~LoopSurface();
  LoopSurface(const LoopSurface&) = delete;
  LoopSurface& operator=(const LoopSurface&) = delete;

  [[nodiscard]] int num_control_points() const;
  [[nodiscard]] const ricci::Mesh& control_mesh() const;

  /// #locations by #control matrix whose row i maps control points to the limit position at
  /// locations[i] (OpenSubdiv LimitStencilTableFactoryReal<double>); the least-squares matrix.
  /// \throw ricci::InvalidInputError on a location outside the faces or the unit triangle.
  [[nodiscard]] Eigen::SparseMatrix<double, Eigen::RowMajor> design_matrix(
      const std::vector<LoopLocation>& locations) const;

  /// All patch points (refined vertices of every level, then Gregory local points) for control
  /// points `control` (#control by 3); the input of evaluate().
  [[nodiscard]] Eigen::MatrixX3d patch_points(const Eigen::MatrixX3d& control) const;

  /// Limit position and derivatives at `location` from patch_points().
  /// \throw ricci::InvalidInputError on a location outside the faces.
  [[nodiscard]] LoopPoint evaluate(const Eigen::MatrixX3d& patch_points, const LoopLocation& location) const;

  /// The face across the edge opposite corner k (0..2, fv_range order) of `face`, -1 on a boundary.
  [[nodiscard]] int neighbour(int face, int k) const;
  /// The vertex index of corner k (0..2) of `face`.
  [[nodiscard]] int corner(int face, int k) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace spline
