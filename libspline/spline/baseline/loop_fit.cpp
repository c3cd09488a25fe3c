#include "spline/baseline/loop_fit.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/SparseCholesky>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/simplify.h"
#include "ricci/metric/subdivide.h"
#include "ricci/util/stopwatch.h"

namespace spline {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// Relative mismatch of the control-point count that triggers a second simplification.
constexpr double kCountTolerance = 0.02;

// Uniform umbrella Laplacian: (L X)_i = X_i - mean of the neighbours of i.
Sparse umbrella_laplacian(const ricci::Mesh& mesh) {
  std::vector<Eigen::Triplet<double>> entries;
  for (auto v : mesh.vertices()) {
    const double valence = static_cast<double>(mesh.valence(v));
    entries.emplace_back(v.idx(), v.idx(), 1.0);
    for (auto w : mesh.vv_range(v)) entries.emplace_back(v.idx(), w.idx(), -1.0 / valence);
  }
  Sparse l(static_cast<Eigen::Index>(mesh.n_vertices()),
           static_cast<Eigen::Index>(mesh.n_vertices()));
  l.setFromTriplets(entries.begin(), entries.end());
  return l;
}

int boundary_edges(const ricci::Mesh& mesh) {
  int count = 0;
  for (auto e : mesh.edges()) count += mesh.is_boundary(e) ? 1 : 0;
  return count;
}

}  // namespace

ricci::Mesh loop_control_mesh(const ricci::Mesh& dense, int control_points, int remesh_iterations) {
  if (control_points < 4) {
    throw ricci::InvalidInputError("loop_control_mesh: control_points is " +
                                   std::to_string(control_points) + ", at least 4 are needed");
  }
  if (dense.n_faces() == 0)
    throw ricci::InvalidInputError("loop_control_mesh: the dense mesh has no faces");
  // F = 2V - 2 chi - B for a triangle mesh; the boundary edge count B scales like sqrt(V).
  const double chi = static_cast<double>(dense.n_vertices()) -
                     static_cast<double>(dense.n_edges()) + static_cast<double>(dense.n_faces());
  const double boundary =
      boundary_edges(dense) * std::sqrt(control_points / static_cast<double>(dense.n_vertices()));
  const int target_faces =
      std::max(4, static_cast<int>(std::lround(2.0 * control_points - 2.0 * chi - boundary)));
  ricci::Mesh source = dense;
  // Simplification only removes vertices: refine first when the scan is coarser than the target.
  while (static_cast<double>(source.n_faces()) < 1.5 * target_faces)
    source = ricci::subdivide_midpoint(source);
  ricci::SimplifyOptions options;
  options.target_faces = target_faces;
  options.remesh_iterations = remesh_iterations;
  ricci::Mesh control = ricci::simplify_mesh(source, options).mesh;
  // Remeshing drifts from the face target (about 10% more vertices on Spot): one corrected rerun,
  // so the control-point count matches the spline it is compared with.
  const double ratio = control_points / static_cast<double>(control.n_vertices());
  if (std::abs(ratio - 1.0) > kCountTolerance) {
    options.target_faces = std::max(4, static_cast<int>(std::lround(target_faces * ratio)));
    while (static_cast<double>(source.n_faces()) < 1.5 * options.target_faces) {
      source = ricci::subdivide_midpoint(source);
    }
    control = ricci::simplify_mesh(source, options).mesh;
  }
  return control;
}

std::vector<LoopLocation> loop_parameters(const LoopSurface& surface,
                                          const Eigen::MatrixX3d& points) {
  const auto closest = ricci::closest_points(surface.control_mesh(), points);
  std::vector<LoopLocation> locations(closest.size());
  for (size_t i = 0; i < closest.size(); ++i) {
    // The closest point is inside its triangle up to rounding: clamp, then renormalise.
    Eigen::Vector3d b = closest[i].barycentric.cwiseMax(0.0);
    b /= b.sum();
    locations[i] = {closest[i].face, b[1], b[2]};
  }
  return locations;
}

