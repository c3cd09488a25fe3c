// The papers' baseline: explicit Ricci flow u += ε (K̄ - K) (discrete-surface-ricci-flow §V
// step 3.1), with ε halved whenever a step breaks a triangle or makes the error blow up.
#include "ricci/flow/flow_internal.h"

namespace ricci::detail {

void run_gradient_descent(const FlowRun& run, FlowState& state, FlowResult& result) {
  const FlowOptions& o = run.options;
  const bool euclidean = run.geometry == Geometry::euclidean;
  double epsilon = o.gradient_step;
  double error = max_error(state, run.target);
  double merit = (state.curvature - run.target).norm();
  result.error_history.push_back(error);
  FlowState trial;
  Eigen::VectorXd step;
  while (error >= o.tolerance) {
    if (result.iterations >= o.max_gradient_iterations) {
      result.status = FlowStatus::max_iterations;
      result.message = failure_message(run, state, result.status,
                                       "gradient descent used its " +
                                           std::to_string(o.max_gradient_iterations) + " iterations");
      return;
    }
    step = run.target - state.curvature;
    if (euclidean) step.array() -= step.mean();  // the papers' normalisation Σu = const
    const Stopwatch t0;
    bool accepted = false;
    for (int halving = 0; halving <= o.max_step_halvings; ++halving, epsilon *= 0.5) {
      if (!evaluate_flow_state(run.tables, run.geometry, run.eta, state.u + epsilon * step, trial)) {
        continue;
      }
      // A stable explicit step may raise ‖K - K̄‖ a little; more means ε is too large.
      if ((trial.curvature - run.target).norm() <= 1.01 * merit) {
        accepted = true;
        break;
      }
    }
    result.timings.evaluation += t0.seconds();
    if (!accepted) {
      result.status = FlowStatus::triangle_inequality;
      result.message = failure_message(run, state, result.status,
                                       "every shortened gradient step broke a triangle");
      return;
    }
    std::swap(state, trial);
    merit = (state.curvature - run.target).norm();
    error = max_error(state, run.target);
    ++result.iterations;
    if (result.iterations % 100 == 0) {
      result.error_history.push_back(error);
      if (o.progress) o.progress({result.iterations, error, epsilon, run.start.seconds()});
    }
  }
  result.error_history.push_back(error);
  result.status = FlowStatus::converged;
}

}  // namespace ricci::detail
