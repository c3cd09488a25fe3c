#include "ricci/flow/continuation.h"

#include <algorithm>
#include <memory>
#include <string>

#include "ricci/metric/curvature.h"

namespace ricci {
namespace {

void add_timings(FlowTimings& sum, const FlowTimings& stage) {
  sum.setup += stage.setup;
  sum.evaluation += stage.evaluation;
  sum.assembly += stage.assembly;
  sum.analysis += stage.analysis;
  sum.factorization += stage.factorization;
  sum.solve += stage.solve;
  sum.total += stage.total;
}

}  // namespace

FlowResult flow_by_continuation(const MeshTables& tables, const CirclePackingMetric& initial, const Targets& targets,
                                const FlowOptions& options, const ContinuationOptions& continuation) {
  const Eigen::VectorXd start_curvature =
      vertex_curvature(tables, circle_packing_lengths(tables, initial), initial.geometry);
  const int stages = std::max(1, continuation.stages);
  CirclePackingMetric metric = initial;
  FlowResult total;
  FlowOptions shared = options;
  if (!shared.factorization_cache) shared.factorization_cache = std::make_shared<FactorizationCache>();
  for (int stage = 1; stage <= stages; ++stage) {
    const double s = static_cast<double>(stage) / stages;
    Targets target{(1.0 - s) * start_curvature + s * targets.curvature};
    FlowOptions stage_options = shared;
    if (stage < stages) stage_options.tolerance = std::max(options.tolerance, continuation.stage_tolerance);
    // flow() checks a target against the valence bound of its scheme (targets.h), a sufficient
    // condition for the final cone; the stages between a realised curvature and a checked target
    // can fail that bound at low-valence vertices whose initial curvature is already negative,
    // so only the last stage is checked.
    CirclePackingMetric stage_metric = metric;
    if (stage < stages) stage_metric.scheme = Scheme::inversive_distance;
    FlowResult result = flow(tables, stage_metric, target, stage_options);
    const int iterations = total.iterations + result.iterations;
    const int factorizations = total.factorizations + result.factorizations;
    LinearWork work = total.linear_work;
    work += result.linear_work;
    FlowTimings timings = total.timings;
    add_timings(timings, result.timings);
    std::vector<BrokenTrial> broken = total.broken_faces;
    broken.insert(broken.end(), result.broken_faces.begin(), result.broken_faces.end());
    total = std::move(result);
    total.iterations = iterations;
    total.factorizations = factorizations;
    total.linear_work = work;
    total.timings = timings;
    total.broken_faces = std::move(broken);
    if (!total.converged()) {
      total.message = "continuation stage " + std::to_string(stage) + " of " + std::to_string(stages) + ": " +
                      total.message;
      return total;
    }
    metric.gamma = total.metric.gamma;
  }
  return total;
}

}  // namespace ricci
