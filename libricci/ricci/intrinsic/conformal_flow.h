#pragma once
// Discrete conformal (vertex-scaling) flow with intrinsic Delaunay flips: the metric with
// lengths l_ij = exp((u_i + u_j) / 2) l_ij^0, re-triangulated by Ptolemy flips to stay Delaunay
// at every u, whose vertex curvature reaches a target. Newton's method on the convex, C^1
// energy of Gillespie, Springborn and Crane 2021 ("Discrete conformal equivalence of polyhedral
// surfaces", sections 4-5; Gu, Luo, Sun, Wu 2018 for the existence): its gradient is K - K̄
// and its Hessian the cotangent Laplacian of the Delaunay triangulation. Any target meeting
// Gauss-Bonnet with cone angles > 0 has a solution, so a single cone of curvature 2 pi chi
// converges at every genus, where the fixed-connectivity flows (flow.h) break triangles.
//
//   ricci::IntrinsicFlowResult r =
//       ricci::intrinsic_conformal_flow(mesh, ricci::single_cone_target(mesh, cone));
//   if (r.converged()) use(ricci::to_mesh(r.triangulation, r.u, positions));
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ricci/flow/flow.h"
#include "ricci/flow/linear_solver.h"
#include "ricci/flow/targets.h"
#include "ricci/intrinsic/intrinsic_triangulation.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

struct IntrinsicFlowOptions {
  /// Stop when max_i |K_i - K̄_i| is below this (radians).
  double tolerance = 1e-10;
  /// Newton iterations allowed.
  int max_iterations = 400;
  /// Halvings of a Newton step before the line search gives up.
  int max_step_halvings = 60;
  /// A step is taken when the energy's slope along it is at most this times |slope at 0|
  /// (0: only up to the line's minimum). 0 rejects every full Newton step that lands a little
  /// past the minimum, and the halved steps that follow converge only linearly
  /// (docs/design-notes.md, "Intrinsic flow line search").
  double slope_fraction = 0.1;
  /// Smallest factor a rejected step shrinks by (the secant estimate is clamped to [this, 0.5]).
  double min_shrink = 0.25;
  /// Sparse factorisation of the cotangent Laplacian (automatic: resolve_linear_solver).
  LinearSolver solver = LinearSolver::automatic;
  /// An edge is flipped when 2 (cos alpha + cos beta) is below -delaunay_margin.
  double delaunay_margin = 1e-12;
  /// Once max |K - K̄| is below this (radians), the triangulation stops flipping and Newton
  /// finishes on it (quadratically; at the answer it is Delaunay up to this order). Flipping to
  /// the end can make Newton circle between the triangulations of nearly co-circular quads.
  double freeze_connectivity_below = 1e-4;
  /// Below this max |K - K̄| (radians), after a full step, Newton first solves with the last
  /// factorisation as a preconditioner (solve_with_nearby_factorization) and factorises only
  /// when that does not converge.
  double nearby_factorization_below = 0.05;
  /// Chord steps (modified Newton): away from the answer too, Newton first solves by
  /// conjugate gradients preconditioned with the last factorisation
  /// (solve_by_preconditioned_cg), to relative residual min(1e-2 max |K - K̄|, this cap); 0:
  /// only below nearby_factorization_below. A solve that fails, or takes chord_stale_steps
  /// back-substitutions or more, has the next step factorise anew; so does the first step
  /// with frozen connectivity (that factorisation serves the remaining steps and the polish).
  /// A cap of 0.1 spared as many factorisations at 100k faces but took the genus-8 flow of
  /// LargeConeCharts to a triangulation whose layout turned a face over.
  double chord_forcing_cap = 1e-3;
  int chord_max_steps = 12;
  int chord_stale_steps = 6;
  /// The first step with frozen connectivity keeps the last factorisation instead (to serve
  /// the remaining steps and the polish) when it is not stale and at most this fraction of the
  /// edges flipped since it was made (0: only when nothing flipped; negative: never).
  double frozen_factor_flips = 1e-3;
  /// A new Laplacian to factorise is analysed with the last analysis' ordering (sparing the
  /// fill-reducing ordering, most of an analysis) when at most this fraction of the edges
  /// flipped since that analysis; otherwise it is ordered afresh (the flips of the first Newton
  /// steps gather around the cone and leave an old ordering much more fill: docs/design-notes.md,
  /// "Orderings, flips and distortion on both cores").
  double ordering_reuse_flips = 1e-3;
  /// Below freeze_connectivity_below, the flow stops (stalled) after this many iterations
  /// without halving max |K - K̄|: the double evaluation's rounding floor (long needles next to
  /// a large cone), which a long-double polish (metric/polish_e2.h) can pass.
  int plateau_iterations = 12;
  /// Below this max |K - K̄| (radians) the plateau ends after floor_plateau_iterations: Newton
  /// on double evaluations gains nothing there that the long-double polish does not do in one
  /// step (a 1.6M-face mesh's floor is ~1e-10).
  double floor_below = 1e-8;
  int floor_plateau_iterations = 2;
  /// Optional progress report, after each Newton iteration.
  std::function<void(const FlowProgress&)> progress;
};

