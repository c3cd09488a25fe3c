#pragma once
// Equality-constrained least squares shared by fitting and fairing (manifold-splines eq. 14):
//     minimise 1/2 x^T K x - tr(b^T x)  subject to  C x = 0,   x: n x 3,
// K symmetric positive definite (given by its lower triangle), C sparse with dependent rows.
//
// Why not a plain KKT system: eq. 14's rows are redundant (the rows of (I, J) and of (J, I) are
// equivalent, and the rows tying the n-1 fold blossom at a vertex close up around its star), so
// [K C^T; C 0] is singular, and CHOLMOD has no pivoting LDL^T for it. Why not a null-space basis
// throughout: for r >= 1 the space {C x = 0} is a C^1-like spline space (measured: dimension
// 3V + F - E_interior for cubics, r = 1), which has no sparse local basis in general.
// So, in two steps:
//  1. Null-space elimination where it is exact and sparse: rows x_i - x_j = 0 (all r = 0 rows,
//     the DMS shared control points) merge i and j into one unknown, x = P y (P: 0/1, one entry
//     per row). K_r = P^T K P, b_r = P^T b.
//  2. The remaining rows C_r = C P by the method of multipliers (augmented Lagrangian) around a
//     reference y0 (the reduced `reference`): (K_r + w C_r^T C_r) e = g - C_r^T lambda + w C_r^T h,
//     lambda += w (C_r e - h), y = y0 + e, with g = b_r - K_r y0, h = -C_r y0; one CHOLMOD
//     factorisation reused. It converges to the exact constrained minimiser whatever the
//     redundancy (the multipliers of dependent rows are simply not unique). A feasible reference
//     that is already optimal gives e = 0 up to rounding of a small right-hand side.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace spline {

struct ConstrainedSolveOptions {
  double penalty = 1e6;     ///< w relative to the mean diagonal of K_r (lowered by 100 on failure)
  int max_iterations = 100;  ///< multiplier updates
  /// Stop when max |C_r y| <= tolerance * max |y|, or when an update no longer reduces it (the
  /// floor set by the factorisation's rounding, ~1e-10 relative on the fits).
  double tolerance = 1e-12;
};

struct ConstrainedSolution {
  Eigen::MatrixX3d x;
  int iterations = 0;
  int merged_rows = 0;        ///< rows eliminated by merging unknowns (step 1)
  int remaining_rows = 0;     ///< rows left to the multipliers (step 2)
  int reduced_unknowns = 0;   ///< columns of P
  double penalty = 0.0;       ///< w actually used (absolute)
  double max_residual = 0.0;  ///< max |C x| over all rows of C
};

/// The part of the solve that depends on C alone: step 1's classes of unknowns (P) and step 2's
/// C_r = C P with the lower triangle of C_r^T C_r. A fit and its parameter corrections solve
/// against one C with several K; built once, it gives the same bits as solve_constrained's own.
struct ReducedConstraints {
  Eigen::Index rows = 0, unknowns = 0;  ///< Of C.
  std::vector<int> unknown_class;       ///< Column of P of every unknown (n entries).
  int classes = 0;                      ///< Columns of P.
  Eigen::SparseMatrix<double> c_r;      ///< C P without the merged rows.
  Eigen::SparseMatrix<double> ctc_lower;  ///< Lower triangle of C_r^T C_r (empty without rows).
};

/// Steps 1 and 2's set-up for the constraint matrix `c` (any size; no rows: P = I).
[[nodiscard]] ReducedConstraints reduce_constraints(const Eigen::SparseMatrix<double>& c);

/// \param k_lower lower triangle of K (n x n); entries above the diagonal are ignored.
/// \param reference n x 3 starting point (e.g. the unconstrained data), or empty for zero.
/// \throw ricci::InvalidInputError on size mismatches; ricci::SolverError when K_r (+ w C^T C)
///        cannot be factored or the solution is not finite.
[[nodiscard]] ConstrainedSolution solve_constrained(const Eigen::SparseMatrix<double>& k_lower,
                                                    const Eigen::MatrixX3d& b,
                                                    const Eigen::SparseMatrix<double>& c,
                                                    const Eigen::MatrixX3d& reference,
                                                    const ConstrainedSolveOptions& options = {});

/// solve_constrained with `reduced` = reduce_constraints(c) built beforehand (the same result).
/// \pre `reduced` was built from `c`.
/// \throw as solve_constrained; ricci::InvalidInputError also when `reduced`'s sizes are not c's.
[[nodiscard]] ConstrainedSolution solve_constrained(const Eigen::SparseMatrix<double>& k_lower,
                                                    const Eigen::MatrixX3d& b,
                                                    const Eigen::SparseMatrix<double>& c,
                                                    const ReducedConstraints& reduced,
                                                    const Eigen::MatrixX3d& reference,
                                                    const ConstrainedSolveOptions& options = {});

}  // namespace spline
