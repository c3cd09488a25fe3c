#pragma once
// Discrete surface Ricci flow: find the circle-packing metric conformal to the mesh's whose
// vertex curvature is a given target, by Newton's method on the convex Ricci energy (or the
// papers' gradient descent, for comparison). The Ricci-flow paper (discrete-surface-ricci-flow)
// §V; the shape-analysis paper (ricci-flow-3d-shape-analysis) §3.5-4.
//
//   ricci::Targets targets = ricci::uniform_target(mesh, ricci::Geometry::euclidean);
//   ricci::FlowResult result = ricci::flow(mesh, targets);
//   if (!result.converged()) std::cerr << result.message;
//   use(result.lengths);
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ricci/flow/linear_solver.h"
#include "ricci/flow/targets.h"
#include "ricci/mesh/mesh.h"
#include "ricci/metric/circle_packing.h"
#include "ricci/metric/geometry.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

enum class FlowMethod { newton, gradient_descent };

enum class FlowStatus {
  converged,           ///< max |K - K̄| < tolerance
  max_iterations,      ///< iteration budget spent while still making progress
  stalled,             ///< the line search found no decrease (or the factorisation failed)
  triangle_inequality  ///< every trial step broke a triangle: the target is out of reach
};

std::string to_string(FlowStatus status);
std::string to_string(FlowMethod method);

/// One line of progress, reported after each iteration (Newton) or every 100 (gradient).
struct FlowProgress {
  int iteration = 0;
  double max_error = 0;  ///< max |K - K̄| after the iteration
  double step = 0;       ///< line-search step length taken (1 = full Newton step)
  double seconds = 0;    ///< since the solve started
};

struct FlowOptions {
  Geometry geometry = Geometry::euclidean;
  Scheme scheme = Scheme::inversive_distance;
  /// Min (shape-analysis Alg. 1) converged on more of the shared models than Mean.
  RadiusInit radii = RadiusInit::min;
  FlowMethod method = FlowMethod::newton;
  /// Stop when max_i |K_i - K̄_i| is below this (radians).
  double tolerance = 1e-10;
  /// Newton iterations allowed.
  int max_newton_iterations = 60;
  /// Gradient-descent iterations allowed.
  int max_gradient_iterations = 2000000;
  /// Initial gradient-descent step ε in u += ε (K̄ - K) (the papers use ≤ 0.05); halved when
  /// the error grows or a triangle breaks.
  double gradient_step = 0.1;
  /// Sparse factorisation for Newton (automatic: resolve_linear_solver).
  LinearSolver solver = LinearSolver::automatic;
  /// Halvings of a Newton step before the line search gives up.
  int max_step_halvings = 40;
  /// E2: end the run when its first Newton step is short (under 1/64 of the step, lowering the
  /// error by under 2%): a prediction that it fails, for a caller with a staged fall-back
  /// (flow/continuation.h). Otherwise three such steps in a row end it.
  bool give_up_on_short_first_step = false;
  /// When the run from (scheme, radii) does not converge, retry from the next metric of
  /// inversive-distance/min → inversive-distance/mean → circle-packing/mean → combinatorial
  /// (the last always satisfies Thurston's conditions for cones of valence ≥ 4 - 2K̄/π, but is
  /// not conformal to the mesh). The result records the metric that converged and the attempts.
  bool fall_back_to_other_metrics = false;
  /// Optional: shares the symbolic analysis of Newton's factorisation with later flows on the
  /// same mesh and unknowns (flow_by_continuation's stages make one when it is empty).
  std::shared_ptr<FactorizationCache> factorization_cache;
  /// Optional progress report (never called from another thread).
  std::function<void(const FlowProgress&)> progress;
};

/// A Newton iteration whose line search broke triangles (for diagnosis: where the metric runs
/// into the boundary of the admissible radii).
struct BrokenTrial {
  int iteration = 0;  ///< 1-based Newton iteration
  int face = -1;      ///< first face whose triangle inequality failed in that line search
  int trials = 0;     ///< trial steps of that line search that broke some triangle
};

/// At most this many BrokenTrial records are kept per run.
inline constexpr size_t kMaxBrokenFacesRecorded = 64;

/// Where the solve's time went (seconds).
struct FlowTimings {
  double setup = 0;          ///< tables, initial metric, target check
  double evaluation = 0;     ///< lengths, angles, curvature (including line-search trials)
  double assembly = 0;       ///< Hessian values
  double analysis = 0;       ///< symbolic factorisation (once)
  double factorization = 0;  ///< numeric factorisations
  double solve = 0;          ///< triangular solves
  double total = 0;          ///< whole call, from the mesh to the result
};

struct FlowResult {
  FlowStatus status = FlowStatus::stalled;
  /// Empty when converged; otherwise one paragraph naming the worst vertices and what to try.
  std::string message;
  /// The final metric: radii at the end of the flow and the fixed edge quantities.
  CirclePackingMetric metric;
  /// Flow variables (log-radii in E2) and the metric's edge lengths, by index.
  Eigen::VectorXd u;
  EdgeLengths lengths;
  /// Final vertex curvature and target.
  Eigen::VectorXd curvature, target;
  /// Lengths of the mesh were multiplied by this before the flow (1 in E2; in H2/S2 the mesh is
  /// scaled so that its area matches the area Gauss-Bonnet gives the target).
  double length_scale = 1;
  /// max |K - K̄| before the first iteration and after each one.
  std::vector<double> error_history;
  int iterations = 0;
  /// Numeric factorisations of the Hessian (Newton reuses one near the answer).
  int factorizations = 0;
  /// Factorisations and back-substitutions of the run (the last one, in fall-back mode).
  LinearWork linear_work;
  double max_error = 0;
  /// The factorisation actually used (after any fallback).
  LinearSolver solver = LinearSolver::automatic;
  FlowTimings timings;
  /// Newton iterations whose line search broke triangles, with the first face broken.
  std::vector<BrokenTrial> broken_faces;
  /// One line per run that did not converge before the reported one (fall-back mode).
  std::vector<std::string> failed_attempts;
  /// The initial metric the reported run started from, named by the one-cone solvers
  /// (singularity/one_cone.h, e.g. "circle-packing/mean"); empty from flow() itself.
  std::string metric_name;

  bool converged() const { return status == FlowStatus::converged; }
};

/// Runs the flow from the initial metric of the mesh (options.scheme, options.radii).
/// \pre a connected triangle 2-manifold (closed or with boundary) without degenerate faces.
/// \throw InfeasibleTargetError before any work when the target violates Gauss-Bonnet or a cone
///        needs more valence; InvalidInputError for bad sizes or degenerate faces. Failure to
///        converge is a status with a best-effort payload, not an exception.
[[nodiscard]] FlowResult flow(const Mesh& mesh, const Targets& targets,
                              const FlowOptions& options = {});

/// Runs the flow from a given initial metric (its geometry overrides options.geometry).
/// \throw as above.
[[nodiscard]] FlowResult flow(const MeshTables& tables, const CirclePackingMetric& initial,
                              const Targets& targets, const FlowOptions& options = {});

}  // namespace ricci