LoopSolve fit_loop_control_points(const LoopSurface& surface,
                                  const std::vector<LoopLocation>& locations,
                                  const Eigen::MatrixX3d& points, double smoothness) {
  if (static_cast<Eigen::Index>(locations.size()) != points.rows()) {
    throw ricci::InvalidInputError("fit_loop_control_points: " + std::to_string(locations.size()) +
                                   " locations for " + std::to_string(points.rows()) + " points");
  }
  if (!(smoothness >= 0.0) || !std::isfinite(smoothness)) {
    throw ricci::InvalidInputError("fit_loop_control_points: smoothness must be finite and >= 0");
  }
  const Sparse a = surface.design_matrix(locations);
  Sparse normal = a.transpose() * a;
  LoopSolve result;
  if (smoothness > 0.0) {
    const Sparse l = umbrella_laplacian(surface.control_mesh());
    const Sparse ltl = l.transpose() * l;
    result.smoothness_weight = smoothness * normal.diagonal().sum() / ltl.diagonal().sum();
    normal += result.smoothness_weight * ltl;
  }
  Eigen::SimplicialLDLT<Sparse> solver(normal);
  if (solver.info() != Eigen::Success) {
    throw ricci::SolverError("fit_loop_control_points: the normal matrix (" +
                             std::to_string(normal.rows()) + " control points, " +
                             std::to_string(points.rows()) + " samples) could not be factorised");
  }
  const Eigen::MatrixX3d rhs = a.transpose() * points;
  result.control = solver.solve(rhs);
  // A singular system factorises with a zero pivot and yields Inf/NaN: treat that as a failure.
  if (solver.info() != Eigen::Success || !result.control.allFinite() ||
      (solver.vectorD().array().abs() <= 1e-14 * solver.vectorD().cwiseAbs().maxCoeff()).any()) {
    throw ricci::SolverError(
        "fit_loop_control_points: the normal matrix is singular (" + std::to_string(points.rows()) +
        " samples for " + std::to_string(normal.rows()) + " control points; use smoothness > 0)");
  }
  return result;
}

LoopFitResult fit_loop_surface(const ricci::Mesh& dense, const LoopFitOptions& options) {
  if (dense.n_vertices() == 0 || dense.n_faces() == 0) {
    throw ricci::InvalidInputError("fit_loop_surface: the dense mesh is empty");
  }
  if (options.projection_steps < 0 || options.parameter_corrections < 0) {
    throw ricci::InvalidInputError(
        "fit_loop_surface: projection_steps and parameter_corrections must be >= 0");
  }
  LoopFitResult result;
  ricci::Stopwatch clock;
  result.control = loop_control_mesh(dense, options.control_points, options.remesh_iterations);
  result.seconds_control_mesh = clock.lap();
  LoopSurfaceOptions surface_options;
  surface_options.isolation_level = options.isolation_level;
  const LoopSurface surface(result.control, surface_options);
  result.seconds_surface = clock.lap();

  const Eigen::MatrixX3d points = ricci::vertex_positions(dense);
  auto locations = loop_parameters(surface, points);
  LoopSolve solve;
  LoopProjection projection;
  for (int round = 0; round <= options.parameter_corrections; ++round) {
    if (round > 0) locations = projection.locations;
    solve = fit_loop_control_points(surface, locations, points, options.smoothness);
    result.seconds_solve += clock.lap();
    projection = project_to_loop_surface(surface, solve.control, points, locations,
                                         options.projection_steps);
    result.seconds_projection += clock.lap();
  }
  for (auto v : result.control.vertices())
    result.control.set_point(v, ricci::to_openmesh(solve.control.row(v.idx())));
  result.control_points = surface.num_control_points();
  result.samples = static_cast<int>(points.rows());
  result.bbox_diagonal = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  const double n = static_cast<double>(points.rows());
  result.rms_relative = std::sqrt(projection.distances.squaredNorm() / n) / result.bbox_diagonal;
  result.max_relative = projection.distances.maxCoeff() / result.bbox_diagonal;
  result.parameter_rms_relative =
      std::sqrt(projection.start_distances.squaredNorm() / n) / result.bbox_diagonal;
  result.parameter_max_relative = projection.start_distances.maxCoeff() / result.bbox_diagonal;
  result.smoothness_weight = solve.smoothness_weight;
  result.locations = std::move(projection.locations);
  return result;
}

}  // namespace spline
