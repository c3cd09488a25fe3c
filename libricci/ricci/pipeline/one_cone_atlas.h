#pragma once
// The whole of libricci's one-extraordinary-point pipeline in one call: singularity choice,
// valence modification, Ricci flow to the one-cone flat metric, cut graph, layout and affine
// atlas, with the distortion report (manifold-splines paper, section 4).
#include <functional>
#include <string>

#include "ricci/atlas/atlas.h"
#include "ricci/flow/flow.h"
#include "ricci/mesh/mesh.h"
#include "ricci/metric/polish_e2.h"
#include "ricci/quality/distortion.h"
#include "ricci/singularity/choose.h"
#include "ricci/singularity/one_cone.h"

namespace ricci {

struct OneConeAtlasOptions {
  /// Input vertex index of the singularity, or -1 to choose it (least area distortion).
  int singular_vertex = -1;
  /// Flow settings (tolerance, solver, ...). The metric is chosen per problem
  /// (one_cone_metric_order) unless `keep_metric`, which forces flow.scheme and flow.radii.
  FlowOptions flow = one_cone_flow_options();
  bool keep_metric = false;
  ValenceOptions valence;
  SingularityOptions choice;
  AtlasOptions atlas;
  /// The long-double polish (metric/polish_e2.h) runs only when the flow's max |K - K̄|,
  /// evaluated in double, is at least this: below it the defect is already at the rounding of
  /// a double angle sum (valence x 1e-16 x 2pi) and the polish (0.3-1 s at 100k faces) gains
  /// nothing the layout can see. 0 always polishes; infinity never does.
  double polish_threshold = 1e-13;
  /// Optional progress: called with a stage name when that stage starts.
  std::function<void(const std::string& stage)> progress;
};

/// Wall-clock seconds of each stage.
struct OneConeAtlasTimings {
  double choice = 0, valence = 0, flow = 0, polish = 0, atlas = 0, distortion = 0, total = 0;
};

struct OneConeAtlasResult {
  OneConeProblem problem;  ///< The (valence-modified or punctured) mesh and its targets.
  /// The flow's result; its `lengths` are replaced by the polished ones (below).
  FlowResult flow;
  /// Long-double polish of the flow's lengths before the layout (error_before/after: max
  /// |K - K̄| evaluated in long double). When skipped (polish_threshold), error_before and
  /// error_after hold the flow's double-precision defect and iterations is 0.
  PolishE2Result polish;
  bool polished = false;  ///< Whether the polish ran.
  AffineAtlas atlas;
  DistortionReport distortion;
  int chosen_vertex = -1;       ///< Input vertex of the singularity, -1 when none.
  int flows_for_choice = 0;     ///< Flows the automatic choice ran (0 when given).
  OneConeAtlasTimings timings;
  /// max transition (and side pairing) residual divided by the domain diameter.
  [[nodiscard]] double relative_transition_residual() const;
};

/// \pre a connected, oriented 2-manifold triangle mesh.
/// \throw InvalidInputError / TopologyError for bad input; SolverError when the flow does not
///        converge (its message names the worst vertices and what to try).
[[nodiscard]] OneConeAtlasResult build_one_cone_atlas(const Mesh& mesh, const OneConeAtlasOptions& options = {});

}  // namespace ricci
