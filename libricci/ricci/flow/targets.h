#pragma once
// Target curvatures for the Ricci flow (Ricci-flow paper §V; manifold-splines paper §4) and their
// feasibility check.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"
#include "ricci/metric/circle_packing.h"
#include "ricci/metric/geometry.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

/// Target discrete curvature K̄ per vertex index (interior: 2π minus the cone angle; boundary:
/// π minus the boundary angle, i.e. the discrete geodesic curvature).
struct Targets {
  Eigen::VectorXd curvature;
};

/// How boundary_target distributes the boundary's total curvature 2πχ.
enum class BoundaryMode {
  spread_by_length,  ///< over all boundary vertices, proportional to their boundary edge length
  one_loop,          ///< over one loop only (by length); the other loops get 0 (geodesic)
  /// Like a circle domain: every loop but the longest gets -2π (a round hole), the longest the
  /// rest, 2π(1 - 2g); each spread over its own loop by length.
  circle_domain
};

/// Uniformization: K̄ = 0 at every vertex (E2 for χ = 0, H2 for χ < 0, S2 for χ > 0, with the
/// curvature carried by the faces in H2/S2). \throw InfeasibleTargetError when the geometry does
/// not match the sign of χ.
[[nodiscard]] Targets uniform_target(const Mesh& mesh, Geometry geometry);

/// Flat metric with one cone: K̄ = 2πχ at `vertex`, 0 elsewhere (manifold-splines §4). On an
/// open surface the boundary takes the curvature instead (interior 0, boundary spread by length)
/// and `vertex` is not used. \throw InvalidInputError for a vertex out of range.
[[nodiscard]] Targets single_cone_target(const Mesh& mesh, int vertex);

/// Flat metric with the given cones (vertex, K̄); every other interior vertex is flat. On an open
/// surface the boundary takes 2πχ minus the cones' sum, spread by length. \throw
/// InvalidInputError for a vertex out of range or listed twice.
[[nodiscard]] Targets cones_target(const Mesh& mesh, const std::vector<std::pair<int, double>>& cones);

/// Flat interior, boundary curvature 2πχ spread by boundary length, over all loops or over one
/// loop (`loop` indexes MeshTables::boundary_loops; -1 picks the longest loop).
/// \throw InvalidInputError for a closed mesh or a loop out of range.
[[nodiscard]] Targets boundary_target(const Mesh& mesh, BoundaryMode mode, int loop = -1);

/// The target named by `spec`, as `msp flow --target` and the Python `flow` read it: "uniform"
/// (uniform_target), "cone:VERTEX" (single_cone_target), "boundary" (boundary_target spread by
/// length) or "boundary-loop" (on the longest loop). \throw InvalidInputError for any other
/// spec, and as the named function throws.
[[nodiscard]] Targets parse_target(const std::string& spec, const Mesh& mesh, Geometry geometry);

/// Checks a target before any work: its size, finiteness, cone angles below 2π (π on the
/// boundary), Gauss-Bonnet (Σ K̄ = 2πχ in E2, > 2πχ in H2, < 2πχ in S2, because the faces carry
/// λ Σ A = 2πχ - Σ K̄ of area with λ = -1 in H2 and +1 in S2), and for circle packings with
/// Φ ∈ [0, π/2] (circle_packing, combinatorial) the valence a cone needs,
/// valence ≥ 4 - 2 K̄/π (manifold-splines §4 step 2).
/// \throw InfeasibleTargetError naming the sums or the vertex and what to do.
void check_targets(const MeshTables& tables, const Targets& targets, Geometry geometry,
                   Scheme scheme);

}  // namespace ricci
