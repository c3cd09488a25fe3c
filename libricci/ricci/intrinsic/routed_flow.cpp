#include "ricci/intrinsic/routed_flow.h"

#include <utility>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"

namespace ricci {

std::string to_string(FlowRoute route) {
  switch (route) {
    case FlowRoute::fixed_connectivity:
      return "fixed-connectivity";
    case FlowRoute::intrinsic_delaunay:
      return "intrinsic-delaunay";
    default: return "automatic";
  }
}

RoutedFlowResult routed_flow(const Mesh& mesh, const Targets& targets,
                             const RoutedFlowOptions& options) {
  // Only an O(edges) walk of the boundary, and only when a route needs to know.
  const auto closed_e2 = [&] {
    return options.flow.geometry == Geometry::euclidean &&
           surface_topology(mesh).boundary_loops == 0;
  };
  if (options.route == FlowRoute::intrinsic_delaunay && !closed_e2()) {
    throw InvalidInputError(
        "the intrinsic-delaunay metric needs a closed surface and the euclidean geometry");
  }
  RoutedFlowResult out;
  if (options.route != FlowRoute::intrinsic_delaunay) {
    out.flow = flow(mesh, targets, options.flow);
    out.metric = to_string(out.flow.metric.scheme);
    if (out.flow.converged() || options.route != FlowRoute::automatic ||
        !options.flow.fall_back_to_other_metrics || !closed_e2())
      return out;
  }
  IntrinsicFlowOptions settings;
  settings.tolerance = options.flow.tolerance;
  settings.solver = options.flow.solver;
  settings.progress = options.flow.progress;
  settings.max_iterations = options.intrinsic_max_iterations;
  std::vector<std::string> failures = std::move(out.flow.failed_attempts);
  if (!out.metric.empty()) failures.push_back(out.flow.message);
  out.intrinsic = intrinsic_conformal_flow(mesh, targets, settings);
  out.flow = to_flow_result(*out.intrinsic);
  out.flow.failed_attempts = std::move(failures);
  out.metric = "intrinsic-delaunay";
  return out;
}

}  // namespace ricci
