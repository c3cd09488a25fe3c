#include "spline/fit/fit.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <array>
#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/boundary_follow.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/simplify.h"
#include "ricci/topology/slice.h"
#include "ricci/util/cross2d.h"
#include "ricci/util/stopwatch.h"
#include "spline/basis/multi_index.h"
#include "spline/fit/boundary_curve.h"
#include "spline/fit/correction.h"
#include "spline/fair/constrained_solve.h"
#include "spline/fit/normal_equations.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

double chart_area(const Eigen::Matrix<double, 3, 2>& p) {
  const Eigen::Vector2d e1 = (p.row(1) - p.row(0)).transpose();
  const Eigen::Vector2d e2 = (p.row(2) - p.row(0)).transpose();
  return 0.5 * std::abs(ricci::cross2d(e1, e2));
}

Eigen::Vector3d face_point(const ricci::Mesh& mesh, int face, const Eigen::Vector3d& bary) {
  const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(face));
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    p += bary[k] * ricci::to_eigen(mesh.point(mesh.to_vertex_handle(hs[k])));
  return p;
}

// True when the basis is no partition of unity at the point (a domain point): within the knot
// clouds' reach of the domain's rim, where the functions of the faces beyond it are missing (the
// basis sums to 0.2-0.5 on the rim's edges and vertices). Fitting a point there scales the
// control points by 1 / (that sum): spikes of up to 47% of the diagonal at knight_decimated.off's
// rim vertices (its domain is the input itself), and genus2_hole.off's spline folded up to three
// rings in from its boundary (normal steps of 150 degrees within 1/100 of an edge). The fill
// patches cover that band (FindRimsOptions::grow), so its points are left to them. Only faces
// within one ring of the rim (`rings`: domain_rim_rings) can lack it.
bool lacks_partition_of_unity(const ManifoldSplineSpace& space, const std::vector<int>& rings,
                              const DomainPoint& p) {
  const int ring = rings[static_cast<std::size_t>(space.domain_index(p.face))];
  if (ring < 0 || ring > 1) return false;
  return !is_partition_of_unity(space.evaluate_basis(p, -1, {}, BasisDerivatives::none));
}

// By face: 1 on the surface, 0 on the collar's ghost faces.
std::vector<char> surface_faces(const std::vector<char>& collar_faces) {
  std::vector<char> surface(collar_faces.size());
  for (std::size_t f = 0; f < collar_faces.size(); ++f) surface[f] = collar_faces[f] == 0;
  return surface;
}

bool has_boundary(const ricci::Mesh& mesh) {
  for (auto h : mesh.halfedges()) {
    if (mesh.is_boundary(h)) return true;
  }
  return false;
}

// Faces of the problem's mesh in the collar: a corner that was a collar vertex of the flow's
// input (index >= surface_vertices). Faces of vertices added later (splits: input_vertex -1)
// alone take their edge neighbours' side, ghost if any is.
std::vector<char> collar_faces(const ricci::OneConeProblem& problem, int surface_vertices) {
  const ricci::Mesh& mesh = problem.mesh;
  std::vector<char> ghost(mesh.n_faces(), 0), known(mesh.n_faces(), 0);
  for (auto f : mesh.faces()) {
    for (auto v : mesh.fv_range(f)) {
      const int input = problem.input_vertex[static_cast<std::size_t>(v.idx())];
      if (input < 0) continue;
      known[static_cast<std::size_t>(f.idx())] = 1;
      if (input >= surface_vertices) ghost[static_cast<std::size_t>(f.idx())] = 1;
    }
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (auto f : mesh.faces()) {
      const auto i = static_cast<std::size_t>(f.idx());
      if (known[i]) continue;
      for (auto g : mesh.ff_range(f)) {
        const auto j = static_cast<std::size_t>(g.idx());
        if (!known[j]) continue;
        known[i] = 1;
        ghost[i] = static_cast<char>(ghost[i] | ghost[j]);
        changed = true;
      }
    }
  }
  return ghost;
}

}  // namespace