/// How a flow given a warm start (intrinsic_conformal_flow's warm_u) began.
enum class WarmStart {
  none,       ///< no warm start given: Newton started at u = 0
  taken,      ///< Newton started at the warm start and converged from there
  rejected,   ///< its max |K - K̄| was no lower than at u = 0 (or its evaluation failed)
  abandoned,  ///< Newton from it stopped far from the answer; the flow restarted at u = 0
};

/// "none", "taken", "rejected", "abandoned".
[[nodiscard]] std::string to_string(WarmStart warm);

struct IntrinsicFlowResult {
  /// converged, max_iterations or stalled (the line search found no step).
  FlowStatus status = FlowStatus::stalled;
  std::string message;  ///< empty when converged
  /// The final triangulation, Delaunay at `u`; its vertices are the input's.
  IntrinsicTriangulation triangulation;
  Eigen::VectorXd u;  ///< log scale factors by vertex (one vertex pinned at 0)
  Eigen::VectorXd curvature, target;
  std::vector<double> error_history;  ///< max |K - K̄| before the first iteration and after each
  int iterations = 0;
  int flips = 0;  ///< Ptolemy flips, including those of rejected line-search trials
  int line_search_trials = 0;  ///< evaluations at trial steps, accepted or not
  /// By flip, in order: the edge flipped (flip_edge) on the way from the initial triangulation
  /// to `triangulation`; point_tracking.h replays it to carry points between the two.
  std::vector<int> flip_log;
  int factorizations = 0;
  /// Analyses that took the previous analysis' ordering (ordering_reuse_flips).
  int orderings_reused = 0;
  LinearWork linear_work;  ///< factorisations and back-substitutions (linear_solver.h)
  double max_error = 0;
  LinearSolver solver = LinearSolver::automatic;
  FlowTimings timings;
  /// The last factorisation Newton used (null if none): of the cotangent Laplacian at an
  /// iterate near u, without pinned_vertex's row and column (a preconditioner for a polish,
  /// metric/polish_e2.h).
  std::shared_ptr<const SymmetricFactorization> laplacian_factorization;
  int pinned_vertex = -1;  ///< the vertex held at u = 0
  WarmStart warm_start = WarmStart::none;
  /// max |K - K̄| at u = 0 on the given triangulation (before any flip) and at the warm start
  /// (shifted to u = 0 at the pinned vertex); both 0 without a warm start.
  double cold_start_error = 0.0, warm_start_error = 0.0;

  [[nodiscard]] bool converged() const { return status == FlowStatus::converged; }
};

/// Runs the flow from the mesh's own edge lengths (first flipped to intrinsic Delaunay).
/// \pre a closed, connected triangle 2-manifold without degenerate faces.
/// \throw InfeasibleTargetError when the target breaks Gauss-Bonnet or asks for a cone angle
///        <= 0; InvalidInputError for a mesh with boundary or a size mismatch.
[[nodiscard]] IntrinsicFlowResult intrinsic_conformal_flow(
    const Mesh& mesh, const Targets& targets, const IntrinsicFlowOptions& options = {});

/// Runs the flow from a given triangulation (its log lengths at u = 0). \throw as above.
[[nodiscard]] IntrinsicFlowResult intrinsic_conformal_flow(
    IntrinsicTriangulation initial, const Eigen::VectorXd& target,
    const IntrinsicFlowOptions& options = {});

/// Runs the flow from a given triangulation with Newton starting at `warm_u` (log scale
/// factors by vertex, e.g. the singularity choice's linear prediction) instead of 0: the first
/// steps, which the line search damps while the cone's neighbourhood flips, are spared. The
/// warm start is rejected when its max |K - K̄| is not below u = 0's, and abandoned (the flow
/// restarts at u = 0 on the triangulation reached) when Newton from it stops with
/// max |K - K̄| >= freeze_connectivity_below; result.warm_start says which.
/// \throw as above; InvalidInputError when warm_u's size is not the vertex count.
[[nodiscard]] IntrinsicFlowResult intrinsic_conformal_flow(
    IntrinsicTriangulation initial, const Eigen::VectorXd& target, const Eigen::VectorXd& warm_u,
    const IntrinsicFlowOptions& options = {});

/// The result's figures (status, message, u, curvature, target, history, iterations,
/// factorisations, linear work, error, solver, timings) as a FlowResult, whose metric and lengths stay empty
/// (the lengths belong to the flipped triangulation: to_mesh).
[[nodiscard]] FlowResult to_flow_result(const IntrinsicFlowResult& result);

}  // namespace ricci
