#pragma once
// Fairing of a manifold spline's control points (manifold-splines paper eq. 14): the control
// points nearest each edge are made to agree with the polynomial piece of the neighbour across it,
//     minimise sum |c~ - c|^2  subject to  c~_{I,beta} = f~^J(V_beta^I)  for beta_k <= r,
// for every domain face I, each edge (opposite corner k) with a domain neighbour J, where f~^J is
// the degree-n polynomial whose blossom values at J's knot sets are J's (faired) control points,
// blossomed at I's control-point arguments; I's and J's clouds are taken in the neighbourhood
// chart of I, which holds both glued (edges across the cut included). r = 0 shares the control
// points along edges (their arguments are knots of the edge's two clouds only).
//
// Solver: the constraints C c~ = 0 are linear and, taken over both orientations (I, J) and
// (J, I), linearly dependent, so the KKT matrix [I C^T; C 0] is singular. We use the augmented
// Lagrangian instead: (I + w C^T C) d = -C^T (w C c + lambda), c~ = c + d, lambda += w C c~, with
// one CHOLMOD factorisation of the SPD matrix reused over the iterations; it converges to the exact
// projection of c onto {C c~ = 0}, dependent rows and all. A global polynomial satisfies every
// constraint, so it is returned unchanged.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "spline/manifold/manifold_space.h"

namespace spline {

struct FairOptions {
  int r = 1;                 ///< rows of control points tied to each neighbour, in [0, n - 1]
  double penalty = 1e8;      ///< w, relative to the identity term
  int max_iterations = 50;   ///< augmented-Lagrangian updates
  double tolerance = 1e-12;  ///< stop when max |C c~| <= tolerance * max |c|
  /// By face: constraints only between two faces both marked (empty: all domain faces).
  std::vector<char> active_faces;
};

struct FairResult {
  Eigen::MatrixX3d control_points;
  int constraints = 0;  ///< rows of C
  int iterations = 0;
  double max_constraint_residual = 0.0;  ///< max |C c~|, absolute
  double max_change = 0.0;               ///< max |c~ - c|
};

/// The constraint matrix C (rows: one per constrained (I, beta, J)), columns: space functions.
/// \throw ricci::InvalidInputError for r outside [0, n - 1].
[[nodiscard]] Eigen::SparseMatrix<double> fairing_constraints(const ManifoldSplineSpace& space,
                                                              const FairOptions& options);

/// \throw ricci::InvalidInputError for a wrong row count or r out of range;
///        ricci::SolverError when the factorisation fails.
[[nodiscard]] FairResult fair(const ManifoldSplineSpace& space,
                              const Eigen::MatrixX3d& control_points,
                              const FairOptions& options = {});

}  // namespace spline