Eigen::MatrixX3d piecewise_linear_control_points(const ManifoldSplineSpace& space,
                                                 const ricci::Mesh& mesh) {
  const int m = space.functions_per_face();
  const std::vector<Eigen::Vector3i> betas = multi_indices(space.degree());
  Eigen::MatrixX3d points(space.function_count(), 3);
  // By face in parallel (each writes its own rows; the chart spaces are built on first use).
  const std::vector<int>& faces = space.domain_faces();
  parallel_for(faces.size(), 0, [&](std::size_t i) {
    const int face = faces[i];
    const int chart = space.chart_of(face);
    const auto clouds = space.face_clouds(chart, face);
    const Eigen::Matrix<double, 3, 2> corners = space.atlas().face_positions(chart, face);
    for (int b = 0; b < m; ++b) {
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto& x : control_point_arguments(clouds[0], clouds[1], clouds[2], betas[b])) {
        mean += x;
      }
      mean /= static_cast<double>(space.degree());
      // L_I is affine, so its blossom at the arguments is L_I at their mean.
      points.row(space.function_index(face, b)) =
          face_point(mesh, face, barycentric_in(corners, mean)).transpose();
    }
  });
  return points;
}

namespace {

// The smoothing weight of each face (by domain index): FitOptions::smoothing, raised to
// rim_smoothing next to the rim and to sparse_smoothing where fewer points than the face's
// functions reach it.
std::vector<double> smoothing_by_face(const ManifoldSplineSpace& space, const FitOptions& options,
                                      const std::vector<int>& points_by_face) {
  const std::vector<int> rings = domain_rim_rings(space);
  if (!options.face_smoothing.empty() &&
      static_cast<int>(options.face_smoothing.size()) != space.face_count()) {
    throw ricci::InvalidInputError("fit: face_smoothing has " +
                                   std::to_string(options.face_smoothing.size()) +
                                   " entries for " + std::to_string(space.face_count()) + " faces");
  }
  std::vector<double> smoothing(points_by_face.size(), options.smoothing);
  for (std::size_t d = 0; d < smoothing.size(); ++d) {
    if (rings[d] >= 0 && rings[d] < options.rim_rings)
      smoothing[d] = std::max(smoothing[d], options.rim_smoothing);
    if (points_by_face[d] < space.functions_per_face())
      smoothing[d] = std::max(smoothing[d], options.sparse_smoothing);
    if (!options.face_smoothing.empty()) {
      const auto face = static_cast<std::size_t>(space.domain_faces()[d]);
      smoothing[d] = std::max(smoothing[d], options.face_smoothing[face]);
    }
  }
  return smoothing;
}

// Thin-plate weight of each face (by domain index) per unit of quadrature weight: the face's
// smoothing (smoothing_by_face) times the face's chart area, over J_I when isometric (see
// FitOptions).
std::vector<double> thin_plate_weights(const ManifoldSplineSpace& space,
                                       const Eigen::MatrixX3d& initial, const FitOptions& options,
                                       int points, const std::vector<int>& points_by_face) {
  const int faces = space.domain_face_count();
  std::vector<double> area(static_cast<std::size_t>(faces)), edges(area.size());
  std::vector<double> jacobian(area.size(), 1.0);
  for (int d = 0; d < faces; ++d) {
    const int face = space.domain_faces()[d];
    const auto p = space.atlas().face_positions(space.chart_of(face), face);
    area[d] = chart_area(p);
    for (int k = 0; k < 3; ++k) edges[d] += (p.row((k + 1) % 3) - p.row(k)).norm();
    if (!options.isometric_smoothing) continue;
    // The face's own polynomial f^I (from its control points alone): exact for the piecewise-
    // linear initial points, and unaffected by the missing functions next to the hole, where
    // the spline itself is no partition of unity. Gradient from the blossom:
    // P(u, ..., u, u + e) - p(u) = D_e p(u) / n.
    const int n = space.degree();
    const auto clouds = space.face_clouds(space.chart_of(face), face);
    const BivariatePolynomial f = polynomial_from_control_points(
        clouds[0], clouds[1], clouds[2],
        initial.middleRows(static_cast<Eigen::Index>(d) * space.functions_per_face(),
                           space.functions_per_face()));
    const Eigen::Vector2d centre = p.colwise().mean().transpose();
    const double step = std::sqrt(area[d]);
    std::vector<Eigen::Vector2d> args(static_cast<std::size_t>(n), centre);
    const Eigen::VectorXd at = blossom(f, args);
    args.back() = centre + Eigen::Vector2d(step, 0.0);
    const Eigen::Vector3d du = n * (blossom(f, args) - at) / step;
    args.back() = centre + Eigen::Vector2d(0.0, step);
    const Eigen::Vector3d dv = n * (blossom(f, args) - at) / step;
    jacobian[d] = du.cross(dv).norm();
  }
  if (options.isometric_smoothing) {
    // A degenerate initial face (zero or non-finite area ratio) takes the median ratio.
    std::vector<double> valid;
    for (double j : jacobian) {
      if (std::isfinite(j) && j > 0.0) valid.push_back(j);
    }
    double median = 1.0;
    if (!valid.empty()) {
      std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
      median = valid[valid.size() / 2];
    }
    for (double& j : jacobian) {
      if (!(std::isfinite(j) && j > 1e-12 * median)) j = median;
    }
  }
  // A and h of the surface: sum J_I A_I and the chart edges scaled by sqrt(J_I).
  double total_area = 0.0, edge_sum = 0.0;
  for (int d = 0; d < faces; ++d) {
    total_area += jacobian[d] * area[d];
    edge_sum += std::sqrt(jacobian[d]) * edges[d];
  }
  const double h = edge_sum / (3.0 * faces);
  const double scale = points / total_area * std::pow(h, 4);
  const std::vector<double> smoothing = smoothing_by_face(space, options, points_by_face);
  std::vector<double> weights(static_cast<std::size_t>(faces));
  for (int d = 0; d < faces; ++d) weights[d] = smoothing[d] * scale * area[d] / jacobian[d];
  return weights;
}

}  // namespace

