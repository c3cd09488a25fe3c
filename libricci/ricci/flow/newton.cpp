// Newton's method on the Ricci energy: H δu = K̄ - K with H = ∂K/∂u, backtracking on the
// curvature residual (the Newton direction decreases ‖K - K̄‖² whether or not H is definite,
// which matters in S2).
#include <cmath>

#include <Eigen/SparseCholesky>

#include "ricci/flow/flow_internal.h"
#include "ricci/flow/hessian.h"
#include "ricci/flow/linear_solver.h"

namespace ricci::detail {

namespace {

// Adds sigma to the diagonal of a lower-triangular CSC matrix (first entry of each column).
void shift_diagonal(Eigen::SparseMatrix<double>& lower, double sigma) {
  for (int j = 0; j < lower.outerSize(); ++j) lower.valuePtr()[lower.outerIndexPtr()[j]] += sigma;
}

double max_abs_diagonal(const Eigen::SparseMatrix<double>& lower) {
  double m = 0;
  for (int j = 0; j < lower.outerSize(); ++j) {
    m = std::max(m, std::abs(lower.valuePtr()[lower.outerIndexPtr()[j]]));
  }
  return m;
}

// Owns the factorisation and its fallbacks: an LLT that fails (the energy is not convex, e.g.
// in S2 or for inversive distances below 1) switches to LDLT for the rest of the run; if that
// fails too, a growing diagonal shift makes the system solvable (a damped Newton step).
class NewtonSystem {
 public:
  // The symbolic analysis comes from `cache` when it has one for this pattern.
  NewtonSystem(LinearSolver kind, const Eigen::SparseMatrix<double>& pattern,
               FactorizationCache* cache, FlowTimings& timings, LinearWork& work)
      : timings_(timings), work_(work) {
    FactorizationCache own;
    factorization_ = (cache ? *cache : own).get(kind, pattern, timings_.analysis);
  }

  LinearSolver kind() const { return factorization_->kind(); }

  int factorizations() const { return factorizations_; }

  // Near the answer H changes little between iterations: iterate x += F⁻¹(rhs - H x) with the
  // previous factorisation F, a stationary iteration that converges to the exact Newton step at
  // rate ‖I - F⁻¹H‖ = O(|δu|). Returns false (and the caller refactorises) if it is not fast.
  bool solve_reusing(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& rhs,
                     Eigen::VectorXd& x) {
    if (!factored_) return false;
    const Stopwatch t0;
    const LinearWorkMeter meter(*factorization_, work_);
    const bool ok = solve_with_nearby_factorization(*factorization_, H, rhs, x);
    timings_.solve += t0.seconds();
    return ok;
  }

  // Refinement steps after each fresh factorisation's solve (2 near the answer, 0 far from it).
  void set_refinements(int refinements) { refinements_ = refinements; }

  // Solves H x = rhs; returns false if no factorisation gave a finite solution.
  bool solve(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
    if (try_solve(H, rhs, x)) return true;
    if (kind() != LinearSolver::eigen_ldlt) {
      factorization_ = std::make_shared<SymmetricFactorization>(LinearSolver::eigen_ldlt);
      const Stopwatch t0;
      factorization_->analyze(H);
      timings_.analysis += t0.seconds();
      if (try_solve(H, rhs, x)) return true;
    }
    Eigen::SparseMatrix<double> shifted = H;
    const double scale = std::max(max_abs_diagonal(H), 1e-300);
    for (double sigma = 1e-10 * scale; sigma < 10 * scale; sigma *= 100) {
      shifted = H;
      shift_diagonal(shifted, sigma);
      if (try_solve(shifted, rhs, x)) return true;
    }
    return false;
  }

 private:
  bool try_solve(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& rhs,
                 Eigen::VectorXd& x) {
    const LinearWorkMeter meter(*factorization_, work_);
    Stopwatch t0;
    const bool ok = factorization_->factorize(H);
    timings_.factorization += t0.seconds();
    ++factorizations_;
    factored_ = ok;
    if (!ok) return false;
    t0.restart();
    x = factorization_->solve(rhs);
    // Iterative refinement: H's condition number grows with the mesh (it is a Laplacian), and
    // on a million faces one triangular solve alone leaves the curvature at ~1e-10. Far from the
    // answer a step accurate to ~1e-8 is as good (Newton's error there is the model's, not the
    // solve's), and each refinement costs two triangular solves and a product.
    for (int refinement = 0; refinement < refinements_ && x.allFinite(); ++refinement) {
      const Eigen::VectorXd residual = rhs - H.selfadjointView<Eigen::Lower>() * x;
      if (residual.norm() <= 1e-14 * rhs.norm()) break;
      x += factorization_->solve(residual);
    }
    timings_.solve += t0.seconds();
    return x.allFinite();
  }

