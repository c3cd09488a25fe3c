#pragma once
// Quad-precision polish of a hyperbolic metric's edge lengths. The flow stops where double
// evaluation of the curvature stops improving (max |K - K̄| ~ 1e-14), and each vertex's angle
// defect is a rotation about it that the Fuchsian relator sees conjugated by partial products
// of norm up to e^d, d the distance of the vertex from the relator's base point (e^30 at genus
// 10): the defects, not the layout's rounding, are what leave relation residuals of 1e-8 on
// genus 3 domains and of order 1 at genus 10. Steps of mixed-precision iterative refinement
// (curvature in quad precision, an approximate Hessian factored once in double) remove them.
#include <vector>

#include <Eigen/Core>

#include "ricci/hyperbolic/mobius_q.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

using LengthsL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

using LengthsQ = std::vector<RealQ>;

struct PolishH2Options {
  /// Each step gains ~2-3 digits (the Hessian is approximate): 1e-14 to 1e-30 takes ~8.
  int max_iterations = 16;
  /// Stop once max |K - K̄| (evaluated in quad precision, radians) is below this.
  double tolerance = 1e-30;
};

struct PolishH2Result {
  LengthsL lengths;       ///< By edge index, hyperbolic: quad_lengths rounded to long double.
  LengthsQ quad_lengths;  ///< The polished lengths in quad precision (what layout_h2 takes).
  /// max |K - K̄| in quad precision before and after, and the steps taken.
  double error_before = 0.0, error_after = 0.0;
  int iterations = 0;
};

/// Hyperbolic vertex scaling sinh(l'_ij / 2) = e^{(u_i + u_j)/2} sinh(l_ij / 2) (the discrete
/// conformal change of Bobenko-Pinkall-Springborn) solving K(u) = target: each step solves
/// (L + diag(2 A_i)) du = -(K - target), L the cotangent Laplacian of the hyperbolic angles and
/// A_i a third of the adjacent faces' areas (dK/du for small triangles; a uniform du scales the
/// area by 2 du), factored once; the residual is evaluated in quad precision, so the steps
/// converge to the quad-precision solution near `lengths`.
/// \pre closed mesh; lengths (by edge index) satisfy the hyperbolic triangle inequality and are
///      already close to the solution (e.g. a converged flow's).
/// \throw InvalidInputError on a size mismatch or a face violating the triangle inequality.
[[nodiscard]] PolishH2Result polish_h2_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                               const Eigen::VectorXd& target,
                                               const PolishH2Options& options = {});

/// The three angles of a hyperbolic triangle with side lengths l (l[k] opposite corner k), by
/// the half-angle formula, in long double. Returns false when the triangle inequality fails.
bool hyperbolic_angles_l(const long double l[3], long double theta[3]);

/// The same in quad precision.
bool hyperbolic_angles_q(const RealQ l[3], RealQ theta[3]);

}  // namespace ricci