namespace {

// The parts of a fit that do not depend on the points' parameters: the thin-plate rows and the
// anchor (as normal equations), and the constraint matrix. Parameter correction refits with new
// parameters many times over the same space, so these are built once.
struct FitSetup {
  detail::NormalEquations regulariser;  // thin-plate + anchor; no data rows
  Eigen::SparseMatrix<double> constraints;
  ReducedConstraints reduced;  // reduce_constraints(constraints), for every solve against them
};

void check_sizes(const ManifoldSplineSpace& space, const std::vector<DomainPoint>& parameters,
                 const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& initial) {
  if (static_cast<Eigen::Index>(parameters.size()) != points.rows() ||
      initial.rows() != space.function_count()) {
    throw ricci::InvalidInputError("fit: " + std::to_string(parameters.size()) + " parameters, " +
                                   std::to_string(points.rows()) + " points, " +
                                   std::to_string(initial.rows()) + " initial control points for " +
                                   std::to_string(space.function_count()) + " functions");
  }
}

bool in_spline_domain(const ManifoldSplineSpace& space, const DomainPoint& p) {
  return p.face >= 0 && p.face < space.face_count() && space.in_domain(p.face);
}

// The number of points in the domain. \throw ricci::InvalidInputError when there is none.
int domain_point_count(const ManifoldSplineSpace& space,
                       const std::vector<DomainPoint>& parameters) {
  const auto count = static_cast<int>(std::count_if(
      parameters.begin(), parameters.end(),
      [&](const DomainPoint& p) { return in_spline_domain(space, p); }));
  if (count == 0) throw ricci::InvalidInputError("fit: no point lies in the spline's domain");
  return count;
}

// Data rows by domain face.
std::vector<detail::FaceRowsSpec> data_rows(const ManifoldSplineSpace& space,
                                            const std::vector<DomainPoint>& parameters) {
  std::vector<detail::FaceRowsSpec> rows(static_cast<std::size_t>(space.domain_face_count()));
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const DomainPoint& p = parameters[k];
    if (!in_spline_domain(space, p)) continue;
    rows[space.domain_index(p.face)].points.push_back(static_cast<int>(k));
  }
  return rows;
}

// The points' count scales the thin-plate and anchor terms (FitOptions: both are relative to
// the number of points) and their spread over the faces sets sparse_smoothing's faces, so the
// setup belongs to one set of parameters (correct_parameters keeps every point in the domain;
// a point moving to a neighbouring face leaves the weights as they were).
FitSetup make_fit_setup(const ManifoldSplineSpace& space, const Eigen::MatrixX3d& initial,
                        const FitOptions& options, const std::vector<DomainPoint>& parameters) {
  const int points = domain_point_count(space, parameters);
  FitSetup setup;
  std::vector<detail::FaceRowsSpec> rows(static_cast<std::size_t>(space.domain_face_count()));
  if (options.smoothing > 0.0) {
    std::vector<int> points_by_face;
    for (const auto& spec : data_rows(space, parameters))
      points_by_face.push_back(static_cast<int>(spec.points.size()));
    const std::vector<double> w =
        thin_plate_weights(space, initial, options, points, points_by_face);
    for (std::size_t d = 0; d < rows.size(); ++d) rows[d].thin_plate_weight = w[d];
  }
  const double anchor = options.anchor * points / space.function_count();
  setup.regulariser = detail::assemble_normal_equations(space, rows, {}, Eigen::MatrixX3d(0, 3),
                                                        anchor, initial,
                                                        std::max(1, options.threads));
  if (options.constraint_r >= 0) {
    FairOptions fair_options;
    fair_options.r = options.constraint_r;
    fair_options.active_faces = options.constraint_faces;
    setup.constraints = fairing_constraints(space, fair_options);
  } else {
    setup.constraints.resize(0, space.function_count());
  }
  setup.reduced = reduce_constraints(setup.constraints);
  return setup;
}

