#pragma once
// Ricci flow by continuation on the target curvature: instead of asking Newton for a large cone
// in one go, walk the target from the initial metric's own curvature K0 to K̄ in stages,
// K(s) = (1 - s) K0 + s K̄, each stage's Newton starting from the last one's radii. Every stage
// is a small change, so its first Newton steps stay inside the admissible radii (at a 6pi or
// 10pi cone the first full step from the mesh's radii changes u by tens at the cone and breaks
// triangles elsewhere); the end point is the same flow's solution (the energy is convex).
#include "ricci/flow/flow.h"

namespace ricci {

struct ContinuationOptions {
  /// Targets on the way to K̄: s = 1/stages, 2/stages, ..., 1.
  int stages = 4;
  /// max |K - K(s)| at which an intermediate stage counts as reached (the last one uses the
  /// flow options' tolerance).
  double stage_tolerance = 1e-3;
};

/// \pre as flow(tables, initial, targets, options); the initial metric must be valid.
/// \throw as flow(); InvalidInputError when the initial metric breaks a triangle.
/// The result is the last stage's (or the first stage that failed, with its status), with
/// iterations, factorisations, error history (the last stage's targets) and timings summed over
/// the stages.
[[nodiscard]] FlowResult flow_by_continuation(const MeshTables& tables, const CirclePackingMetric& initial,
                                              const Targets& targets, const FlowOptions& options = {},
                                              const ContinuationOptions& continuation = {});

}  // namespace ricci
