#include "spline/fit/fit.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <chrono>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/simplify.h"
#include "ricci/topology/slice.h"
#include "spline/basis/multi_index.h"

namespace spline {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Dunavant's 6-point rule, exact for degree 4 (the thin-plate integrand of a cubic piece has
// degree 2, of a quintic 6): barycentric points and weights summing to one.
struct QuadraturePoint {
  Eigen::Vector3d bary;
  double weight;
};
std::vector<QuadraturePoint> quadrature_rule() {
  const double a = 0.445948490915965, wa = 0.223381589678011;
  const double b = 0.091576213509771, wb = 0.109951743655322;
  return {{{a, a, 1 - 2 * a}, wa}, {{a, 1 - 2 * a, a}, wa}, {{1 - 2 * a, a, a}, wa},
          {{b, b, 1 - 2 * b}, wb}, {{b, 1 - 2 * b, b}, wb}, {{1 - 2 * b, b, b}, wb}};
}

double chart_area(const Eigen::Matrix<double, 3, 2>& p) {
  const Eigen::Vector2d e1 = (p.row(1) - p.row(0)).transpose();
  const Eigen::Vector2d e2 = (p.row(2) - p.row(0)).transpose();
  return 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
}

Eigen::Vector3d face_point(const ricci::Mesh& mesh, int face, const Eigen::Vector3d& bary) {
  const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(face));
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    p += bary[k] * ricci::to_eigen(mesh.point(mesh.to_vertex_handle(hs[k])));
  return p;
}

// Barycentric coordinates of u in the chart triangle p.
Eigen::Vector3d barycentric_in(const Eigen::Matrix<double, 3, 2>& p, const Eigen::Vector2d& u) {
  Eigen::Matrix2d m;
  m.col(0) = (p.row(1) - p.row(0)).transpose();
  m.col(1) = (p.row(2) - p.row(0)).transpose();
  const Eigen::Vector2d l = m.partialPivLu().solve(u - p.row(0).transpose());
  return {1.0 - l.x() - l.y(), l.x(), l.y()};
}

}  // namespace

Eigen::MatrixX3d piecewise_linear_control_points(const ManifoldSplineSpace& space,
                                                 const ricci::Mesh& mesh) {
  const int m = space.functions_per_face();
  const std::vector<Eigen::Vector3i> betas = multi_indices(space.degree());
  Eigen::MatrixX3d points(space.function_count(), 3);
  for (int face : space.domain_faces()) {
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
  }
  return points;
}