// Checks the sizes and builds the setup for these points (their count scales the regulariser).
FitSetup prepare_fit(const ManifoldSplineSpace& space, const std::vector<DomainPoint>& parameters,
                     const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& initial,
                     const FitOptions& options) {
  check_sizes(space, parameters, points, initial);
  return make_fit_setup(space, initial, options, parameters);
}

// The fit with a prepared setup. `reference`: the multipliers' starting point (feasible ideally:
// the previous round's solution converges in fewer updates). `known`: basis values already
// evaluated at (some of) the parameters, or null. `samples`, when not null, receives the basis
// values and gradients at the parameters (detail::take_data_rows).
FitResult fit_with_setup(const ManifoldSplineSpace& space, const FitSetup& setup,
                         const std::vector<DomainPoint>& parameters,
                         const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& initial,
                         const Eigen::MatrixX3d& reference, const FitOptions& options,
                         const detail::PointBasisValues* known = nullptr,
                         detail::PointBasisValues* samples = nullptr) {
  const ricci::Stopwatch start;
  FitResult result;
  result.points = domain_point_count(space, parameters);
  const std::vector<detail::FaceRowsSpec> rows = data_rows(space, parameters);
  const int threads = std::max(1, options.threads);
  detail::NormalEquations normal = detail::assemble_normal_equations(
      space, rows, parameters, points, 0.0, initial, threads, known, samples != nullptr);
  normal.lower += setup.regulariser.lower;
  normal.rhs += setup.regulariser.rhs;
  result.seconds_assemble = start.seconds();

  const ricci::Stopwatch solve_start;
  ConstrainedSolveOptions solve_options;
  solve_options.penalty = options.constraint_penalty;
  solve_options.max_iterations = options.constraint_iterations;
  Eigen::SparseMatrix<double> identity(normal.lower.rows(), normal.lower.cols());
  identity.setIdentity();
  // Rounding in A^T A can outweigh a tiny anchor where a sliver makes basis Hessians huge: raise
  // the anchor to 1e-12, then 1e-10, of the largest diagonal entry before giving up.
  const double largest = normal.lower.diagonal().maxCoeff();
  for (double relative : {0.0, 1e-12, 1e-10}) {
    if (relative > 0.0) {
      normal.lower += relative * largest * identity;
      normal.rhs += relative * largest * initial;
      result.anchor_raised = true;
    }
    try {
      const ConstrainedSolution solution =
          solve_constrained(normal.lower, normal.rhs, setup.constraints, setup.reduced,
                            reference, solve_options);
      result.control_points = solution.x;
      result.max_constraint_residual = solution.max_residual;
      result.constraint_iterations = solution.iterations;
      result.reduced_unknowns = solution.reduced_unknowns;
      result.constraint_rows = static_cast<int>(setup.constraints.rows());
      break;
    } catch (const ricci::SolverError&) {
      if (relative == 1e-10) {
        throw ricci::SolverError("fit: CHOLMOD could not factor the normal equations (" +
                                 std::to_string(normal.lower.rows()) + " unknowns, r = " +
                                 std::to_string(options.constraint_r) + ")");
      }
    }
  }
  result.seconds_solve = solve_start.seconds();

  const Eigen::MatrixX3d residual =
      detail::residuals_at_parameters(normal, rows, points, result.control_points);
  const Eigen::VectorXd distance = residual.rowwise().norm();
  result.rms_at_parameters = std::sqrt(distance.squaredNorm() / result.points);
  result.max_at_parameters = distance.maxCoeff();
  if (samples) *samples = detail::take_data_rows(normal, rows, parameters);
  return result;
}

}  // namespace

FitResult fit_control_points(const ManifoldSplineSpace& space,
                             const std::vector<DomainPoint>& parameters,
                             const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& initial,
                             const FitOptions& options) {
  const ricci::Stopwatch start;
  const FitSetup setup = prepare_fit(space, parameters, points, initial, options);
  const double setup_seconds = start.seconds();
  FitResult result = fit_with_setup(space, setup, parameters, points, initial, initial, options);
  result.seconds_assemble += setup_seconds;
  return result;
}

