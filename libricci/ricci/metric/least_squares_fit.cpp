#include "ricci/metric/least_squares_fit.h"

#include <algorithm>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "ricci/metric/circle_packing.h"

namespace ricci {

namespace {

// Largest change of a log-radius per Levenberg-Marquardt step. Unbounded steps let the radii
// of sliver vertices run off to 1e-89 (genus2_100k), where every circle packing of their faces
// is degenerate in double precision.
constexpr double kMaxLogStep = 0.5;

// Residual of one edge and the clamped weight it uses; 0 when some Φ ∈ [0, π/2] fits exactly.
struct EdgeFit {
  double residual = 0;
  double eta = 0;
  bool active = false;
};

EdgeFit fit_edge(Geometry g, double a, double b, double target) {
  const double exact = circle_edge_eta(g, a, b, target);
  EdgeFit fit;
  if (exact >= 0.0 && exact <= 1.0) return fit;
  fit.active = true;
  fit.eta = std::clamp(exact, 0.0, 1.0);
  fit.residual = circle_edge_length(g, a, b, fit.eta) - target;
  return fit;
}

double cost_of(const MeshTables& t, const EdgeLengths& l, Geometry g, const Eigen::VectorXd& gamma) {
  double cost = 0;
  for (int e = 0; e < t.num_edges(); ++e) {
    const EdgeFit fit = fit_edge(g, gamma[t.edge_vertices(e, 0)], gamma[t.edge_vertices(e, 1)], l[e]);
    cost += fit.residual * fit.residual;
  }
  return cost;
}

}  // namespace

double circle_packing_fit_cost(const MeshTables& t, const EdgeLengths& l, Geometry g,
                               const Eigen::VectorXd& gamma) {
  return cost_of(t, l, g, gamma);
}

Eigen::VectorXd fit_circle_packing_radii(const MeshTables& t, const EdgeLengths& l, Geometry g,
                                         const Eigen::VectorXd& initial_radii) {
  const int nv = t.num_vertices();
  Eigen::VectorXd gamma = initial_radii;
  double cost = cost_of(t, l, g, gamma);
  double damping = 1e-3;
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  for (int iteration = 0; iteration < 50 && cost > 0; ++iteration) {
    // Normal equations J^T J δ = -J^T r over the active (clamped) edges.
    triplets.clear();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nv);
    Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(nv);
    for (int e = 0; e < t.num_edges(); ++e) {
      const int i = t.edge_vertices(e, 0), j = t.edge_vertices(e, 1);
      const EdgeFit fit = fit_edge(g, gamma[i], gamma[j], l[e]);
      if (!fit.active) continue;
      const double len = fit.residual + l[e];
      const double di = circle_edge_length_du(g, gamma[i], gamma[j], fit.eta, len);
      const double dj = circle_edge_length_du(g, gamma[j], gamma[i], fit.eta, len);
      triplets.emplace_back(i, i, di * di);
      triplets.emplace_back(j, j, dj * dj);
      triplets.emplace_back(i, j, di * dj);
      triplets.emplace_back(j, i, di * dj);
      diagonal[i] += di * di;
      diagonal[j] += dj * dj;
      rhs[i] -= di * fit.residual;
      rhs[j] -= dj * fit.residual;
    }
    const double scale = std::max(diagonal.maxCoeff(), 1e-300);
    bool improved = false;
    for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
      // Levenberg-Marquardt: J^T J + μ diag(J^T J) + tiny·I is definite even on free vertices.
      std::vector<Eigen::Triplet<double>> damped = triplets;
      for (int v = 0; v < nv; ++v) damped.emplace_back(v, v, damping * diagonal[v] + 1e-12 * scale);
      Eigen::SparseMatrix<double> normal(nv, nv);
      normal.setFromTriplets(damped.begin(), damped.end());
      solver.compute(normal);
      if (solver.info() != Eigen::Success) {
        damping *= 10;
        continue;
      }
      const Eigen::VectorXd step = solver.solve(rhs).cwiseMax(-kMaxLogStep).cwiseMin(kMaxLogStep);
      Eigen::VectorXd trial(nv);
      for (int v = 0; v < nv; ++v) {
        trial[v] = radius_from_u(g, u_from_radius(g, gamma[v]) + step[v]);
      }
      const double trial_cost = trial.allFinite() ? cost_of(t, l, g, trial) : cost;
      if (trial_cost < cost) {
        improved = (cost - trial_cost) > 1e-14 * cost;
        gamma = trial;
        cost = trial_cost;
        damping = std::max(damping * 0.3, 1e-9);
        if (!improved) return gamma;
      } else {
        damping *= 10;
      }
    }
    if (!improved) break;
  }
  return gamma;
}

}  // namespace ricci
