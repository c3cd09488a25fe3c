#include "spline/fair/fair.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/basis/blossom.h"
#include "spline/basis/multi_index.h"

namespace spline {
namespace {

bool active(const FairOptions& options, int face) {
  return options.active_faces.empty() || options.active_faces[face] != 0;
}

}  // namespace

Eigen::SparseMatrix<double> fairing_constraints(const ManifoldSplineSpace& space,
                                                const FairOptions& options) {
  const int n = space.degree();
  if (options.r < 0 || options.r > n - 1) {
    throw ricci::InvalidInputError("fair: r = " + std::to_string(options.r) + " outside [0, " +
                                   std::to_string(n - 1) + "]");
  }
  if (!options.active_faces.empty() &&
      static_cast<int>(options.active_faces.size()) != space.face_count()) {
    throw ricci::InvalidInputError("fair: " + std::to_string(options.active_faces.size()) +
                                   " active flags for " + std::to_string(space.face_count()) +
                                   " faces");
  }
  const int m = space.functions_per_face();
  const std::vector<Eigen::Vector3i> betas = multi_indices(n);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(m, m);
  std::vector<Eigen::Triplet<double>> triplets;
  int rows = 0;
  for (int face : space.domain_faces()) {
    if (!active(options, face)) continue;
    const int chart = space.chart_of(face);
    const auto own = space.face_clouds(chart, face);
    for (int k = 0; k < 3; ++k) {
      const int other = space.neighbour(face, k);
      if (other < 0 || !space.in_domain(other) || !active(options, other)) continue;
      // The neighbour's polynomial as a linear map of its m control points: one column each.
      const auto theirs = space.face_clouds(chart, other);
      const BivariatePolynomial basis =
          polynomial_from_control_points(theirs[0], theirs[1], theirs[2], identity);
      for (int b = 0; b < m; ++b) {
        if (betas[b][k] > options.r) continue;
        const Eigen::VectorXd weights =
            blossom(basis, control_point_arguments(own[0], own[1], own[2], betas[b]));
        triplets.emplace_back(rows, space.function_index(face, b), 1.0);
        for (int g = 0; g < m; ++g) {
          // Below 1e-13 the weight is rounding noise of an exact 0 (e.g. r = 0: a unit vector).
          if (std::abs(weights[g]) > 1e-13) {
            triplets.emplace_back(rows, space.function_index(other, g), -weights[g]);
          }
        }
        ++rows;
      }
    }
  }
  Eigen::SparseMatrix<double> c(rows, space.function_count());
  c.setFromTriplets(triplets.begin(), triplets.end());
  return c;
}

FairResult fair(const ManifoldSplineSpace& space, const Eigen::MatrixX3d& control_points,
                const FairOptions& options) {
  if (control_points.rows() != space.function_count()) {
    throw ricci::InvalidInputError("fair: " + std::to_string(control_points.rows()) +
                                   " control points for " + std::to_string(space.function_count()) +
                                   " functions");
  }
  const Eigen::SparseMatrix<double> c = fairing_constraints(space, options);
  FairResult result;
  result.constraints = static_cast<int>(c.rows());
  result.control_points = control_points;
  if (c.rows() == 0) return result;

  const double w = options.penalty;
  Eigen::SparseMatrix<double> k = Eigen::SparseMatrix<double>(c.transpose()) * c;
  k *= w;
  Eigen::SparseMatrix<double> identity(k.rows(), k.cols());
  identity.setIdentity();
  k += identity;
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
  solver.cholmod().print = 0;  // libraries never print; failures are reported by info()
  solver.compute(k);
  if (solver.info() != Eigen::Success) {
    throw ricci::SolverError("fair: CHOLMOD could not factor I + w C^T C (" +
                             std::to_string(k.rows()) + " unknowns)");
  }
  // Unknown: the correction d = c~ - c, small when c is nearly feasible, so the solver's relative
  // error (about cond(K) eps) costs little absolutely; a feasible c gives d = 0 to rounding.
  const double scale = std::max(control_points.cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::MatrixX3d infeasibility = c * control_points;
  Eigen::MatrixX3d lambda = Eigen::MatrixX3d::Zero(c.rows(), 3);
  Eigen::MatrixX3d x = control_points;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::MatrixX3d rhs = -Eigen::MatrixX3d(c.transpose() * (w * infeasibility + lambda));
    const Eigen::MatrixX3d d = solver.solve(rhs);
    if (!d.allFinite()) throw ricci::SolverError("fair: non-finite solution");
    x = control_points + d;
    const Eigen::MatrixX3d residual = infeasibility + c * d;
    lambda += w * residual;
    result.iterations = it + 1;
    result.max_constraint_residual = residual.cwiseAbs().maxCoeff();
    if (result.max_constraint_residual <= options.tolerance * scale) break;
  }
  result.control_points = x;
  result.max_change = (x - control_points).rowwise().norm().maxCoeff();
  return result;
}

}  // namespace spline
