#pragma once
// Extended-precision polish of a flat metric's edge lengths. Newton on the Ricci energy stops
// where double evaluation of the curvature stops improving (max |K - K̄| ~ 1e-12 on scans with
// slivers or many boundary loops), and the layout multiplies that leftover defect by the size of
// the loops it closes (beetle: relative edge errors of 1e-7 in the central chart). A few steps of
// mixed-precision refinement (curvature in long double, the cotangent Laplacian factored once
// in double) bring the defect to the rounding of the lengths themselves. The polish_h2 of the
// hyperbolic room does the same for H2.
#include <Eigen/Core>

#include "ricci/flow/linear_solver.h"
#include "ricci/mesh/mesh.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

struct PolishE2Result {
  Eigen::VectorXd lengths;  ///< By edge index.
  /// The long-double lengths' low parts: lengths + lengths_low is the polished metric to ~1e-19
  /// (layout_e2 and build_affine_atlas take it; rounding it to double alone leaves defects of
  /// 2e-11 at the needles of a 1.6M-face intrinsic triangulation). Empty when no step was taken.
  Eigen::VectorXd lengths_low;
  /// max |K - K̄| evaluated in long double before and after, and the steps taken.
  double error_before = 0.0, error_after = 0.0;
  int iterations = 0;
  /// Factorisations and back-substitutions spent (on the nearby factorisation and its own).
  LinearWork linear_work;
};

/// A factorisation of a cotangent Laplacian near the one at the lengths being polished (the
/// flow's last), without vertex `pinned`'s row and column: polish_e2_lengths then solves by
/// solve_with_nearby_factorization with it (factorising its own matrix only if that fails).
struct NearbyLaplacian {
  const SymmetricFactorization* factorization = nullptr;
  int pinned = 0;
};

/// Vertex scaling l'_ij = e^{(u_i + u_j) / 2} l_ij solving K(u) = target (interior: 2 pi minus
/// the angle sum; boundary: pi minus it), each step solving L du = -(K - target) with du
/// pinned to 0 at one vertex and L the cotangent Laplacian at the given lengths (dK/du),
/// factored once (or `nearby`'s, see NearbyLaplacian); the residual is evaluated in long
/// double. Steps until max |K - K̄| is at most `good_enough`, or until a step fails to halve it
/// (the evaluation's floor: that step is kept), or one does not improve it (thrown away).
/// Returns the given lengths when the first step does not improve.
/// \pre lengths close to a solution (a converged flow's); target sums to 2 pi chi; a nearby
///      factorisation has the size of the mesh's vertices minus one; good_enough >= 0.
/// \throw InvalidInputError on a size mismatch or a face violating the triangle inequality.
[[nodiscard]] PolishE2Result polish_e2_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                               const Eigen::VectorXd& target,
                                               int max_iterations = 6,
                                               NearbyLaplacian nearby = {},
                                               double good_enough = 0.0);

/// The same on the mesh's tables (metric/mesh_tables.h; lengths by their edge index), for a
/// caller that holds the tables and not the mesh (the intrinsic flow's triangulation at 1.6M
/// faces: to_mesh_tables). The same results as on the mesh whose tables they are.
[[nodiscard]] PolishE2Result polish_e2_lengths(const MeshTables& tables,
                                               const Eigen::VectorXd& lengths,
                                               const Eigen::VectorXd& target,
                                               int max_iterations = 6,
                                               NearbyLaplacian nearby = {},
                                               double good_enough = 0.0);

}  // namespace ricci