FitResult fit_control_points(const ManifoldSplineSpace& space,
                             const std::vector<DomainPoint>& setup_parameters,
                             const std::vector<DomainPoint>& parameters,
                             const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& initial,
                             const FitOptions& options) {
  const ricci::Stopwatch start;
  check_sizes(space, parameters, points, initial);
  const FitSetup setup = make_fit_setup(space, initial, options, setup_parameters);
  const double setup_seconds = start.seconds();
  FitResult result = fit_with_setup(space, setup, parameters, points, initial, initial, options);
  result.seconds_assemble += setup_seconds;
  return result;
}

std::vector<int> domain_rim_rings(const ManifoldSplineSpace& space) {
  std::vector<int> ring(static_cast<std::size_t>(space.domain_face_count()), -1);
  std::vector<int> queue;
  for (int d = 0; d < space.domain_face_count(); ++d) {
    const int face = space.domain_faces()[d];
    for (int k = 0; k < 3; ++k) {
      const int g = space.neighbour(face, k);
      if (g < 0 || !space.in_domain(g)) ring[d] = 0;
    }
    if (ring[d] == 0) queue.push_back(face);
  }
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const int face = queue[i];
    for (int k = 0; k < 3; ++k) {
      const int g = space.neighbour(face, k);
      if (g < 0 || !space.in_domain(g) || ring[space.domain_index(g)] >= 0) continue;
      ring[space.domain_index(g)] = ring[space.domain_index(face)] + 1;
      queue.push_back(g);
    }
  }
  return ring;
}

