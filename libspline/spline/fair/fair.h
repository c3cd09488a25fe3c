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
// Solver: solve_constrained (constrained_solve.h) with K = I: the rows c~_i = c~_j (all of r = 0,
// and the beta_k = 0 rows of every r) merge unknowns exactly, so r = 0 is the closed form "mean
// of the shared copies"; the beta_k >= 1 rows go to the method of multipliers (they are
// redundant over (I, J) / (J, I), so the KKT matrix is singular). It converges to the exact
// projection of c onto {C c~ = 0}. A global polynomial satisfies every constraint, so it is
// returned unchanged.
//
// What the rows mean: for the edge (v0, v1) opposite v2 in I and each (n-1)-tuple a of knots of
// the two edge clouds (first knots of each, beta_2 = 0 or 1), the affine map x -> P(a, x) of I's
// blossom equals J's. r = 1 therefore makes the four distinct control points
// P(a, t_{0,beta0}), P(a, t_{1,beta1}) (shared), P^I(a, v2) and P^J(a, v3) (Fig. 13's six
// highlighted points, two pairs coinciding) images of one affine map: coplanar, with v3's
// barycentric coordinates in (t_{0,beta0}, t_{1,beta1}, v2) (tests/spline/fair). With knot clouds
// off the edge this is not C^1 of the pieces f^I, f^J across the edge line; counted like C^1
// cubics (3V + F - E_interior for n = 3, r = 1, measured by rank), and r = n - 1 leaves only a
// few global polynomials.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "spline/manifold/manifold_space.h"

namespace spline {

struct FairOptions {
  int r = 1;                 ///< rows of control points tied to each neighbour, in [0, n - 1]
  double penalty = 1e8;      ///< w, relative to the mean class size (the reduced K's diagonal)
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
