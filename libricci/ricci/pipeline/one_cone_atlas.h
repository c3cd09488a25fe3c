#pragma once
// The whole of libricci's one-extraordinary-point pipeline in one call: singularity choice,
// valence modification, Ricci flow to the one-cone flat metric, cut graph, layout and affine
// atlas, with the distortion report (manifold-splines paper, section 4).
#include <functional>
#include <string>

#include "ricci/atlas/atlas.h"
#include "ricci/flow/flow.h"
#include "ricci/intrinsic/conformal_flow.h"
#include "ricci/intrinsic/routed_flow.h"
#include "ricci/mesh/collapse_short_edges.h"
#include "ricci/mesh/flat_flips.h"
#include "ricci/mesh/mesh.h"
#include "ricci/mesh/simplify.h"
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
  /// Which flow runs (see FlowRoute); `intrinsic` holds the intrinsic flow's settings (its
  /// tolerance, solver and progress are taken from `flow`).
  FlowRoute route = FlowRoute::automatic;
  IntrinsicFlowOptions intrinsic;
  /// automatic: closed surfaces of this genus or more take the intrinsic flow directly (the
  /// fixed-connectivity flows break triangles under cones of -12 pi and beyond).
  int intrinsic_from_genus = 4;
  /// From this many faces the intrinsic flow hands a metric below its floor_below (1e-8) to
  /// the long-double polish at once (IntrinsicFlowOptions::floor_plateau_iterations 0): there
  /// the double evaluation's floor (~1e-10 at 1.6M faces) meets the tolerance, and the Newton
  /// steps spent on it gain nothing the polish does not do (docs/design-notes.md, "Memory at
  /// 1.6M faces by stage"). Smaller meshes keep the flow's own plateau rule.
  int polish_floor_from_faces = 400000;
  /// Below this many faces the intrinsic flow's mesh is built from its triangulation on a
  /// second thread while the long-double polish runs (it needs the connectivity only); from
  /// here on it is built after the polish, once the flow's factorisation is freed (peak memory).
  int mesh_beside_polish_below_faces = 400000;
  /// With that mesh, also the atlas' cut graph and slicing beside the polish: the cut graph's
  /// shortest paths then follow the unpolished lengths (within ~1e-12 of the polished ones;
  /// only exact ties could cut differently); the atlas measures its loops with the polished.
  bool cut_beside_polish = true;
  /// Collapse of edges much shorter than the median (mesh/collapse_short_edges.h) before
  /// anything else; the singular vertex is kept. The problem's `input_vertex` maps back.
  bool collapse_short_edges = false;
  ShortEdgeOptions short_edges;
  /// Delaunay flips of the edges between coplanar faces (mesh/flat_flips.h) before the valence
  /// modification: the surface stays, its caps and slivers go.
  bool flip_flat_edges = false;
  FlatFlipOptions flat_flips;
  /// Single cones: metrics tried in turn (solve_cone_ring_flow) before solve_one_cone_flow's.
  std::vector<ConeRingMetric> cone_ring_metrics;
  /// Continuation stages for the cone-ring metrics' flows (1 = the plain flow).
  ContinuationOptions continuation{1};
  ValenceOptions valence;
  /// Denser sampling around a single cone, after the valence modification (refine_around_cone;
  /// off here, on in the scan pipeline, spline/fit/fit.h).
  ConeRefinementOptions cone_refinement;
  SingularityOptions choice;
  AtlasOptions atlas;
  /// The long-double polish (metric/polish_e2.h) runs only when the flow's max |K - K̄|,
  /// evaluated in double, is at least this (radians). 0 always polishes; infinity never does.
  double polish_threshold = 8e-13;
  /// On a closed surface of genus >= 2 (and no cone_ring_metrics given), by default or with
  /// keep_metric and the inversive-distance scheme, first try inversive_distance_route(*this):
  /// the most conformal metric (area-weighted QC ~1.03 on genus2_100k against ~1.7 for the
  /// circle packing), which converges where the plain inversive-distance flow breaks triangles.
  /// If it fails, solve_one_cone_flow's metric order by default, the plain flow as asked with
  /// keep_metric; the route's failures are listed first in flow.failed_attempts and
  /// flow.metric_name names the winner.
  bool inversive_distance_route = true;
  /// With route automatic and no metric asked for (keep_metric false), on a closed surface of
  /// genus >= 2: the intrinsic Delaunay flow (vertex scaling with flips, the discrete conformal
  /// metric, which exists for any cone) runs first; the inversive-distance route and the
  /// circle packings run only if it fails. It is at least as conformal as the route on the
  /// bench and shared genus 2-3 meshes (docs/design-notes.md, "Default metric order") and
  /// costs one flow where the route fails at 10 pi cones. The atlas is then on the flipped
  /// triangulation (OneConeAtlasResult::intrinsic).
  bool intrinsic_first = true;
  /// With route automatic, when the inversive-distance route fails: the intrinsic Delaunay flow
  /// (vertex scaling, the discrete conformal metric: QC near 1) is tried before the circle
  /// packings of solve_one_cone_flow (area-weighted QC ~1.7 under the 10 pi cone of genus 3),
  /// which run only if it fails too. The atlas is then on the flipped triangulation
  /// (OneConeAtlasResult::intrinsic).
  bool intrinsic_before_fixed = true;
  /// With route automatic and no metric asked for: when the fixed-connectivity flows converge
  /// only on the combinatorial metric (tangent circles, last of one_cone_metric_order, which
  /// ignore the mesh's shape), the intrinsic Delaunay flow runs (if not tried yet) and is taken
  /// when it converges; the tangent circles are then listed in flow.failed_attempts as set
  /// aside (docs/design-notes.md, "Tangent circles after the intrinsic flow"). Closed surfaces
  /// of genus >= 1 only (where the intrinsic flow applies).
  bool intrinsic_before_combinatorial = true;
  /// When the intrinsic flow makes the metric: keep the mesh it started from and its flips
  /// (OneConeAtlasResult::flip_record), so that points of the surface can be placed exactly on
  /// the flipped triangulation (place_on_problem_mesh). Costs a copy of the problem's mesh.
  bool keep_flip_record = false;
  /// When the singularity is chosen automatically and the intrinsic flow runs first: Newton
  /// starts at warm_start_fraction times the choice's linear prediction of the flat metric
  /// (its log scale factors, SingularityChoice::predicted_log_scale, carried to the problem's
  /// vertices) instead of u = 0, with u = 0 as the fallback (intrinsic_conformal_flow's warm
  /// start). The whole prediction overshoots next to the cone, where the linear model's cone
  /// has the input's valence (docs/design-notes.md, "Warm start from the choice").
  /// Below warm_start_below_faces faces only: at 1.6M faces the first cold step already lands
  /// where the warm start does, and the warm start costs a factorisation.
  bool warm_start = true;
  double warm_start_fraction = 0.5;
  int warm_start_below_faces = 400000;
  /// Optional progress: called with a stage name when that stage starts.
  std::function<void(const std::string& stage)> progress;
};

