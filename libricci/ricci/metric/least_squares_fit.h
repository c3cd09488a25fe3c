#pragma once
// Least-squares fit of Thurston circle-packing radii to given edge lengths (manifold-splines
// eq. 10): min over (Γ, Φ) of Σ_e (l_e(Γ, Φ) - l̄_e)², Φ_e ∈ [0, π/2].
#include <Eigen/Core>

#include "ricci/metric/geometry.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

/// For fixed radii the best Φ_e is the cosine-law weight clamped to [0, π/2], so the problem
/// reduces to the radii: each edge's residual is its length's distance to the interval of
/// lengths reachable with Φ ∈ [0, π/2]. Minimised by Levenberg-Marquardt in the flow variables
/// u (which keep radii positive), starting from `initial_radii`. Returns the fitted radii; never
/// worse than the start.
[[nodiscard]] Eigen::VectorXd fit_circle_packing_radii(const MeshTables& tables,
                                                       const EdgeLengths& lengths,
                                                       Geometry geometry,
                                                       const Eigen::VectorXd& initial_radii);

/// Σ_e (l_e - l̄_e)² for radii gamma with the best clamped weights.
[[nodiscard]] double circle_packing_fit_cost(const MeshTables& tables, const EdgeLengths& lengths,
                                             Geometry geometry, const Eigen::VectorXd& gamma);

}  // namespace ricci