namespace {

// Radius of the oriented closest-point search, in mean domain edge lengths.
constexpr double kOrientedSearchEdges = 3.0;

// Points of the input surface to fit, each with the input's unit normal there.
struct DataPoints {
  Eigen::MatrixX3d positions, normals;
};

// The input's vertices (first, in index order; area-weighted normals), its face centroids,
// then, while fewer than `wanted`, the interior points of a barycentric grid of level m on
// every face ((m - 1)(m - 2) / 2 of them, the centroid not twice). When the vertices alone
// are at least `enough`, they are all: a dense scan's centroids would triple the points to
// project, fit and correct for no better fit.
DataPoints data_points(const ricci::Mesh& dense, Eigen::Index wanted, Eigen::Index enough) {
  const Eigen::Index nv = static_cast<Eigen::Index>(dense.n_vertices());
  const bool with_faces = nv < enough;
  const Eigen::Index nf = with_faces ? static_cast<Eigen::Index>(dense.n_faces()) : 0;
  const auto per_face = [](int m) {
    return static_cast<Eigen::Index>((m - 1) * (m - 2) / 2 - (m % 3 == 0 ? 1 : 0));
  };
  int level = 3;  // the centroid only
  while (level < 16 && nv + nf + nf * per_face(level) < wanted) ++level;
  std::vector<Eigen::Vector3d> grid;  // barycentric, interior, the centroid left out
  for (int i = 1; i < level; ++i) {
    for (int j = 1; i + j < level; ++j) {
      const int k = level - i - j;
      if (3 * i != level || 3 * j != level) grid.emplace_back(i, j, k);
    }
  }
  const Eigen::Index rows = nv + nf * (1 + static_cast<Eigen::Index>(grid.size()));
  DataPoints data{Eigen::MatrixX3d(rows, 3), Eigen::MatrixX3d::Zero(rows, 3)};
  for (auto v : dense.vertices())
    data.positions.row(v.idx()) = ricci::to_eigen(dense.point(v)).transpose();
  Eigen::Index row = nv + nf;
  for (auto f : dense.faces()) {
    Eigen::Matrix3d corners;
    std::array<int, 3> ids{};
    int c = 0;
    for (auto v : dense.fv_range(f)) {
      ids[static_cast<std::size_t>(c)] = v.idx();
      corners.col(c++) = ricci::to_eigen(dense.point(v));
    }
    const Eigen::Vector3d area_normal =
        (corners.col(1) - corners.col(0)).cross(corners.col(2) - corners.col(0));
    for (int id : ids) data.normals.row(id) += area_normal.transpose();
    if (!with_faces) continue;
    const Eigen::Vector3d n = area_normal.normalized();
    data.positions.row(nv + f.idx()) = corners.rowwise().mean().transpose();
    data.normals.row(nv + f.idx()) = n.transpose();
    for (const Eigen::Vector3d& b : grid) {
      data.positions.row(row) = (corners * b / level).transpose();
      data.normals.row(row++) = n.transpose();
    }
  }
  for (Eigen::Index v = 0; v < nv; ++v) {
    const double length = data.normals.row(v).norm();
    if (length > 0.0) data.normals.row(v) /= length;
  }
  return data;
}

double mean_edge_length(const ricci::Mesh& mesh) {
  double sum = 0.0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return mesh.n_edges() > 0 ? sum / static_cast<double>(mesh.n_edges()) : 0.0;
}

double diagonal_of(const ricci::Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (auto v : mesh.vertices()) {
    lo = lo.cwiseMin(ricci::to_eigen(mesh.point(v)));
    hi = hi.cwiseMax(ricci::to_eigen(mesh.point(v)));
  }
  return mesh.n_vertices() > 0 ? (hi - lo).norm() : 0.0;
}

// The boundary samples the fit misses by more than the tolerance weigh reweight_factor times
// more (appended copies), and the spline is fitted again; up to reweight_rounds times.
void refit_missed_boundary(const ManifoldSplineSpace& space, const FitSetup& setup,
                           const BoundaryCurvePoints& boundary, const ricci::Mesh& dense,
                           const BoundaryCurveOptions& options, const Eigen::MatrixX3d& initial,
                           const FitOptions& fit_options, std::vector<DomainPoint>& parameters,
                           Eigen::MatrixX3d& data, ScanFitResult& result) {
  if (boundary.samples == 0) return;
  const double distance = options.tolerance * diagonal_of(dense);
  int weight = options.weight;
  for (int round = 0; round < options.reweight_rounds; ++round) {
    const BoundaryCurvePoints missed = missed_boundary_points(
        result.spline, boundary, distance, (options.reweight_factor - 1) * weight);
    weight *= options.reweight_factor;
    if (missed.samples == 0) break;
    parameters.insert(parameters.end(), missed.parameters.begin(), missed.parameters.end());
    Eigen::MatrixX3d grown(data.rows() + missed.points.rows(), 3);
    grown << data, missed.points;
    data = std::move(grown);
    result.fit = fit_with_setup(space, setup, parameters, data, initial,
                                result.fit.control_points, fit_options);
    result.spline.control_points = result.fit.control_points;
    ++result.boundary_refits;
  }
}

// ScanFitOptions::free_cone_faces_from_genus: by face of the problem's mesh, 0 for a face with a
// corner within free_cone_rings edges of the cone, 1 elsewhere; empty (every face constrained)
// below that genus or without a single cone.
std::vector<char> free_cone_faces(const ricci::OneConeProblem& problem,
                                  const ScanFitOptions& options) {
  if (problem.cone < 0 || options.free_cone_faces_from_genus <= 0 ||
      problem.genus < options.free_cone_faces_from_genus)
    return {};
  const ricci::Mesh& mesh = problem.mesh;
  std::vector<int> ring(mesh.n_vertices(), -1);
  std::vector<int> queue{problem.cone};
  ring[static_cast<std::size_t>(problem.cone)] = 0;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int v = queue[q];
    if (ring[static_cast<std::size_t>(v)] >= options.free_cone_rings) continue;
    for (auto w : mesh.vv_range(mesh.vertex_handle(v))) {
      if (ring[static_cast<std::size_t>(w.idx())] >= 0) continue;
      ring[static_cast<std::size_t>(w.idx())] = ring[static_cast<std::size_t>(v)] + 1;
      queue.push_back(w.idx());
    }
  }
  std::vector<char> constrained(mesh.n_faces(), 1);
  for (auto f : mesh.faces())
    for (auto v : mesh.fv_range(f))
      if (ring[static_cast<std::size_t>(v.idx())] >= 0) constrained[f.idx()] = 0;
  return constrained;
}

// A closed genus-0 domain with the automatic singularity: its puncture is chosen here
// (ScanFitOptions::puncture), not by the atlas.
bool takes_puncture_choice(const ricci::Mesh& domain, const ScanFitOptions& options) {
  if (options.atlas.singular_vertex >= 0 || !(options.puncture.distortion_tolerance > 0.0))
    return false;
  const ricci::SurfaceTopology topology = ricci::surface_topology(domain);
  return topology.boundary_loops == 0 && topology.genus == 0;
}

// The choice's work in the atlas' figures, as if the atlas had made it.
void record_choice(const ricci::SingularityChoice& choice, ricci::OneConeAtlasResult& atlas) {
  atlas.flows_for_choice = choice.flows_run;
  atlas.solves_for_choice = choice.linear_solves;
  atlas.linear_work.choice = choice.linear_work;
  atlas.timings.choice = choice.seconds;
  atlas.timings.total += choice.seconds;
}

}  // namespace