/// Seconds of each stage: wall clock, and the process' CPU time (all threads) beside it. The
/// distortion is measured on a thread of its own while the atlas is built: `distortion` is its
/// own wall time, within `atlas`' span, whose CPU time (cpu_atlas) covers both (cpu_distortion
/// stays 0).
struct OneConeAtlasTimings {
  double choice = 0, flips = 0, valence = 0, flow = 0, polish = 0, atlas = 0, distortion = 0, total = 0;
  double cpu_choice = 0, cpu_valence = 0, cpu_flow = 0, cpu_polish = 0, cpu_atlas = 0,
         cpu_distortion = 0, cpu_total = 0;
};

/// Linear-system work of each stage (flow/linear_solver.h: numeric factorisations and passes
/// over a factor, a blocked back-substitution counting once), thrown-away attempts included.
/// The clean-up, valence, atlas and distortion stages solve no linear system.
struct OneConeAtlasLinearWork {
  LinearWork choice, flow, polish;
  [[nodiscard]] LinearWork total() const {
    LinearWork sum = choice;
    sum += flow;
    sum += polish;
    return sum;
  }
};

/// What the intrinsic flow did to the problem's mesh (OneConeAtlasOptions::keep_flip_record):
/// the mesh before its flips and the flips in order. Empty when the option is off or the
/// intrinsic flow did not make the metric.
struct IntrinsicFlipRecord {
  /// problem.mesh as the flow started on it: the same vertices (indices and positions), the
  /// faces before the flips, which lie on the surface (the flipped ones are chords).
  Mesh initial;
  /// The flow's starting triangulation (make_intrinsic_triangulation of `initial`; its face f
  /// is initial's face f), whose edge numbering flip_log uses.
  IntrinsicTriangulation triangulation;
  std::vector<int> flip_log;  ///< IntrinsicFlowResult::flip_log, in order
  Eigen::VectorXd u;          ///< the flow's log scale factors by vertex
  [[nodiscard]] bool empty() const { return initial.n_faces() == 0; }
};