FitResult fit_control_points(const ManifoldSplineSpace& space,
                             const std::vector<DomainPoint>& parameters,
                             const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& initial,
                             const FitOptions& options) {
  if (static_cast<Eigen::Index>(parameters.size()) != points.rows() ||
      initial.rows() != space.function_count()) {
    throw ricci::InvalidInputError("fit: " + std::to_string(parameters.size()) + " parameters, " +
                                   std::to_string(points.rows()) + " points, " +
                                   std::to_string(initial.rows()) + " initial control points for " +
                                   std::to_string(space.function_count()) + " functions");
  }
  const auto start = Clock::now();
  FitResult result;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<Eigen::Vector3d> targets;
  int row = 0;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const DomainPoint& p = parameters[k];
    if (p.face < 0 || !space.in_domain(p.face)) continue;
    for (const auto& s : space.evaluate_basis(p))
      triplets.emplace_back(row, s.function, s.jet.value);
    targets.push_back(points.row(static_cast<Eigen::Index>(k)).transpose());
    ++row;
  }
  result.points = row;
  if (row == 0) throw ricci::InvalidInputError("fit: no point lies in the spline's domain");

  // Thin-plate rows, scaled so that lambda is dimensionless (see FitOptions).
  double area = 0.0, edge_sum = 0.0;
  for (int face : space.domain_faces()) {
    const auto p = space.atlas().face_positions(space.chart_of(face), face);
    area += chart_area(p);
    for (int k = 0; k < 3; ++k) edge_sum += (p.row((k + 1) % 3) - p.row(k)).norm();
  }
  const double h = edge_sum / (3.0 * space.domain_face_count());
  const double smoothing = options.smoothing * row / area * std::pow(h, 4);
  const int data_rows = row;
  if (smoothing > 0.0) {
    const auto rule = quadrature_rule();
    for (int face : space.domain_faces()) {
      const double face_area = chart_area(space.atlas().face_positions(space.chart_of(face), face));
      for (const auto& q : rule) {
        const double w = std::sqrt(smoothing * face_area * q.weight);
        for (const auto& s : space.evaluate_basis({face, q.bary})) {
          triplets.emplace_back(row, s.function, w * s.jet.hessian[0]);
          triplets.emplace_back(row + 1, s.function, w * std::sqrt(2.0) * s.jet.hessian[1]);
          triplets.emplace_back(row + 2, s.function, w * s.jet.hessian[2]);
        }
        row += 3;
      }
    }
  }
  Eigen::SparseMatrix<double> design(row, space.function_count());
  design.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::MatrixX3d rhs_points = Eigen::MatrixX3d::Zero(row, 3);
  for (int k = 0; k < data_rows; ++k) rhs_points.row(k) = targets[k].transpose();

  const double anchor = options.anchor * data_rows / space.function_count();
  Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(design.transpose()) * design;
  Eigen::SparseMatrix<double> identity(normal.rows(), normal.cols());
  identity.setIdentity();
  normal += anchor * identity;
  Eigen::MatrixX3d rhs = design.transpose() * rhs_points + anchor * initial;
  result.seconds_assemble = seconds_since(start);

  const auto solve_start = Clock::now();
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
  solver.cholmod().print = 0;  // libraries never print; failures are reported by info()
  solver.compute(normal);
  // Rounding in A^T A can outweigh a tiny anchor where a sliver makes basis Hessians huge: raise
  // the anchor to 1e-12, then 1e-10, of the largest diagonal entry before giving up.
  for (double relative : {1e-12, 1e-10}) {
    if (solver.info() == Eigen::Success) break;
    const double shift = relative * normal.diagonal().maxCoeff();
    normal += shift * identity;
    rhs += shift * initial;
    result.anchor_raised = true;
    solver.compute(normal);
  }
  if (solver.info() != Eigen::Success) {
    throw ricci::SolverError("fit: CHOLMOD could not factor the normal equations (" +
                             std::to_string(normal.rows()) + " unknowns)");
  }
  if (options.constraint_r < 0) {
    result.control_points = solver.solve(rhs);
    if (!result.control_points.allFinite()) throw ricci::SolverError("fit: non-finite solution");
  } else {
    FairOptions fair_options;
    fair_options.r = options.constraint_r;
    const Eigen::SparseMatrix<double> c = fairing_constraints(space, fair_options);
    const double w = options.constraint_penalty * normal.diagonal().mean();
    Eigen::SparseMatrix<double> penalised =
        normal + w * Eigen::SparseMatrix<double>(Eigen::SparseMatrix<double>(c.transpose()) * c);
    solver.compute(penalised);
    if (solver.info() != Eigen::Success) {
      throw ricci::SolverError("fit: CHOLMOD could not factor the constrained normal equations");
    }
    Eigen::MatrixX3d lambda = Eigen::MatrixX3d::Zero(c.rows(), 3);
    for (int it = 0; it < options.constraint_iterations; ++it) {
      result.control_points = solver.solve(Eigen::MatrixX3d(rhs - c.transpose() * lambda));
      if (!result.control_points.allFinite()) throw ricci::SolverError("fit: non-finite solution");
      const Eigen::MatrixX3d residual = c * result.control_points;
      lambda += w * residual;
      result.max_constraint_residual = residual.cwiseAbs().maxCoeff();
      if (result.max_constraint_residual <= 1e-12 * result.control_points.cwiseAbs().maxCoeff())
        break;
    }
  }
  result.seconds_solve = seconds_since(solve_start);

  const Eigen::MatrixX3d residual =
      Eigen::MatrixX3d(design.topRows(data_rows) * result.control_points) -
      rhs_points.topRows(data_rows);
  const Eigen::VectorXd distance = residual.rowwise().norm();
  result.rms_at_parameters = std::sqrt(distance.squaredNorm() / data_rows);
  result.max_at_parameters = distance.maxCoeff();
  return result;
}

Projection project_to_spline(const ManifoldSpline& spline, const DomainPoint& start,
                             const Eigen::Vector3d& target, int iterations) {
  const ManifoldSplineSpace& space = *spline.space;
  DomainPoint point = start;
  SurfaceJet jet = spline.evaluate(point);
  for (int it = 0; it < iterations; ++it) {
    const int chart = space.chart_of(point.face);
    Eigen::Matrix<double, 3, 2> j;
    j << jet.du, jet.dv;
    const Eigen::Matrix2d jtj = j.transpose() * j;
    if (std::abs(jtj.determinant()) < 1e-300) break;
    const Eigen::Vector2d step = -jtj.ldlt().solve(j.transpose() * (jet.position - target));
    const Eigen::Vector2d u = space.chart_point(chart, point.face, point.barycentric) + step;
    // The face of the neighbourhood (glued in this chart) containing u, else stay on the rim.
    DomainPoint next{-1, Eigen::Vector3d::Zero()};
    const ricci::Chart& c = space.atlas().charts[chart];
    // The face and the faces across its edges: one Gauss-Newton step rarely goes further.
    std::vector<int> candidates{point.face};
    for (int a = 0; a < 3; ++a) {
      const int g = space.neighbour(point.face, a);
      if (g >= 0) candidates.push_back(g);
    }
    double best = -1e300;
    for (int g : candidates) {
      if (!space.in_domain(g) || c.slot(g) < 0) continue;
      const Eigen::Vector3d bary = barycentric_in(space.atlas().face_positions(chart, g), u);
      const double worst = bary.minCoeff();
      if (worst > best) {
        best = worst;
        next = {g, bary};
      }
    }
    if (next.face < 0) break;
    if (best < 0.0) {  // outside the reachable faces: clamp into the best one
      next.barycentric = next.barycentric.cwiseMax(0.0);
      next.barycentric /= next.barycentric.sum();
    }
    const SurfaceJet trial = spline.evaluate(next);
    if ((trial.position - target).squaredNorm() > (jet.position - target).squaredNorm()) break;
    point = next;
    jet = trial;
    if (step.norm() < 1e-12 * space.atlas().domain_diameter) break;
  }
  return {point, jet.position, (jet.position - target).norm()};
}

