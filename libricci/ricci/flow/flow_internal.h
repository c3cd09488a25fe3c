#pragma once
// Shared pieces of the two flow methods (newton.cpp, gradient_descent.cpp). Not installed API.
#include <string>

#include "ricci/flow/flow.h"
#include "ricci/flow/flow_state.h"
#include "ricci/util/stopwatch.h"

namespace ricci::detail {

/// Inputs of one run, fixed for its duration.
struct FlowRun {
  const MeshTables& tables;
  Geometry geometry;
  const Eigen::VectorXd& eta;
  const Eigen::VectorXd& target;
  const FlowOptions& options;
  const Stopwatch& start;  ///< started with the run
};

/// max_i |K_i - K̄_i|.
inline double max_error(const FlowState& s, const Eigen::VectorXd& target) {
  return (s.curvature - target).cwiseAbs().maxCoeff();
}

/// Explains a failed run: the worst vertices (index, K, K̄) and what to try.
std::string failure_message(const FlowRun& run, const FlowState& state, FlowStatus status,
                            const std::string& reason);

/// Newton's method with backtracking from `state` (valid). Fills the result's status,
/// iterations, history and timings; leaves the final state in `state`.
void run_newton(const FlowRun& run, FlowState& state, FlowResult& result);

/// The papers' gradient descent u += ε (K̄ - K), as a baseline.
void run_gradient_descent(const FlowRun& run, FlowState& state, FlowResult& result);

}  // namespace ricci::detail