struct OneConeAtlasResult {
  OneConeProblem problem;  ///< The (flipped, valence-modified or punctured) mesh and its targets.
  FlatFlipResult flat_flips;  ///< What flip_flat_edges did (zeros when off).
  /// What collapse_short_edges did (its mesh left empty; empty map when off).
  ShortEdgeCollapse short_edges;
  /// The flow's result; its `lengths` are replaced by the polished ones (below).
  FlowResult flow;
  /// Whether the intrinsic Delaunay flow made the metric: problem.mesh is then its flipped
  /// triangulation (the same vertices with the same indices, positions and input_vertex map;
  /// other faces and edges) and flow.lengths its lengths; flow.metric is empty.
  bool intrinsic = false;
  int intrinsic_flips = 0;  ///< Ptolemy flips the intrinsic flow made (0 when it did not run)
  int intrinsic_trials = 0;  ///< its line-search evaluations (IntrinsicFlowResult's)
  /// How the intrinsic flow started (WarmStart::none without the choice's prediction).
  WarmStart warm_start = WarmStart::none;
  /// The choice's linear prediction of the flat metric by input vertex (options.warm_start;
  /// empty when not computed).
  Eigen::VectorXd predicted_log_scale;
  /// Edges of the mesh the intrinsic flow's final triangulation does not have
  /// (intrinsic/flip_free.h; 0: the mesh is its own Delaunay triangulation for the metric; -1:
  /// the intrinsic flow did not run or did not get near the target).
  int removed_edges = -1;
  /// (With `intrinsic`, `distortion` compares the metric with the flipped faces' 3D triangles
  /// (chords of the surface), leaving out and counting those that are degenerate.)
  /// Long-double polish of the flow's lengths before the layout (error_before/after: max
  /// |K - K̄| evaluated in long double). When skipped (polish_threshold), error_before and
  /// error_after hold the flow's double-precision defect and iterations is 0.
  PolishE2Result polish;
  bool polished = false;  ///< Whether the polish ran.
  AffineAtlas atlas;
  DistortionReport distortion;
  int chosen_vertex = -1;       ///< Input vertex of the singularity, -1 when none.
  int flows_for_choice = 0;     ///< Flows the automatic choice ran (0 when given).
  int solves_for_choice = 0;    ///< Its linear model's back-substitutions (0 when given).
  ConeRefinement cone_refinement;  ///< What options.cone_refinement did.
  OneConeAtlasTimings timings;
  OneConeAtlasLinearWork linear_work;
  IntrinsicFlipRecord flip_record;  ///< (OneConeAtlasOptions::keep_flip_record)
  /// max transition (and side pairing) residual divided by the domain diameter.
  [[nodiscard]] double relative_transition_residual() const;
};

