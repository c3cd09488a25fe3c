#include "ricci/intrinsic/conformal_flow.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <queue>
#include <sstream>
#include <vector>

#include <Eigen/SparseCore>

#include "ricci/flow/hessian.h"
#include "ricci/flow/linear_solver.h"
#include "ricci/mesh/errors.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/util/memory.h"
#include "ricci/util/stopwatch.h"

namespace ricci {
namespace {

std::string format(double x) {
  std::ostringstream out;
  out.precision(12);
  out << x;
  return out.str();
}

void check_intrinsic_target(const IntrinsicTriangulation& tri, const Eigen::VectorXd& target) {
  if (target.size() != tri.vertex_count) {
    throw InvalidInputError("target curvature has " + std::to_string(target.size()) +
                            " entries for " + std::to_string(tri.vertex_count) + " vertices");
  }
  for (int v = 0; v < tri.vertex_count; ++v) {
    if (!std::isfinite(target[v]) || !(target[v] < 2.0 * M_PI)) {
      throw InfeasibleTargetError("target curvature " + format(target[v]) + " at vertex " +
                                  std::to_string(v) + " asks for a cone angle <= 0");
    }
  }
  const double sum = target.sum(), expected = 2.0 * M_PI * euler_characteristic(tri);
  if (std::abs(sum - expected) > 1e-8 * (1.0 + target.cwiseAbs().sum())) {
    throw InfeasibleTargetError("target violates Gauss-Bonnet: sum of target curvatures " +
                                format(sum) + " != 2 pi chi = " + format(expected) +
                                " (chi = " + std::to_string(euler_characteristic(tri)) + ")");
  }
}

// The vertex pinned at u = 0 (the Laplacian's kernel): the one farthest in hops from the vertex
// of largest |target|, where the scale factors stay moderate.
int pinned_vertex(const IntrinsicTriangulation& tri, const Eigen::VectorXd& target) {
  Eigen::Index start = 0;
  target.cwiseAbs().maxCoeff(&start);
  std::vector<std::vector<int>> neighbours(static_cast<size_t>(tri.vertex_count));
  for (size_t h = 0; h < tri.tail.size(); ++h) {
    neighbours[static_cast<size_t>(tri.tail[h])].push_back(tri.head(static_cast<int>(h)));
  }
  std::vector<char> seen(static_cast<size_t>(tri.vertex_count), 0);
  std::queue<int> queue;
  queue.push(static_cast<int>(start));
  seen[static_cast<size_t>(start)] = 1;
  int last = static_cast<int>(start);
  while (!queue.empty()) {
    last = queue.front();
    queue.pop();
    for (int w : neighbours[static_cast<size_t>(last)]) {
      if (!seen[static_cast<size_t>(w)]) {
        seen[static_cast<size_t>(w)] = 1;
        queue.push(w);
      }
    }
  }
  return last;
}

// State of the flow at one u: Delaunay triangulation, cotangents and curvature (the corner
// angles only while the curvature is summed: the accepted and the trial evaluation live
// together, 38 MB of angles each at 1.6M faces).
struct Evaluation {
  Eigen::MatrixX3d cotangents;
  Eigen::VectorXd curvature;
};

// Flips (when `flip`) are counted in and appended to result's flips and flip_log.
bool evaluate(IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
              const IntrinsicFlowOptions& options, bool flip, Evaluation& eval,
              IntrinsicFlowResult& result) {
  if (flip) {
    const DelaunayFlipResult flipped =
        flip_to_delaunay(tri, u, options.delaunay_margin, kMaxFlipsPerEdge, &result.flip_log);
    result.flips += flipped.flips;
    if (!flipped.delaunay) return false;
  }
  Eigen::MatrixX3d angles;
  if (!intrinsic_corner_angles(tri, u, angles, &eval.cotangents)) return false;
  eval.curvature = intrinsic_curvature(tri, angles);
  return eval.curvature.allFinite();
}

// Lower triangle of the cotangent Laplacian without the pinned vertex's row and column.
Eigen::SparseMatrix<double> reduced_laplacian(const IntrinsicTriangulation& tri,
                                              const Eigen::MatrixX3d& cot, int pinned) {
  Eigen::MatrixX2i ends(tri.edge_count(), 2);
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(tri.edge_count());
  for (int e = 0; e < tri.edge_count(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    ends(e, 0) = tri.tail[static_cast<size_t>(h)];
    ends(e, 1) = tri.head(h);
  }
  for (int f = 0; f < tri.face_count(); ++f) {
    // The corner at tail(3f + k) faces the halfedge 3f + (k + 1) % 3.
    for (int k = 0; k < 3; ++k) {
      weights[tri.edge[static_cast<size_t>(3 * f + (k + 1) % 3)]] += 0.5 * cot(f, k);
    }
  }
  return reduced_graph_laplacian(ends, weights, tri.vertex_count, pinned);
}

std::string failure_message(const IntrinsicFlowResult& result, const std::string& reason) {
  Eigen::Index worst = 0;
  (result.curvature - result.target).cwiseAbs().maxCoeff(&worst);
  return "intrinsic conformal flow " + to_string(result.status) + " after " +
         std::to_string(result.iterations) + " Newton iterations (" + reason +
         "): max |K - K̄| = " + format(result.max_error) + " at vertex " + std::to_string(worst) +
         "; try a larger --max-iterations or --tolerance";
}

// One Newton solve towards `target` from result.u (with `eval` its evaluation), until max |K - K̄|
// is below `tolerance` or `max_iterations` pass. Updates result's u, flips, iterations, timings,
// max_error and history. Returns the status and sets `reason` when it is not converged.
FlowStatus newton(IntrinsicFlowResult& result, Evaluation& eval, const Eigen::VectorXd& target,
                  double tolerance, int max_iterations, int pinned,
                  const IntrinsicFlowOptions& options, const Stopwatch& start,
                  std::string& reason) {
  IntrinsicTriangulation& tri = result.triangulation;
  const int n = tri.vertex_count;
  Eigen::VectorXd gradient = eval.curvature - target;
  double error = gradient.cwiseAbs().maxCoeff();
  Stopwatch clock;
  double best = error;
  int since_best = 0;
  FactorizationCache cache;  // flips change the pattern; steps without flips keep the analysis
  // The last factorised Laplacian: near the answer Newton takes full steps, the next Laplacian
  // differs from it by little (and a few flips), and refinement steps with it
  // (solve_with_nearby_factorization) spare the analysis and the factorisation.
  std::shared_ptr<const SymmetricFactorization>& factored_last = result.laplacian_factorization;
  result.pinned_vertex = pinned;
  bool last_step_full = false;
  bool factor_stale = false, factored_frozen = false;
  int flips_at_analysis = -1;  // result.flips when the cache last analysed a pattern
  int flips_at_factor = -1;    // result.flips when factored_last was made
  for (int iteration = 0; error > tolerance; ++iteration) {
    if (iteration >= max_iterations) {
      reason = "iteration budget spent";
      return FlowStatus::max_iterations;
    }
    const int plateau = error < options.floor_below ? options.floor_plateau_iterations
                                                    : options.plateau_iterations;
    if (error < options.freeze_connectivity_below && since_best >= plateau) {
      reason = "rounding plateau: no progress in " + std::to_string(since_best) + " iterations";
      return FlowStatus::stalled;
    }
    clock.restart();
    const Eigen::SparseMatrix<double> lower = reduced_laplacian(tri, eval.cotangents, pinned);
    result.timings.assembly += clock.seconds();
    Eigen::VectorXd rhs(n - 1);
    for (int v = 0; v < n; ++v) {
      if (v != pinned) rhs[reduced_index(v, pinned)] = -gradient[v];
    }
    Eigen::VectorXd reduced;
    clock.restart();
    const bool frozen = error < options.freeze_connectivity_below;
    // Chord steps: the last factorisation preconditions conjugate gradients on this step's
    // Laplacian, to a forcing term loose far from the answer (Eisenstat-Walker), tight near it.
    // It is refactorised when a solve on it got slow (stale) or failed, and once when the
    // connectivity freezes: that factor then serves every remaining step and the polish.
    const bool near_regime = last_step_full && error < options.nearby_factorization_below;
    // A factorisation made a few flips before the freeze serves as the frozen one: the flips
    // were its last, and it is as near the answer as a new one would be.
    if (frozen && !factored_frozen && factored_last && !factor_stale &&
        result.flips - flips_at_factor <= options.frozen_factor_flips * tri.edge_count()) {
      factored_frozen = true;
    }
    const bool try_nearby = factored_last && !factor_stale && !(frozen && !factored_frozen) &&
                            (near_regime || options.chord_forcing_cap > 0);
    // An inexact Newton step: a relative residual eta adds eta * error to the next error,
    // below Newton's own error^2 while eta <= error (Dembo-Eisenstat-Steihaug forcing term).
    const double forcing = near_regime ? std::clamp(1e-2 * error, 1e-12, 1e-6)
                                       : std::clamp(1e-2 * error, 1e-12,
                                                    std::max(options.chord_forcing_cap, 1e-12));
    bool reused = false;
    if (try_nearby) {
      const LinearWorkMeter meter(*factored_last, result.linear_work);
      const int before = factored_last->work().back_substitutions;
      reused = solve_by_preconditioned_cg(*factored_last, lower, rhs, reduced, forcing,
                                          options.chord_max_steps);
      factor_stale = factored_last->work().back_substitutions - before >= options.chord_stale_steps;
    }
    result.timings.solve += clock.seconds();
    if (!reused) {
      factored_last.reset();  // at most one factor alive besides the cache's
      // the line search's freed evaluations, before the new factor
      release_free_memory(static_cast<std::size_t>(n));
      // The last analysis' ordering serves a pattern few flips away (ordering_reuse_flips).
      const bool near_pattern =
          flips_at_analysis >= 0 &&
          result.flips - flips_at_analysis <= options.ordering_reuse_flips * tri.edge_count();
      const int analyses = cache.analyses();
      const std::shared_ptr<SymmetricFactorization> factorization =
          cache.get(result.solver, lower, result.timings.analysis,
                    near_pattern ? OrderingReuse::offer : OrderingReuse::skip);
      if (cache.analyses() != analyses) flips_at_analysis = result.flips;
      result.orderings_reused = cache.orderings_reused();
      const LinearWorkMeter meter(*factorization, result.linear_work);
      clock.restart();
      const bool factored = factorization->factorize(lower);
      result.timings.factorization += clock.seconds();
      ++result.factorizations;
      if (!factored) {
        reason = "the cotangent Laplacian did not factorise";
        return FlowStatus::stalled;
      }
      factored_last = factorization;
      factor_stale = false;
      factored_frozen = frozen;
      flips_at_factor = result.flips;
      clock.restart();
      reduced = factorization->solve(rhs);
      result.timings.solve += clock.seconds();
    }
    Eigen::VectorXd direction = Eigen::VectorXd::Zero(n);
    for (int v = 0; v < n; ++v) {
      if (v != pinned) direction[v] = reduced[reduced_index(v, pinned)];
    }
    if (!direction.allFinite()) {
      reason = "the Newton step is not finite";
      return FlowStatus::stalled;
    }
    // Along the line the energy is convex with slope phi'(t) = (K - K̄) . d, phi'(0) < 0. A step
    // is taken when phi'(t) <= slope_fraction |phi'(0)| (by convexity this also bounds how far
    // past the line's minimum it lands); otherwise the step shrinks to the secant estimate of
    // the minimum, by min_shrink-0.5.
    // Near the answer, where the slopes are rounding noise, a step lowering max |K - K̄| is taken.
    const double slope0 = gradient.dot(direction);
    const bool flip = error >= options.freeze_connectivity_below;
    clock.restart();
    double step = 1.0;
    bool accepted = false;
    for (int trial_count = 0; trial_count <= options.max_step_halvings; ++trial_count) {
      const Eigen::VectorXd trial = result.u + step * direction;
      ++result.line_search_trials;
      Evaluation trial_eval;
      if (!evaluate(tri, trial, options, flip, trial_eval, result)) {
        step *= 0.5;
        continue;
      }
      const Eigen::VectorXd trial_gradient = trial_eval.curvature - target;
      const double slope = trial_gradient.dot(direction);
      const double trial_error = trial_gradient.cwiseAbs().maxCoeff();
      if (slope <= -options.slope_fraction * slope0 || (error < 1e-6 && trial_error < error)) {
        result.u = trial;
        eval = std::move(trial_eval);
        gradient = trial_gradient;
        error = trial_error;
        accepted = true;
        break;
      }
      const double secant = slope0 < 0 && slope > slope0 ? -slope0 / (slope - slope0) : 0.5;
      step *= std::clamp(secant, options.min_shrink, 0.5);
    }
    result.timings.evaluation += clock.seconds();
    if (!accepted) {
      Evaluation back;  // leave the triangulation Delaunay at the last accepted u
      evaluate(tri, result.u, options, flip, back, result);
      reason = "the line search found no decrease";
      return FlowStatus::stalled;
    }
    ++result.iterations;
    last_step_full = step == 1.0;
    if (error < 0.5 * best) {
      best = error;
      since_best = 0;
    } else {
      ++since_best;
    }
    result.max_error = (eval.curvature - result.target).cwiseAbs().maxCoeff();
    result.error_history.push_back(result.max_error);
    if (options.progress)
      options.progress({result.iterations, result.max_error, step, start.seconds()});
  }
  return FlowStatus::converged;
}

}  // namespace

IntrinsicFlowResult intrinsic_conformal_flow(const Mesh& mesh, const Targets& targets,
                                             const IntrinsicFlowOptions& options) {
  return intrinsic_conformal_flow(make_intrinsic_triangulation(mesh, mesh_edge_lengths(mesh)),
                                  targets.curvature, options);
}

namespace {

// The flow's starting point: u = 0 (flipped to Delaunay there), or the warm start when given
// and its max |K - K̄| is below u = 0's, measured on the given triangulation (flips keep the
// angle sums but on degenerate triangles; sparing the flips to u = 0's Delaunay
// triangulation). Sets result.u, eval, error history and warm-start figures.
void start(IntrinsicFlowResult& result, const Eigen::VectorXd* warm_u, int pinned,
           const IntrinsicFlowOptions& options, Evaluation& eval) {
  IntrinsicTriangulation& tri = result.triangulation;
  const int n = tri.vertex_count;
  result.u = Eigen::VectorXd::Zero(n);
  if (warm_u != nullptr) {
    {
      Evaluation cold;  // (freed before the warm start's: 77 MB at 1.6M faces)
      if (!evaluate(tri, result.u, options, false, cold, result)) {
        throw InvalidInputError(
            "intrinsic conformal flow: the input's lengths break a triangle inequality");
      }
      result.cold_start_error = (cold.curvature - result.target).cwiseAbs().maxCoeff();
    }
    const Eigen::VectorXd u = warm_u->array() - (*warm_u)[pinned];
    result.warm_start = WarmStart::rejected;
    if (u.allFinite() && evaluate(tri, u, options, true, eval, result)) {
      result.warm_start_error = (eval.curvature - result.target).cwiseAbs().maxCoeff();
      if (result.warm_start_error < result.cold_start_error) {
        result.u = u;
        result.warm_start = WarmStart::taken;
      }
    }
  }
  // Intrinsic flips keep the metric at u = 0: the triangulation reached at a rejected warm
  // start serves as well as the input's.
  if (result.warm_start != WarmStart::taken &&
      !evaluate(tri, result.u, options, true, eval, result)) {
    throw InvalidInputError(
        "intrinsic conformal flow: the input's lengths break a triangle inequality");
  }
  result.max_error = (eval.curvature - result.target).cwiseAbs().maxCoeff();
  result.error_history.push_back(result.max_error);
}

IntrinsicFlowResult run_flow(IntrinsicTriangulation initial, const Eigen::VectorXd& target,
                             const Eigen::VectorXd* warm_u, const IntrinsicFlowOptions& options) {
  const Stopwatch clock;
  check_intrinsic_target(initial, target);
  if (warm_u != nullptr && warm_u->size() != initial.vertex_count) {
    throw InvalidInputError("warm start has " + std::to_string(warm_u->size()) +
                            " entries for " + std::to_string(initial.vertex_count) + " vertices");
  }
  IntrinsicFlowResult result;
  result.triangulation = std::move(initial);
  result.target = target;
  const int pinned = pinned_vertex(result.triangulation, target);
  result.solver = resolve_linear_solver(options.solver, result.triangulation.vertex_count - 1);
  Evaluation eval;
  start(result, warm_u, pinned, options, eval);
  result.timings.setup = clock.seconds();
  std::string reason;
  FlowStatus status = newton(result, eval, target, options.tolerance, options.max_iterations,
                             pinned, options, clock, reason);
  if (result.warm_start == WarmStart::taken && status != FlowStatus::converged &&
      result.max_error >= options.freeze_connectivity_below) {
    // The warm start led Newton astray: again from u = 0, on the triangulation reached.
    result.warm_start = WarmStart::abandoned;
    result.laplacian_factorization.reset();
    start(result, nullptr, pinned, options, eval);
    status = newton(result, eval, target, options.tolerance,
                    std::max(options.max_iterations - result.iterations, 0), pinned, options,
                    clock, reason);
  }
  result.curvature = eval.curvature;
  result.max_error = (eval.curvature - target).cwiseAbs().maxCoeff();
  result.status = result.max_error <= options.tolerance ? FlowStatus::converged : status;
  if (!result.converged()) result.message = failure_message(result, reason);
  result.timings.total = clock.seconds();
  return result;
}

}  // namespace

IntrinsicFlowResult intrinsic_conformal_flow(IntrinsicTriangulation initial,
                                             const Eigen::VectorXd& target,
                                             const IntrinsicFlowOptions& options) {
  return run_flow(std::move(initial), target, nullptr, options);
}

IntrinsicFlowResult intrinsic_conformal_flow(IntrinsicTriangulation initial,
                                             const Eigen::VectorXd& target,
                                             const Eigen::VectorXd& warm_u,
                                             const IntrinsicFlowOptions& options) {
  return run_flow(std::move(initial), target, &warm_u, options);
}

std::string to_string(WarmStart warm) {
  switch (warm) {
    case WarmStart::taken: return "taken";
    case WarmStart::rejected: return "rejected";
    case WarmStart::abandoned: return "abandoned";
    case WarmStart::none: break;
  }
  return "none";
}

FlowResult to_flow_result(const IntrinsicFlowResult& r) {
  FlowResult flow;
  flow.status = r.status;
  flow.message = r.message;
  flow.u = r.u;
  flow.curvature = r.curvature;
  flow.target = r.target;
  flow.error_history = r.error_history;
  flow.iterations = r.iterations;
  flow.factorizations = r.factorizations;
  flow.linear_work = r.linear_work;
  flow.max_error = r.max_error;
  flow.solver = r.solver;
  flow.timings = r.timings;
  return flow;
}

}  // namespace ricci