ScanFitResult fit_scan(const ricci::Mesh& dense, const ScanFitOptions& options) {
  const ricci::Stopwatch total_start;
  const auto stage = [&](const char* name) {
    if (options.progress) options.progress(name);
    return ricci::Stopwatch();
  };
  ScanFitResult result;
  auto t = stage("simplify");
  ricci::SimplifyOptions simplify;
  simplify.target_faces = options.domain_faces;
  const bool simplified =
      !options.domain &&
      (options.remesh_coarse_inputs || static_cast<int>(dense.n_faces()) > options.domain_faces);
  ricci::Mesh domain = options.domain ? *options.domain
                       : simplified   ? ricci::simplify_mesh(dense, simplify).mesh
                                      : dense;
  if (simplified && options.boundary_follow.max_rounds > 0) {
    result.boundary_follow = ricci::follow_boundary(domain, dense, options.boundary_follow);
  }
  result.domain = domain;
  result.timings.simplify = t.seconds();

  t = stage("atlas");
  // The collar's outer boundary takes the boundary's geodesic curvature; where the flow cannot
  // reach that target on the collared mesh (eight_hole.off: genus 2, one small hole), the
  // surface is fitted without it.
  // With tracked_parameters the data points are placed through the intrinsic flow's flips
  // (parameters, below).
  ricci::OneConeAtlasOptions atlas_options = options.atlas;
  atlas_options.keep_flip_record = atlas_options.keep_flip_record || options.tracked_parameters;
  bool collared = false;
  if (options.collar.rings > 0 && has_boundary(domain)) {
    const ricci::CollarResult collar = ricci::add_boundary_collar(domain, options.collar);
    try {
      result.atlas = ricci::build_one_cone_atlas(collar.mesh, atlas_options);
      result.collar_faces = collar_faces(result.atlas.problem, collar.original_vertices);
      collared = true;
    } catch (const ricci::Error& e) {
      result.collar_refused = e.what();
    }
  }
  if (!collared) {
    ricci::OneConeAtlasOptions atlas = atlas_options;
    if (takes_puncture_choice(domain, options)) {
      result.puncture = choose_puncture(domain, ricci::singularity_options(domain, atlas),
                                        options.puncture);
      atlas.singular_vertex = result.puncture.vertex;
    }
    result.atlas = ricci::build_one_cone_atlas(domain, atlas);
    if (result.puncture.vertex >= 0) record_choice(result.puncture.choice, result.atlas);
  }
  result.timings.atlas = t.seconds();

  t = stage("space");
  const ricci::Mesh& mesh = result.atlas.problem.mesh;
  ManifoldSplineOptions space_options;
  space_options.degree = options.degree;
  space_options.knots = options.knots;
  auto space = std::make_shared<ManifoldSplineSpace>(mesh, result.atlas.atlas, space_options);
  const Eigen::MatrixX3d initial = piecewise_linear_control_points(*space, mesh);
  result.timings.space = t.seconds();

  t = stage("parameters");
  // Data: the scan's vertices and face centroids (points of the input surface), by closest point;
  // points over a hole or the rim's band (the closest point in a rim face, on the rim, where the
  // basis is no partition of unity: a punctured sphere's removed star lands there, and fitted
  // it dragged the rim, bunny: rim faces' RMS 4%) are left to the fill patches.
  const Eigen::Index nv = static_cast<Eigen::Index>(dense.n_vertices());
  const auto per_control_point = [&](double ratio) {
    return static_cast<Eigen::Index>(ratio * static_cast<double>(space->function_count()));
  };
  const DataPoints points =
      data_points(dense, per_control_point(options.data_points_per_control_point),
                  per_control_point(options.vertices_only_per_control_point));
  // Oriented: a point on one side of a thin part is placed on that side of the domain. On the
  // intrinsic route the atlas' faces are chords of the surface (anchor.off: up to 5.7% of the
  // diagonal off it); with tracked_parameters the points are placed on the faces the flow
  // started from and carried through its flips.
  const ricci::Mesh& placement =
      options.tracked_parameters ? ricci::placement_mesh(result.atlas) : mesh;
  std::vector<ricci::SurfacePoint> closest =
      options.oriented_parameters
          ? ricci::closest_points(placement, points.positions, points.normals,
                                  kOrientedSearchEdges * mean_edge_length(placement))
          : ricci::closest_points(placement, points.positions);
  if (options.tracked_parameters)
    closest = ricci::place_on_problem_mesh(result.atlas, std::move(closest));
  std::vector<DomainPoint> parameters(closest.size());
  const std::vector<int> rings = domain_rim_rings(*space);
  for (std::size_t k = 0; k < closest.size(); ++k) {
    const DomainPoint p{closest[k].face, closest[k].barycentric};
    const bool covered = space->in_domain(p.face) && !lacks_partition_of_unity(*space, rings, p);
    parameters[k] = covered ? p : DomainPoint{-1, Eigen::Vector3d::Zero()};
    if (!covered) ++result.uncovered_points;
  }
  // With a collar, the surface's boundary (the collar's inner edges) is fitted to the scan's
  // boundary curve, and the scan's boundary vertices keep their parameters on it.
  const BoundaryCurvePoints boundary =
      collared ? boundary_curve_points(mesh, surface_faces(result.collar_faces), dense,
                                       options.boundary_curve)
               : BoundaryCurvePoints{};
  const auto scan_points = static_cast<Eigen::Index>(parameters.size());
  result.scan_data_points = static_cast<int>(scan_points);
  const auto pin_boundary = [&](std::vector<DomainPoint>& p) {
    for (std::size_t i = 0; i < boundary.scan_vertices.size(); ++i)
      p[static_cast<std::size_t>(boundary.scan_vertices[i])] = boundary.scan_vertex_parameters[i];
    std::copy(boundary.parameters.begin(), boundary.parameters.end(), p.begin() + scan_points);
  };
  parameters.resize(parameters.size() + boundary.parameters.size());
  pin_boundary(parameters);
  Eigen::MatrixX3d data(scan_points + boundary.points.rows(), 3);
  data << points.positions, boundary.points;
  result.vertex_parameters.assign(parameters.begin(), parameters.begin() + nv);
  result.timings.parameters = t.seconds();

  t = stage("fit");
  FitOptions fit_options = options.fit;
  fit_options.constraint_faces = free_cone_faces(result.atlas.problem, options);
  result.unconstrained_faces = static_cast<int>(
      std::count(fit_options.constraint_faces.begin(), fit_options.constraint_faces.end(), 0));
  if (options.constrained_fit && options.fair_r >= 0) fit_options.constraint_r = options.fair_r;
  // Correction keeps every point in the domain (correct_parameters), so one setup serves all.
  const FitSetup setup = prepare_fit(*space, parameters, data, initial, fit_options);
  result.setup_parameters = parameters;
  result.pinned_scan_vertices = boundary.scan_vertices;
  // The fit keeps its basis samples (with gradients) for the first correction's projections.
  detail::PointBasisValues start_samples;
  result.fit =
      fit_with_setup(*space, setup, parameters, data, initial, initial, fit_options, nullptr,
                     options.parameter_corrections > 0 ? &start_samples : nullptr);
  result.timings.fit = t.seconds();

  result.spline.space = space;
  result.spline.control_points = result.fit.control_points;
  if (options.parameter_corrections > 0) t = stage("correction");
  for (int round = 0; round < options.parameter_corrections; ++round) {
    // The projections end with the basis values at the new parameters: the refit takes them
    // (a pinned boundary parameter differs from the kept one and is evaluated again).
    detail::PointBasisValues known;
    parameters = detail::correct_parameters_keeping(result.spline, parameters, data,
                                                    options.correction_iterations,
                                                    fit_options.threads, &start_samples, &known)
                     .parameters;
    start_samples = std::move(known);  // values only: a further round evaluates its starts
    pin_boundary(parameters);
    result.fit = fit_with_setup(*space, setup, parameters, data, initial,
                                result.fit.control_points, fit_options, &start_samples);
    result.spline.control_points = result.fit.control_points;
    ++result.corrections;
  }
  if (options.parameter_corrections > 0) {
    result.vertex_parameters.assign(parameters.begin(), parameters.begin() + nv);
    result.timings.correction = t.seconds();
  }
  refit_missed_boundary(*space, setup, boundary, dense, options.boundary_curve, initial,
                        fit_options, parameters, data, result);
  if (fit_options.constraint_r >= 0 && fit_options.constraint_r == options.fair_r) {
    // Fitted inside the constraint set: eq. 14's projection would return the same points.
    result.fairing.control_points = result.fit.control_points;
    result.fairing.constraints = result.fit.constraint_rows;
    result.fairing.max_constraint_residual = result.fit.max_constraint_residual;
  } else if (options.fair_r >= 0) {
    t = stage("fair");
    FairOptions fair_options = options.fair;
    fair_options.r = options.fair_r;
    result.fairing = fair(*space, result.fit.control_points, fair_options);
    result.spline.control_points = result.fairing.control_points;
    result.timings.fair = t.seconds();
  }
  result.data_points = std::move(data);
  result.data_parameters = std::move(parameters);
  result.fit_options = std::move(fit_options);
  result.timings.total = total_start.seconds();
  return result;
}

}  // namespace spline
