#pragma once
// The flow as `msp flow` and the Python `flow` run it: the fixed-connectivity flow (flow.h)
// and, when it fails on a closed surface in E2, the conformal flow with intrinsic Delaunay
// flips (conformal_flow.h), which has a solution for every target meeting Gauss-Bonnet.
//
//   ricci::RoutedFlowOptions o;
//   o.flow.fall_back_to_other_metrics = true;
//   ricci::RoutedFlowResult r = ricci::routed_flow(mesh, ricci::uniform_target(mesh, g), o);
//   if (r.flow.converged()) report(r.metric, r.flips());
#include <optional>
#include <string>

#include "ricci/flow/flow.h"
#include "ricci/flow/targets.h"
#include "ricci/intrinsic/conformal_flow.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

/// Which flows may compute a metric (routed_flow here; the one-cone atlas,
/// pipeline/one_cone_atlas.h, also takes the intrinsic flow directly from a genus on).
enum class FlowRoute {
  /// The fixed-connectivity flows (flow.h); where they do not converge, the intrinsic
  /// Delaunay flow (closed surfaces in E2).
  automatic,
  fixed_connectivity,  ///< flow.h's circle-packing family only
  intrinsic_delaunay   ///< intrinsic/conformal_flow.h only (closed surfaces, E2)
};

/// "automatic", "fixed-connectivity", "intrinsic-delaunay".
[[nodiscard]] std::string to_string(FlowRoute route);

struct RoutedFlowOptions {
  FlowRoute route = FlowRoute::automatic;
  /// ricci::flow's options; their tolerance, solver and progress also drive the intrinsic flow.
  FlowOptions flow;
  /// Newton iterations allowed to the intrinsic flow.
  int intrinsic_max_iterations = 400;
};

struct RoutedFlowResult {
  /// The delivered flow's figures; failed_attempts lists every run that failed before it. For
  /// the intrinsic flow, metric and lengths stay empty (they belong to `intrinsic`).
  FlowResult flow;
  /// "intrinsic-delaunay" when the intrinsic flow ran, otherwise flow.metric's scheme.
  std::string metric;
  std::optional<IntrinsicFlowResult> intrinsic;  ///< when the intrinsic flow ran

  /// Ptolemy flips of the intrinsic flow (0 when it did not run).
  [[nodiscard]] int flips() const { return intrinsic ? intrinsic->flips : 0; }
};

/// Runs the flows `options.route` allows, in the order above.
/// \throw InvalidInputError for FlowRoute::intrinsic_delaunay outside E2 or on a surface with
///        boundary; otherwise as ricci::flow and intrinsic_conformal_flow. Failure to converge
///        is flow.status, not an exception.
[[nodiscard]] RoutedFlowResult routed_flow(const Mesh& mesh, const Targets& targets,
                                           const RoutedFlowOptions& options = {});

}  // namespace ricci
