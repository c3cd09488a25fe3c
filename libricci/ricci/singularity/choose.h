#pragma once
// Choosing the extraordinary point: the vertex whose one-cone flat metric has the least area
// distortion (manifold-splines paper, section 4, step 1). The paper runs one Ricci flow per
// vertex. Here a linearised model ranks vertices with one factorisation of the cotangent
// Laplacian (the flat metric's log-scale is, to first order, u = L^+ (K_target - K), so a cone
// at p adds 2*pi*chi times the Green's function of p): a spread sample of vertices, then a
// zoom search of shrinking ring radius around the best few, every candidate costing one
// back-substitution (done in blocks). Real flows check the best candidates only within a work
// budget that falls as 1 / V^2: on small meshes (where flows are cheap and the linear model's
// ranking is noisiest) they verify the top candidates and descend over one-rings; from a few
// tens of thousands of vertices the choice is the linear model's and costs about one
// factorisation and a few solves.
#include <functional>
#include <vector>

#include "ricci/flow/flow.h"
#include "ricci/mesh/mesh.h"
#include "ricci/singularity/one_cone.h"

namespace ricci {

struct SingularityOptions {
  /// Vertices the linear model scores in its first, spread sample: all of them up to this many
  /// vertex-solves (about ranking_work / V vertices, at least min_ranked_vertices and at most
  /// max_ranked_vertices; a farthest-point sample by ring distance when not all).
  double ranking_work = 1.5e6;
  int min_ranked_vertices = 32;
  int max_ranked_vertices = 5000;
  /// Zoom search on the linear model from the best few sampled vertices (at most this many,
  /// fewer on large meshes: about ranking_work / (32 V)): a spread sample of the vertices
  /// within the sample spacing is scored, the centre moves to the best, the radius shrinks
  /// threefold, down to two rings.
  int linear_search_starts = 3;
  /// Vertices each zoom level scores: 0.4 times the first sample's size (about
  /// 0.4 ranking_work / V), at least min_zoom_samples and at most max_zoom_samples (24 below
  /// 25k vertices, 12 from 50k, where each costs a column of a blocked solve and its score).
  int min_zoom_samples = 12;
  int max_zoom_samples = 24;
  /// Real flows allowed: floor(verification_work / V^2), at most max_verified_flows (about 30
  /// at 5k vertices, 7 at 10k, none above 27.4k).
  double verification_work = 7.5e8;
  int max_verified_flows = 400;
  /// The best linear candidates verified with a flow first (within the budget)...
  int verified_candidates = 8;
  /// ...on this many threads, each flow on a problem of its own (0: the hardware's
  /// concurrency; the same choice, scores and work on any number).
  int verification_threads = 0;
  /// ...then greedy descent over one-rings with flows (each step checks a vertex's neighbours
  /// and moves to the best) from the `descent_starts` best verified vertices, while the budget
  /// lasts.
  bool refine_in_one_ring = true;
  int descent_starts = 3;
  /// Flow settings for the verifying flows (tolerance 1e-8 is plenty to compare distortions).
  FlowOptions flow = [] {
    FlowOptions o = one_cone_flow_options();
    o.tolerance = 1e-8;
    return o;
  }();
  ValenceOptions valence;
  /// Force flow.scheme / flow.radii instead of one_cone_metric_order.
  bool keep_metric = false;
  /// Also return the linear model's log scale factors for the chosen vertex
  /// (SingularityChoice::predicted_log_scale; one more back-substitution).
  bool predict_log_scale = false;
  /// Optional work of the caller's that needs no cone (e.g. the next stage's analysis of the
  /// mesh), run once on a second thread while the linear model's Laplacian is factorised, where
  /// that core would idle; the choice waits for it, and rethrows what it throws. It may read
  /// the mesh, not change it.
  std::function<void()> beside_factorization;
};

struct SingularityScore {
  int vertex = -1;
  double area_distortion = 0.0;  ///< +inf when the flow did not converge
};

struct SingularityChoice {
  int vertex = -1;  ///< -1 when the topology needs no singular vertex
  /// Of the chosen vertex's flat metric, measured by its flow; NaN when no flow verified it
  /// (large meshes: the linear model's choice, see predicted_area_distortion).
  double area_distortion = 0.0;
  /// The linear model's prediction for the chosen vertex (0 when no vertex is needed).
  double predicted_area_distortion = 0.0;
  /// With SingularityOptions::predict_log_scale: the linear model's flat metric for the chosen
  /// vertex, u = L^+ (K_target - K) by input vertex (zero mean; clamped cotangent weights), a
  /// warm start for the flow (intrinsic_conformal_flow's warm_u). Empty otherwise.
  Eigen::VectorXd predicted_log_scale;
  std::vector<SingularityScore> verified;  ///< every vertex checked with a full flow
  int flows_run = 0;
  int ranked = 0;         ///< vertices the linear model scored
  int linear_solves = 0;  ///< right-hand sides solved with the Laplacian's factorisation
  /// The linear model's factorisation and (blocked) back-substitutions, with the verifying
  /// flows' own.
  LinearWork linear_work;
  double seconds = 0.0;
};

/// Area distortion of the one-cone flat metric around `vertex` (one full flow); +inf when the
/// flow does not converge. The measure leaves out no face (the paper's definition).
[[nodiscard]] double one_cone_area_distortion(const Mesh& mesh, int vertex,
                                              const SingularityOptions& options = {});

/// Vertices each level of the linear zoom search scores on a mesh of this many vertices.
[[nodiscard]] int zoom_sample_count(int vertices, const SingularityOptions& options);

/// Real flows the choice may run on a mesh of this many vertices.
[[nodiscard]] int verified_count(int vertices, const SingularityOptions& options);

/// Predicted area distortion of the first, spread sample of vertices (every interior vertex
/// up to options' ranking budget), by the linearised model, best first; its factorisation and
/// back-substitutions are added to `work` when given.
/// \throw SolverError when the Laplacian cannot be factorised.
[[nodiscard]] std::vector<SingularityScore> rank_singularities(
    const Mesh& mesh, const SingularityOptions& options = {}, LinearWork* work = nullptr);

/// The chosen vertex. \pre a connected closed or open 2-manifold.
/// \throw SolverError when no verified candidate converges; as flow().
[[nodiscard]] SingularityChoice choose_singularity(const Mesh& mesh,
                                                   const SingularityOptions& options = {});

}  // namespace ricci