FitErrors fit_errors(const ManifoldSpline& spline, const std::vector<DomainPoint>& parameters,
                     const Eigen::MatrixX3d& points, int iterations) {
  FitErrors errors;
  double sum = 0.0;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    if (parameters[k].face < 0 || !spline.space->in_domain(parameters[k].face)) continue;
    const Eigen::Vector3d p = points.row(static_cast<Eigen::Index>(k)).transpose();
    const double d = project_to_spline(spline, parameters[k], p, iterations).distance;
    sum += d * d;
    errors.max = std::max(errors.max, d);
    ++errors.points;
  }
  if (errors.points > 0) errors.rms = std::sqrt(sum / errors.points);
  return errors;
}

ScanFitResult fit_scan(const ricci::Mesh& dense, const ScanFitOptions& options) {
  const auto total_start = Clock::now();
  const auto stage = [&](const char* name) {
    if (options.progress) options.progress(name);
    return Clock::now();
  };
  ScanFitResult result;
  auto t = stage("simplify");
  ricci::SimplifyOptions simplify;
  simplify.target_faces = options.domain_faces;
  const ricci::Mesh domain = static_cast<int>(dense.n_faces()) > options.domain_faces
                                 ? ricci::simplify_mesh(dense, simplify).mesh
                                 : dense;
  result.timings.simplify = seconds_since(t);

  t = stage("atlas");
  result.atlas = ricci::build_one_cone_atlas(domain, options.atlas);
  result.timings.atlas = seconds_since(t);

  t = stage("space");
  const ricci::Mesh& mesh = result.atlas.problem.mesh;
  ManifoldSplineOptions space_options;
  space_options.degree = options.degree;
  space_options.knots = options.knots;
  auto space = std::make_shared<ManifoldSplineSpace>(mesh, result.atlas.atlas, space_options);
  const Eigen::MatrixX3d initial = piecewise_linear_control_points(*space, mesh);
  result.timings.space = seconds_since(t);

  t = stage("parameters");
  // Data: the scan's vertices and face centroids (points of the input surface), by closest point.
  const Eigen::Index nv = static_cast<Eigen::Index>(dense.n_vertices());
  Eigen::MatrixX3d data(nv + static_cast<Eigen::Index>(dense.n_faces()), 3);
  for (auto v : dense.vertices()) data.row(v.idx()) = ricci::to_eigen(dense.point(v)).transpose();
  for (auto f : dense.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (auto v : dense.fv_range(f)) c += ricci::to_eigen(dense.point(v));
    data.row(nv + f.idx()) = (c / 3.0).transpose();
  }
  const auto closest = ricci::closest_points(mesh, data);
  std::vector<DomainPoint> parameters(closest.size());
  for (std::size_t k = 0; k < closest.size(); ++k) {
    if (space->in_domain(closest[k].face))
      parameters[k] = {closest[k].face, closest[k].barycentric};
    else
      parameters[k] = {-1, Eigen::Vector3d::Zero()};
  }
  result.vertex_parameters.assign(parameters.begin(), parameters.begin() + nv);
  result.timings.parameters = seconds_since(t);

  t = stage("fit");
  FitOptions fit_options = options.fit;
  if (options.constrained_fit && options.fair_r >= 0) fit_options.constraint_r = options.fair_r;
  result.fit = fit_control_points(*space, parameters, data, initial, fit_options);
  result.timings.fit = seconds_since(t);

  result.spline.space = space;
  result.spline.control_points = result.fit.control_points;
  if (options.fair_r >= 0) {
    t = stage("fair");
    FairOptions fair_options = options.fair;
    fair_options.r = options.fair_r;
    result.fairing = fair(*space, result.fit.control_points, fair_options);
    result.spline.control_points = result.fairing.control_points;
    result.timings.fair = seconds_since(t);
  }
  result.timings.total = seconds_since(total_start);
  return result;
}

}  // namespace spline