/// The mesh whose faces lie on the surface and carry the problem's points: flip_record.initial
/// when the record was kept, problem.mesh otherwise. Place points of the input there (e.g. by
/// closest_points), then carry them to the atlas' mesh with place_on_problem_mesh.
[[nodiscard]] const Mesh& placement_mesh(const OneConeAtlasResult& result);

/// Points of placement_mesh(result) (SurfacePoint: face and barycentric coordinates in the
/// face's fv_range order) as points of result.problem.mesh, whose faces the atlas lays out:
/// through the intrinsic flow's flips by IntrinsicCorrespondence (exact, point_tracking.h),
/// with barycentric coordinates in the flat metric's triangle (the layout's). `point` and
/// `distance` are kept. Unchanged without a flip record.
/// \throw InvalidInputError for a face out of range; TopologyError when the record's flips do
///        not give problem.mesh's faces.
[[nodiscard]] std::vector<SurfacePoint> place_on_problem_mesh(const OneConeAtlasResult& result,
                                                              std::vector<SurfacePoint> points);

/// `options` set up for the inversive-distance flow on marching-cubes meshes: edges under 1% of
/// the median collapsed, non-Delaunay edges flipped where their faces are within 5 degrees of
/// coplanar or their diagonals within 1% of the median edge apart (not at the cone), inversive
/// distances made >= 0 with Thurston's angles within 4 rings of the cone, the cone reached in 4
/// stages. The surface moves by at most ~2% of a local edge (5-degree flips) or 1% of the median
/// edge (collapses, thin flips).
[[nodiscard]] OneConeAtlasOptions inversive_distance_route(const OneConeAtlasOptions& options);

/// Whether build_one_cone_atlas runs the intrinsic Delaunay flow first (see intrinsic_first).
[[nodiscard]] bool takes_intrinsic_flow_first(const Mesh& mesh, const OneConeAtlasOptions& options);

/// Whether build_one_cone_atlas tries inversive_distance_route (see the option; after the
/// intrinsic flow when takes_intrinsic_flow_first).
[[nodiscard]] bool takes_inversive_distance_route(const Mesh& mesh, const OneConeAtlasOptions& options);

/// The settings build_one_cone_atlas chooses the automatic singularity of `mesh` with:
/// options.choice with the atlas's flow (its tolerance no tighter than the choice's), valence
/// and metric (default metrics when the inversive-distance route would replace the asked one).
[[nodiscard]] SingularityOptions singularity_options(const Mesh& mesh,
                                                     const OneConeAtlasOptions& options);

/// The one-cone atlas of `mesh`, which stays the caller's: it is held beside the flow's
/// factorisation all along (about 80 bytes per face). To spare that memory, pass the mesh by
/// rvalue (below).
/// \pre a connected, oriented 2-manifold triangle mesh.
/// \throw InvalidInputError / TopologyError for bad input; InfeasibleTargetError for a target
///        the theory forbids; SolverError when the flow does not converge (its message names the
///        worst vertices and what to try).
[[nodiscard]] OneConeAtlasResult build_one_cone_atlas(const Mesh& mesh, const OneConeAtlasOptions& options = {});

/// The same atlas, on a mesh handed over to the pipeline (`std::move(mesh)`: it is used in
/// place, not copied): once the problem's mesh is made from it (valence modification) the
/// input waits as (V, F) arrays (about a third of the mesh's memory) while the flow runs, and is
/// rebuilt in the same vertex and face order only if a fallback route needs it. The result is
/// the const-reference call's whenever that rebuild gives back the same mesh, as for a mesh
/// read by read_mesh or built face by face without deletions. `mesh` is left empty, also
/// when it throws. \pre and \throw as above.
[[nodiscard]] OneConeAtlasResult build_one_cone_atlas(Mesh&& mesh, const OneConeAtlasOptions& options = {});

}  // namespace ricci
