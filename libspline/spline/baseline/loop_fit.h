#pragma once
// Baseline for the spline benchmark (issue 5): a Loop subdivision surface fitted by least squares
// to the vertices of a dense mesh, with a control mesh of a chosen number of vertices.
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"
#include "spline/baseline/loop_surface.h"

namespace spline {

struct LoopFitOptions {
  /// Number of control vertices wanted; the simplified control mesh reaches it within a few
  /// percent (LoopFitResult::control_points has the exact count). >= 4.
  int control_points = 2000;
  /// Relative weight lambda of the umbrella-Laplacian term |L X|^2 on the control points; the
  /// weight used is lambda * trace(A^T A) / trace(L^T L), so it does not depend on the scale or
  /// on the number of samples. 0 = plain least squares.
  double smoothness = 1e-3;
  /// Adaptive refinement depth of the OpenSubdiv patches (see LoopSurfaceOptions).
  int isolation_level = 3;
  /// Gauss-Newton closest-point steps per vertex when measuring the error (0 = distance to the
  /// point at the vertex's fit parameter only).
  int projection_steps = 8;
  /// Parameter corrections: after a fit, each vertex's parameter moves to its closest point on
  /// the fitted surface and the control points are fitted again (0 = parameters stay the closest
  /// points on the control mesh).
  int parameter_corrections = 2;
  /// Isotropic remeshing rounds of the control mesh after simplification.
  int remesh_iterations = 3;
};

struct LoopFitResult {
  ricci::Mesh control;  ///< The control mesh; its positions are the fitted control points.
  int control_points = 0;
  int samples = 0;               ///< Dense vertices fitted (every vertex, unweighted).
  double bbox_diagonal = 0.0;    ///< Of the dense mesh; the unit of the relative errors.
  double rms_relative = 0.0;     ///< RMS over dense vertices of the distance to the limit surface.
  double max_relative = 0.0;     ///< Largest such distance.
  double parameter_rms_relative = 0.0;  ///< The same at the last fit's parameters, before projection.
  double parameter_max_relative = 0.0;
  double smoothness_weight = 0.0;       ///< Absolute weight of |L X|^2 that was used.
  std::vector<LoopLocation> locations;  ///< Closest limit-surface location of each dense vertex.
  /// Wall-clock seconds of the stages: control mesh (simplification), OpenSubdiv set-up
  /// (refinement, patches, stencils), least-squares solves, closest-point projections.
  double seconds_control_mesh = 0.0, seconds_surface = 0.0, seconds_solve = 0.0, seconds_projection = 0.0;
};

/// Simplifies (or, when it has too few faces, first midpoint-subdivides) `dense` to a mesh of
/// about `control_points` vertices with the same genus and boundaries, fits the Loop limit
/// surface of that connectivity to the dense vertices (parameters from closest points on the
/// control mesh, then corrected by projection), and measures the distance of every dense vertex to the fitted surface.
/// \throw ricci::InvalidInputError on an empty mesh, control_points < 4 or bad options;
///        ricci::SolverError if the normal equations cannot be factorised or give NaN.
[[nodiscard]] LoopFitResult fit_loop_surface(const ricci::Mesh& dense, const LoopFitOptions& options = {});

/// Step 1: the control connectivity with about `control_points` vertices (positions on `dense`).
[[nodiscard]] ricci::Mesh loop_control_mesh(const ricci::Mesh& dense, int control_points, int remesh_iterations = 3);

/// Step 2: the location of each row of `points` (#P by 3): the closest point on the control mesh
/// mapped to the face's (u, v).
[[nodiscard]] std::vector<LoopLocation> loop_parameters(const LoopSurface& surface, const Eigen::MatrixX3d& points);

/// Step 3: control points X minimising |A X - points|^2 + w |L X|^2, A = surface.design_matrix,
/// L the umbrella Laplacian of the control mesh, w = smoothness * trace(A^T A) / trace(L^T L).
/// \throw ricci::InvalidInputError on mismatched sizes; ricci::SolverError when the normal
///        matrix is singular (too few samples with smoothness 0) or the solution is not finite.
struct LoopSolve {
  Eigen::MatrixX3d control;
  double smoothness_weight = 0.0;
};
[[nodiscard]] LoopSolve fit_loop_control_points(const LoopSurface& surface, const std::vector<LoopLocation>& locations,
                                                const Eigen::MatrixX3d& points, double smoothness);

/// Step 4: from each start location, Gauss-Newton steps towards the closest point of the limit
/// surface of `control` to the matching row of `points`, crossing into neighbouring faces; a
/// step is kept only if it brings the surface closer, so distances never exceed the start's.
struct LoopProjection {
  std::vector<LoopLocation> locations;
  Eigen::VectorXd distances;        ///< After the steps.
  Eigen::VectorXd start_distances;  ///< At the start locations.
};
[[nodiscard]] LoopProjection project_to_loop_surface(const LoopSurface& surface, const Eigen::MatrixX3d& control,
                                                     const Eigen::MatrixX3d& points,
                                                     const std::vector<LoopLocation>& start, int steps);

}  // namespace spline