  std::shared_ptr<SymmetricFactorization> factorization_;
  FlowTimings& timings_;
  LinearWork& work_;
  bool factored_ = false;  // the factorisation holds a (possibly older) Hessian
  int refinements_ = 2;
  int factorizations_ = 0;
};

// Levenberg-Marquardt step for ‖K - K̄‖² in S2: (H² + μI) δ = H (K̄ - K) with μ = ‖K - K̄‖ times
// the Hessian's scale. Circle packings on the sphere are unique only up to Möbius maps, so H is
// singular at the answer (and indefinite: growing all radii lowers every K); μ ∝ ‖K - K̄‖ damps
// the free directions yet keeps fast local convergence on such non-isolated solutions
// (Yamashita-Fukushima). λ adapts: smaller after full steps, larger after cut ones.
bool levenberg_marquardt_step(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& rhs,
                              double lambda, FlowTimings& timings, Eigen::VectorXd& step) {
  Stopwatch t0;
  const Eigen::SparseMatrix<double> H = lower.selfadjointView<Eigen::Lower>();
  const double mu = lambda * rhs.norm() * std::max(max_abs_diagonal(lower), 1e-300);
  Eigen::SparseMatrix<double> normal = (H * H).pruned();
  for (int j = 0; j < normal.outerSize(); ++j) normal.coeffRef(j, j) += mu;
  const Eigen::SparseMatrix<double> normal_lower = normal.triangularView<Eigen::Lower>();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver(normal_lower);
  timings.factorization += t0.seconds();
  if (solver.info() != Eigen::Success) return false;
  t0.restart();
  step = solver.solve(H * rhs);
  timings.solve += t0.seconds();
  return step.allFinite();
}

struct LineSearch {
  bool accepted = false;
  double step = 1.0;  // fraction of the Newton step taken
  int broken = 0;     // trials that broke a triangle
  int first_broken_face = -1;  // the face that broke the first such trial
};

// Backtracking: halve the step while a triangle breaks or ½‖K - K̄‖² does not fall by Armijo's
// rule (its slope along the Newton step is -‖K - K̄‖²; the Levenberg-Marquardt step of S2 only
// promises some decrease). When the Ricci energy E (∇E = K - K̄) is convex, the energy decides
// instead: a trial is taken where E's slope along the step, φ'(t) = δu·(K - K̄), is still <= 0
// (E fell all the way there; the first such halving is within a factor 2 of the line minimum),
// or where the residual falls and φ'(t) is small next to |φ'(0)| (the quadratic phase, where
// φ'(1) = O(|δu|³)). The residual alone accepts overshoots: at a 6π cone on 160k+ faces the
// first full step (δu up to 33 at the cone) lowers ‖K - K̄‖ while it blows up radii elsewhere
// (K = 5.3 at vertices whose target is 0), and the next Hessian is singular. On success
// `trial` holds the new state.
LineSearch line_search(const FlowRun& run, const FlowState& state, const Eigen::VectorXd& step,
                       double merit, bool spherical, bool convex, FlowState& trial) {
  LineSearch search;
  const double initial_slope = convex ? step.dot(state.curvature - run.target) : 0.0;
  for (int halving = 0; halving <= run.options.max_step_halvings; ++halving, search.step *= 0.5) {
    if (!evaluate_flow_state(run.tables, run.geometry, run.eta, state.u + search.step * step, trial)) {
      ++search.broken;
      if (search.first_broken_face < 0) search.first_broken_face = trial.bad_face;
      continue;
    }
    const double trial_merit = (trial.curvature - run.target).squaredNorm();
    const double wanted = spherical ? merit : (1.0 - 1e-4 * search.step) * merit;
    bool accept = trial_merit <= wanted;
    if (convex) {
      // The energy's slope along the step, from φ'(0) = -δu·H·δu < 0; φ' increases (convexity).
      const double slope = step.dot(trial.curvature - run.target);
      accept = slope <= 0.0 || (accept && slope <= 0.1 * std::abs(initial_slope));
    }
    if (accept || max_error(trial, run.target) < run.options.tolerance) {
      search.accepted = true;
      return search;
    }
  }
  return search;
}

// Thurston's weights (η = cos Φ, Φ ∈ [0, π/2]) make the E2 energy convex in u (Chow-Luo);
// inversive distances outside [0, 1] need not.
bool convex_energy(const FlowRun& run) {
  return run.geometry == Geometry::euclidean && run.eta.size() > 0 && run.eta.minCoeff() >= 0.0 &&
         run.eta.maxCoeff() <= 1.0;
}

// One more Newton step after convergence when the error is still above 1e-12 (the tolerance,
// 1e-10, can stop a step short of the rounding floor), kept only if it lowers the error: a
// layout's closure error is the curvature error times the size of the loops it closes, up to
// 1e3 times an edge. The step reuses the factorisation (no new numeric factorisation). A loose
// tolerance (a continuation's intermediate stage, a ranking flow) asks for no such step.
void polish(const FlowRun& run, HessianAssembler& assembler, NewtonSystem& system, FlowState& state,
            FlowResult& result) {
  const MeshTables& t = run.tables;
  const double error = max_error(state, run.target);
  constexpr double kLooseTolerance = 1e-8;
  if (run.geometry != Geometry::euclidean || result.iterations == 0 || error < 1e-12 ||
      run.options.tolerance > kLooseTolerance) {
    return;
  }
  Stopwatch t0;
  const Eigen::SparseMatrix<double>& H = assembler.assemble(run.geometry, run.eta, state);
  result.timings.assembly += t0.seconds();
  const int n = assembler.num_unknowns();
  Eigen::VectorXd rhs(n), reduced(n), step(t.num_vertices());
  for (int v = 0; v < t.num_vertices(); ++v) {
    if (assembler.unknown(v) >= 0) rhs[assembler.unknown(v)] = run.target[v] - state.curvature[v];
  }
  if (!system.solve_reusing(H, rhs, reduced)) return;
  for (int v = 0; v < t.num_vertices(); ++v) {
    step[v] = assembler.unknown(v) >= 0 ? reduced[assembler.unknown(v)] : 0.0;
  }
  step.array() -= step.mean();
  t0.restart();
  FlowState trial;
  const bool valid = evaluate_flow_state(t, run.geometry, run.eta, state.u + step, trial);
  result.timings.evaluation += t0.seconds();
  if (!valid || !(max_error(trial, run.target) < error)) return;
  std::swap(state, trial);
  ++result.iterations;
  result.error_history.push_back(max_error(state, run.target));
  if (run.options.progress) {
    run.options.progress(
        {result.iterations, result.error_history.back(), 1.0, run.start.seconds()});
  }
}

}  // namespace

void run_newton(const FlowRun& run, FlowState& state, FlowResult& result) {
  const MeshTables& t = run.tables;
  const FlowOptions& o = run.options;
  const bool euclidean = run.geometry == Geometry::euclidean;
  // E2 gauge: H·1 = 0 (scaling all radii keeps every angle), so pin vertex 0 and solve the
  // reduced system; its dropped equation holds because Σ(K̄ - K) = 0 by Gauss-Bonnet.
  HessianAssembler assembler(t, euclidean ? 0 : -1);
  NewtonSystem system(o.solver, assembler.matrix(), o.factorization_cache.get(), result.timings,
                      result.linear_work);
  const int n = assembler.num_unknowns();

  FlowState trial;
  Eigen::VectorXd rhs(n), reduced_step(n), step(t.num_vertices());
  double error = max_error(state, run.target);
  double merit = (state.curvature - run.target).squaredNorm();
  int crawling = 0;  // consecutive iterations whose step was cut hard by broken triangles
  int recent_broken = 0;  // iterations with broken trial triangles in the last window
  int stagnant = 0;       // consecutive short steps that barely lowered the error
  int stagnant_broken = 0;  // ... of which broke triangles at longer trial steps
  double lambda = 1.0;  // Levenberg-Marquardt damping factor (S2 only)
  const bool convex = convex_energy(run);
  bool last_step_full = false;
  result.error_history.push_back(error);
  while (error >= o.tolerance) {
    if (result.iterations >= o.max_newton_iterations) {
      result.status = FlowStatus::max_iterations;
      result.message = failure_message(run, state, result.status,
                                       "Newton used its " + std::to_string(o.max_newton_iterations) +
                                           " iterations");
      return;
    }
    Stopwatch t0;
    const Eigen::SparseMatrix<double>& H = assembler.assemble(run.geometry, run.eta, state);
    result.timings.assembly += t0.seconds();
    for (int v = 0; v < t.num_vertices(); ++v) {
      if (assembler.unknown(v) >= 0) rhs[assembler.unknown(v)] = run.target[v] - state.curvature[v];
    }
    const bool spherical = run.geometry == Geometry::spherical;
    // Reuse the last factorisation once Newton is in its fast phase (full steps, small error).
    const bool reuse = last_step_full && error < 1e-2;
    system.set_refinements(error < 1e-3 ? 2 : 0);
    if (spherical ? !levenberg_marquardt_step(H, rhs, lambda, result.timings, reduced_step)
                  : !((reuse && system.solve_reusing(H, rhs, reduced_step)) ||
                      system.solve(H, rhs, reduced_step))) {
      result.status = FlowStatus::stalled;
      result.message = failure_message(run, state, result.status,
                                       "no factorisation of the Hessian gave a finite step");
      return;
    }
    result.solver = spherical ? LinearSolver::eigen_ldlt : system.kind();
    for (int v = 0; v < t.num_vertices(); ++v) {
      step[v] = assembler.unknown(v) >= 0 ? reduced_step[assembler.unknown(v)] : 0.0;
    }
    // In E2 a constant shift of u is a global scale: keep Σu fixed as the papers normalise.
    if (euclidean) step.array() -= step.mean();

    t0.restart();
    const LineSearch search = line_search(run, state, step, merit, spherical, convex, trial);
    if (search.first_broken_face >= 0 && result.broken_faces.size() < kMaxBrokenFacesRecorded) {
      result.broken_faces.push_back({result.iterations + 1, search.first_broken_face, search.broken});
    }
    result.timings.evaluation += t0.seconds();
    const double t_step = search.step;
    const int broken = search.broken;
    if (!search.accepted) {
      const bool triangles = broken > o.max_step_halvings / 2;
      result.status = triangles ? FlowStatus::triangle_inequality : FlowStatus::stalled;
      result.message = failure_message(
          run, state, result.status,
          triangles ? std::string("every shortened Newton step broke a triangle")
                    : "the line search found no decrease of the curvature error (rounding floor "
                      "or a non-convex energy)");
      return;
    }
    last_step_full = t_step == 1.0;
    result.factorizations = system.factorizations();
    lambda = t_step == 1.0 ? std::max(lambda * 0.1, 1e-10) : std::min(lambda * 4.0, 1e4);
    std::swap(state, trial);
    merit = (state.curvature - run.target).squaredNorm();
    const double previous_error = error;
    error = max_error(state, run.target);
    ++result.iterations;
    result.error_history.push_back(error);
    if (o.progress) o.progress({result.iterations, error, t_step, run.start.seconds()});
    crawling = (broken > 0 && t_step < 1e-3) ? crawling + 1 : 0;
    recent_broken += broken > 0 ? 1 : 0;
    // Newton converges quadratically once it is near the answer; ten iterations without halving
    // the error mean it is creeping along the boundary of the admissible metrics.
    constexpr int kWindow = 10;
    if (result.iterations % kWindow == 0) {
      const double before = result.error_history[result.error_history.size() - 1 - kWindow];
      if (error > 0.5 * before) {
        result.status = recent_broken > 0 ? FlowStatus::triangle_inequality : FlowStatus::stalled;
        result.message = failure_message(
            run, state, result.status,
            "the error fell from " + std::to_string(before) + " to only " + std::to_string(error) +
                " in " + std::to_string(kWindow) + " iterations" +
                (recent_broken > 0 ? " while steps kept breaking triangles" : ""));
        return;
      }
      recent_broken = 0;
    }
    // Short steps that gain under 2% each: the radii are heading to the boundary of the metric
    // space (no solution with these edge quantities, e.g. Thurston's angles at a 10pi cone).
    // Waiting for the ten-iteration window costs seconds on 100k faces before the next metric.
    const bool short_step = t_step < 1.0 / 64 && error > 0.98 * previous_error;
    stagnant = short_step ? stagnant + 1 : 0;
    stagnant_broken = short_step ? stagnant_broken + (broken > 0 ? 1 : 0) : 0;
    if (euclidean && short_step && o.give_up_on_short_first_step && result.iterations == 1) {
      result.status = broken > 0 ? FlowStatus::triangle_inequality : FlowStatus::stalled;
      result.message = failure_message(run, state, result.status,
                                       "the first Newton step was cut below 1/64 and lowered the error by "
                                       "less than 2% (predicted to fail in one go)");
      return;
    }
    if (euclidean && stagnant >= 3) {
      result.status = stagnant_broken > 0 ? FlowStatus::triangle_inequality : FlowStatus::stalled;
      result.message = failure_message(run, state, result.status,
                                       std::string("three short Newton steps in a row lowered the error by "
                                                   "less than 2% each") +
                                           (stagnant_broken > 0 ? " while longer ones broke triangles"
                                                                : " (no solution for these edge quantities?)"));
      return;
    }
    if (crawling >= 8) {
      result.status = FlowStatus::triangle_inequality;
      result.message = failure_message(run, state, result.status,
                                       "Newton steps keep breaking triangles and shrink below 1e-3");
      return;
    }
  }
  result.status = FlowStatus::converged;
  polish(run, assembler, system, state, result);
}

}  // namespace ricci::detail
