#pragma once
// Choosing the extraordinary point: the vertex whose one-cone flat metric has the least area
// distortion (manifold-splines paper, section 4, step 1). The paper runs one Ricci flow per
// vertex. Here a linearised model ranks every vertex with one factorisation (the flat metric's
// log-scale is, to first order, u = L^+ (K_target - K), so a cone at p adds 2*pi*chi times the
// Green's function of p), and only the best few candidates and the neighbours of the winner are
// checked with real flows.
#include <vector>

#include "ricci/flow/flow.h"
#include "ricci/mesh/mesh.h"
#include "ricci/singularity/one_cone.h"

namespace ricci {

struct SingularityOptions {
  /// Candidates from the linear ranking checked with a full flow: at least this many, more on
  /// small meshes (min(V / 20, 4e4 / V)), where flows are cheap and the linear model's
  /// ranking is noisiest.
  int verified_candidates = 8;
  /// Then greedy descent over one-rings (each step checks a vertex's neighbours and moves to
  /// the best) from the `descent_starts` best verified vertices.
  bool refine_in_one_ring = true;
  int descent_starts = 3;
  /// Above this many vertices, the linear model ranks a seeded random sample of this size.
  int max_ranked_vertices = 5000;
  /// Flow settings for the verifying flows (tolerance 1e-9 is plenty to compare distortions).
  FlowOptions flow = [] {
    FlowOptions o = one_cone_flow_options();
    o.tolerance = 1e-9;
    return o;
  }();
  ValenceOptions valence;
  /// Force flow.scheme / flow.radii instead of one_cone_metric_order.
  bool keep_metric = false;
};

struct SingularityScore {
  int vertex = -1;
  double area_distortion = 0.0;  ///< +inf when the flow did not converge
};

struct SingularityChoice {
  int vertex = -1;                ///< -1 when the topology needs no singular vertex
  double area_distortion = 0.0;   ///< of the chosen vertex's flat metric
  std::vector<SingularityScore> verified;  ///< every vertex checked with a full flow
  int flows_run = 0;
  double seconds = 0.0;
};

/// Area distortion of the one-cone flat metric around `vertex` (one full flow); +inf when the
/// flow does not converge. The measure leaves out no face (the paper's definition).
[[nodiscard]] double one_cone_area_distortion(const Mesh& mesh, int vertex,
                                              const SingularityOptions& options = {});

/// Candidates verified with a flow for a mesh of this many vertices.
[[nodiscard]] int verified_count(int vertices, const SingularityOptions& options);

/// Predicted area distortion of every vertex (or a sample) by the linearised model.
[[nodiscard]] std::vector<SingularityScore> rank_singularities(const Mesh& mesh,
                                                               const SingularityOptions& options = {});

/// The chosen vertex. \pre a connected closed or open 2-manifold. \throw as flow().
[[nodiscard]] SingularityChoice choose_singularity(const Mesh& mesh, const SingularityOptions& options = {});

}  // namespace ricci
